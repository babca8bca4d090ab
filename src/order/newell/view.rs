//! The view in f64, as Newell's tests and the screen boxes see it: clip
//! coordinates, screen positions and the eye's side of a plane.

use crate::camera::Camera;
use crate::mesh::Viewpoint;
use crate::order::plane::{exact_side, Plane, Side};
use crate::vector::dot;

/// The view, in f64.
pub(super) struct View {
    /// Rows of the affine map to clip coordinates, applied to `p - eye`.
    rows: [[f64; 3]; 3],
    eye: [f64; 3],
    perspective: bool,
    pub(super) viewpoint: Viewpoint,
}

impl View {
    pub(super) fn new(camera: &Camera) -> Self {
        Self {
            rows: camera.clip_rows(1.0).map(|r| r.map(f64::from)),
            eye: camera.eye().map(f64::from),
            perspective: camera.is_perspective(),
            viewpoint: camera.viewpoint(),
        }
    }

    /// `(x, y, depth)`: clip x and y, and the distance in front of the eye.
    pub(super) fn clip(&self, p: [f32; 3]) -> [f64; 3] {
        let p = p.map(f64::from);
        let d = [p[0] - self.eye[0], p[1] - self.eye[1], p[2] - self.eye[2]];
        self.rows.map(|r| dot(r, d))
    }

    /// Screen position (normalised device units, y up), `None` at or behind the
    /// eye under perspective.
    pub(super) fn screen(&self, p: [f32; 3]) -> Option<[f64; 2]> {
        let [x, y, w] = self.clip(p);
        if !self.perspective {
            Some([x, y])
        } else if w > 0.0 {
            Some([x / w, y / w])
        } else {
            None
        }
    }

    /// The eye's side of `plane`: `On` when it is on the plane (within the
    /// tolerance), so that the plane's polygons are seen edge-on.
    pub(super) fn eye_side(&self, plane: &Plane) -> Side {
        match self.viewpoint {
            Viewpoint::Perspective { eye } => plane.side_of(plane.distance(eye), eye),
            Viewpoint::Orthographic { direction_to_eye } => {
                exact_side(dot(plane.n, direction_to_eye.map(f64::from)))
            }
        }
    }
}
