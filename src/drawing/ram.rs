//! The RAM of the short API's buffers, as `const fn`s of their sizes: the bytes of
//! a [`Drawing`], a [`BakedDrawing`] and a [`FrameRows`] for sizes known at run
//! time (from [`DrawingNeeds`], say), computed from `size_of` of the types they
//! hold, so that they follow the types. Each equals `size_of` of the type with
//! those parameters (a test holds them to it), which the types' `RAM_BYTES` give
//! at compile time.

use core::mem::{align_of, size_of};

use super::{Baked, BakedDrawing, Drawing, DrawingNeeds, FrameBuffers, FrameRows, CLIPPED_CORNERS};
use crate::bits::padded;
use crate::mesh::{HalfEdgeRecord, MeshEdge};
use crate::render::{
    fast_renderer_bytes, BakedMesh, CompactEdge, FacePlane, FastVertex, MonoPalette, Settings,
};

/// Bytes of the frame buffers a drawing holds (the engine and its tables).
const fn frame_bytes(v: usize, f: usize, e: usize, facets: usize, lines: usize) -> usize {
    let fields = v * size_of::<FastVertex>()
        + f * size_of::<u32>()
        + f * size_of::<[u16; 2]>()
        + e * size_of::<u16>()
        + CLIPPED_CORNERS * size_of::<FastVertex>()
        + fast_renderer_bytes(facets, lines);
    padded(fields, align_of::<FrameBuffers<0, 0, 0, 0, 0>>())
}

/// Bytes of a [`Drawing`]`<v, f, e, facets, lines>`: its frame buffers, the
/// baked planes and edges, and the baking scratch (48 bytes an edge and 4 a
/// vertex).
///
/// ```
/// use pbuffer::{ram, Drawing};
/// assert_eq!(ram::drawing_bytes(8, 6, 12, 32, 32), Drawing::<8, 6, 12>::RAM_BYTES);
/// ```
pub const fn drawing_bytes(v: usize, f: usize, e: usize, facets: usize, lines: usize) -> usize {
    let fields = size_of::<Option<Baked<'static>>>()
        + size_of::<Settings>()
        + size_of::<MonoPalette>()
        + f * size_of::<FacePlane>()
        + e * size_of::<CompactEdge>()
        + frame_bytes(v, f, e, facets, lines)
        + v * size_of::<u32>()
        + e * size_of::<[HalfEdgeRecord; 2]>()
        + e * size_of::<MeshEdge>();
    padded(fields, align_of::<Drawing<'static, 0, 0, 0, 0, 0>>())
}

/// Bytes of a [`BakedDrawing`]`<v, f, e, facets, lines>`: only the buffers of a
/// frame (the baked mesh stays in flash).
pub const fn baked_drawing_bytes(
    v: usize,
    f: usize,
    e: usize,
    facets: usize,
    lines: usize,
) -> usize {
    let fields = size_of::<Option<BakedMesh<'static>>>()
        + size_of::<Settings>()
        + size_of::<MonoPalette>()
        + frame_bytes(v, f, e, facets, lines);
    padded(fields, align_of::<BakedDrawing<'static, 0, 0, 0, 0, 0>>())
}

/// Bytes of a [`FrameRows`]`<w, h>`: a word a pixel of one row, and three words a
/// row (two list heads of 16 bits and a line-mask word).
pub const fn frame_rows_bytes(w: usize, h: usize) -> usize {
    let fields = w * size_of::<u32>() + h * size_of::<[u16; 2]>() + h * size_of::<u32>();
    padded(fields, align_of::<FrameRows<0, 0>>())
}

impl<
        'm,
        const V: usize,
        const F: usize,
        const E: usize,
        const FACETS: usize,
        const LINES: usize,
    > Drawing<'m, V, F, E, FACETS, LINES>
{
    /// The bytes of RAM this drawing takes: `size_of::<Self>()`, as
    /// [`drawing_bytes`] computes it for sizes known at run time.
    pub const RAM_BYTES: usize = size_of::<Self>();
}

impl<
        'm,
        const V: usize,
        const F: usize,
        const E: usize,
        const FACETS: usize,
        const LINES: usize,
    > BakedDrawing<'m, V, F, E, FACETS, LINES>
{
    /// The bytes of RAM this drawing takes: `size_of::<Self>()`, as
    /// [`baked_drawing_bytes`] computes it for sizes known at run time.
    pub const RAM_BYTES: usize = size_of::<Self>();
}

impl<const W: usize, const H: usize> FrameRows<W, H> {
    /// The bytes of RAM these rows take: `size_of::<Self>()`, as
    /// [`frame_rows_bytes`] computes it for sizes known at run time.
    pub const RAM_BYTES: usize = size_of::<Self>();
}

impl DrawingNeeds {
    /// The RAM of the [`Drawing`] these needs size ([`drawing_bytes`]).
    pub const fn drawing_bytes(&self) -> usize {
        drawing_bytes(
            self.vertices,
            self.faces,
            self.edges,
            self.facets,
            self.lines,
        )
    }

    /// The RAM of the [`BakedDrawing`] these needs size ([`baked_drawing_bytes`]).
    pub const fn baked_drawing_bytes(&self) -> usize {
        baked_drawing_bytes(
            self.vertices,
            self.faces,
            self.edges,
            self.facets,
            self.lines,
        )
    }

    /// The RAM of the [`FrameRows`] these needs size ([`frame_rows_bytes`]).
    pub const fn frame_rows_bytes(&self) -> usize {
        frame_rows_bytes(self.width, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `size_of` of the types against the functions, for odd and even sizes.
    macro_rules! same {
        ($($v:literal $f:literal $e:literal $fa:literal $l:literal),*) => {$(
            assert_eq!(
                drawing_bytes($v, $f, $e, $fa, $l),
                size_of::<Drawing<'static, $v, $f, $e, $fa, $l>>(),
                "Drawing<{}, {}, {}, {}, {}>", $v, $f, $e, $fa, $l
            );
            assert_eq!(
                baked_drawing_bytes($v, $f, $e, $fa, $l),
                size_of::<BakedDrawing<'static, $v, $f, $e, $fa, $l>>(),
                "BakedDrawing<{}, {}, {}, {}, {}>", $v, $f, $e, $fa, $l
            );
            assert_eq!(frame_rows_bytes($v, $f), size_of::<FrameRows<$v, $f>>());
        )*};
    }

    #[test]
    fn the_functions_are_the_sizes_of_the_types() {
        same!(0 0 0 0 0, 1 1 1 1 1, 8 6 12 32 32, 16 14 28 7 5, 3 5 7 9 11,
            2903 5804 8706 118 85, 255 127 63 31 15);
    }
}
