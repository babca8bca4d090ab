//! Where each face is seen from: the facing test and the shading ask it. One
//! mesh is seen from the camera's viewpoint; the instances of a scene each from
//! the camera's viewpoint brought into the instance's own space, so that their
//! baked planes serve as they are (`crate::scene`).

use super::{faces_view, FacePlane};
use crate::bits::bit;
use crate::mesh::Viewpoint;

/// Where each face is seen from.
pub(crate) trait FaceViews: Copy {
    /// Does face `f`, whose baked plane is `plane`, face the eye of `view` (the
    /// camera's)? `facing` holds the bits a scene set before the frame.
    fn facing(&self, f: usize, plane: &FacePlane, view: &Viewpoint, facing: &[u32]) -> bool;

    /// The viewpoint face `f`'s baked plane is seen from, `view` being the
    /// camera's (for its shade).
    fn view_of(&self, f: u16, view: &Viewpoint) -> Viewpoint;
}

/// One mesh, seen from the camera: the engine's own path, with nothing to look up.
#[derive(Clone, Copy)]
pub(crate) struct OneMesh;

impl FaceViews for OneMesh {
    #[inline(always)]
    fn facing(&self, _: usize, plane: &FacePlane, view: &Viewpoint, _: &[u32]) -> bool {
        faces_view(plane, view)
    }

    #[inline(always)]
    fn view_of(&self, _: u16, view: &Viewpoint) -> Viewpoint {
        *view
    }
}

/// The instances of a scene: instance `k`'s faces start at `starts[k]` (ascending)
/// and are seen from `views[k]`; their facing bits were set before the frame.
#[derive(Clone, Copy)]
pub(crate) struct InstanceViews<'a> {
    pub starts: &'a [u16],
    pub views: &'a [Viewpoint],
}

impl FaceViews for InstanceViews<'_> {
    #[inline(always)]
    fn facing(&self, f: usize, _: &FacePlane, _: &Viewpoint, facing: &[u32]) -> bool {
        bit(facing, f)
    }

    fn view_of(&self, f: u16, view: &Viewpoint) -> Viewpoint {
        let k = self.starts.partition_point(|&s| s <= f).saturating_sub(1);
        self.views.get(k).copied().unwrap_or(*view)
    }
}
