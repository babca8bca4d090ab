//! Model only what a scene needs: the smallest sub-pixel bits S, depth bits and
//! surface-code width that keep a frame's error under a stated bound.
//!
//! The formulas (the `report` command of the host crate checks them on every scene
//! it renders, and `host_tests/tests/tools/recommend.rs` asserts them):
//!
//! * **Sub-pixel bits.** A vertex is rounded to the nearest point of the `1/2^S`
//!   grid, so each coordinate moves by at most `2^-(S+1)` px and the vertex by at
//!   most `sqrt(2) 2^-(S+1)` px; an edge, a convex combination of its ends, moves
//!   no farther. Under that sits a floor that no S removes: world positions are
//!   fixed point with 26 bits for the largest coordinate (`max_coordinate`) and the
//!   camera is set up in `f32`; in pixels that is about
//!   `(max_coordinate / radius) 2^-26 max(width, height)`. S is the smallest value
//!   with `sqrt(2) 2^-(S+1) + floor <= edge_px`, at most
//!   [`MAX_SUBPIXEL_BITS`]. Overlapping coplanar faces
//!   (`coplanar_overlaps`) are ordered by face index through the depth test's tie
//!   margin, `1/16` of a face's nearness change per pixel: that survives snapping
//!   only when a plane moves by less than `1/16` px, so they need `S >= 4`.
//! * **Depth bits** (the Z-buffer engine only; the code-fill engine compares planes
//!   at full precision). Depth is nearness scaled to the distances the frame draws,
//!   `lo..hi` (the nearest and farthest drawn distance, within near..far; see
//!   `Stats::depth_step_near`): `q = lo (hi - d) / ((hi - lo) d)` (perspective) or
//!   `q = (hi - d) / (hi - lo)` (orthographic), stored in `B` bits: one step is
//!   `2^-(B-1)` (`q = 1` is `2^31`; a 16-bit sample keeps the top 16 bits). Two
//!   surfaces `g` apart differ in nearness by at least `lo g / ((hi - lo) hi)` (at
//!   the farthest drawn distance, the worst place) or `g / (hi - lo)`. They are
//!   ordered when that exceeds two steps (one for the truncation of each); for 32
//!   bits the step is taken as `2^-27`, covering the depth test's tie margin of 8
//!   units of `2^-31` and the projection's rounding. Overlapping coplanar faces need
//!   32 bits: they tie within the test's margin (8 units of `2^-31` plus `1/16` of a
//!   plane's change per pixel), which a 16-bit sample's truncation breaks.
//!   [`Recommendation::separable_gap_16`] and `_32` say how close two surfaces at the
//!   farthest drawn distance may be for each width to tell them apart.
//! * **Code width** (the code-fill engine): the surface code has one bit per face
//!   covering a pixel, plus one while a crossing hands a pixel from one face to its
//!   neighbour, so `ceil((max_layers + 1) / 32)` words. (Measured: the crossing
//!   rows needed exactly `max_layers` bits on every scene of the report. Bit-sliced
//!   rows, `RowCodes::BitSliced`, are not covered: they reported up to 76 bits on
//!   suzanne, whose depth complexity is 8.)
//!
//! ```
//! use pbuffer::recommend::{recommend, ErrorBound, SceneBounds};
//! use pbuffer::Viewport;
//!
//! let scene = SceneBounds::perspective(1.0, 1.0, 2.0, 5.0).with_min_depth_gap(0.001);
//! let r = recommend(&scene, Viewport { width: 128, height: 64 }, &ErrorBound::default());
//! assert_eq!(r.subpixel_bits, 2);
//! assert_eq!(r.depth_bits, 16);
//! assert!(r.meets_bound);
//! ```

use crate::{Viewport, MAX_SUBPIXEL_BITS};

/// What the recommendation needs to know of a scene and its camera (world units).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SceneBounds {
    /// The largest absolute coordinate of any vertex or of the eye: it sets the
    /// fixed-point position scale (26 bits for this value).
    pub max_coordinate: f32,
    /// Radius of the part of the scene the view frames (the bounding sphere the
    /// camera is fitted to): `radius` world units span about half the screen.
    pub radius: f32,
    /// The nearest and farthest distances the frame draws, `0 < near < far`: the
    /// camera's near and far at most, or tighter, the distances of the drawn
    /// geometry along the view clamped to them (depth is scaled to those).
    pub near: f32,
    /// See `near`.
    pub far: f32,
    /// Orthographic projection (nearness linear in distance) rather than perspective.
    pub orthographic: bool,
    /// The smallest distance along the view between two surfaces that must be drawn
    /// in the right order (the thinnest wall, the smallest step), world units.
    pub min_depth_gap: f32,
    /// The scene has overlapping coplanar faces, to be ordered by face index.
    pub coplanar_overlaps: bool,
    /// The most faces covering one pixel centre after culling (depth complexity);
    /// 1 for a convex closed mesh. At most the number of faces drawn.
    pub max_layers: u32,
}

impl SceneBounds {
    /// A perspective scene of bounding radius `radius` whose largest coordinate
    /// (vertices and eye) is `max_coordinate`, seen between `near` and `far`; the
    /// smallest depth gap defaults to `radius / 1000` and the layers to 8.
    pub fn perspective(max_coordinate: f32, radius: f32, near: f32, far: f32) -> Self {
        Self {
            max_coordinate,
            radius,
            near,
            far,
            orthographic: false,
            min_depth_gap: radius / 1000.0,
            coplanar_overlaps: false,
            max_layers: 8,
        }
    }

    /// The same scene with another smallest depth gap.
    pub fn with_min_depth_gap(self, min_depth_gap: f32) -> Self {
        Self {
            min_depth_gap,
            ..self
        }
    }

    /// The same scene, with overlapping coplanar faces or without.
    pub fn with_coplanar_overlaps(self, coplanar_overlaps: bool) -> Self {
        Self {
            coplanar_overlaps,
            ..self
        }
    }

    /// The same scene with another depth complexity.
    pub fn with_max_layers(self, max_layers: u32) -> Self {
        Self { max_layers, ..self }
    }
}

/// The error a frame may have.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ErrorBound {
    /// The largest displacement of a drawn edge from its exact position, in pixels
    /// (> 0). A pixel centre closer than this to an edge may take the neighbouring
    /// face; a centre farther away never does.
    pub edge_px: f32,
}

impl Default for ErrorBound {
    /// A quarter pixel: a pixel changes only where an exact edge passes within a
    /// quarter pixel of its centre.
    fn default() -> Self {
        Self { edge_px: 0.25 }
    }
}

/// Settings that keep a scene's error under an [`ErrorBound`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Recommendation {
    /// Sub-pixel bits S (the renderers' `Frac` type parameter).
    pub subpixel_bits: u32,
    /// The predicted worst edge displacement at that S, pixels (snapping plus floor).
    pub edge_error_px: f32,
    /// The part of `edge_error_px` that no S removes (fixed-point positions, `f32`
    /// camera), pixels.
    pub floor_px: f32,
    /// Depth bits for the Z-buffer engine: 16 or 32.
    pub depth_bits: u32,
    /// The smallest nearness difference between two surfaces `min_depth_gap` apart,
    /// in units of `2^-31` (the depth test needs it above two steps of the samples).
    pub min_gap_q31: f32,
    /// The smallest gap between two surfaces at the farthest drawn distance that
    /// 16-bit depth tells apart (world units); closer surfaces may tie, and the
    /// lower face index shows.
    pub separable_gap_16: f32,
    /// The same for 32-bit depth.
    pub separable_gap_32: f32,
    /// 32-bit words of the code-fill engine's surface code (its `WORDS` parameter).
    pub code_words: u32,
    /// Every part of the bound can be met: the floor is below `edge_px` and 32-bit
    /// depth separates `min_depth_gap`.
    pub meets_bound: bool,
}

/// The depth test's tie margin, as a move of a face's plane: 1/16 px.
const TIE_PX: f32 = 1.0 / 16.0;
/// `2^-31` (nearness unit of a 32-bit sample).
const Q31: f32 = 1.0 / 2_147_483_648.0;
/// Two steps of a 16-bit sample (`2 * 2^-15`).
const NEED_16: f32 = 2.0 / 32_768.0;
/// Two steps of a 32-bit sample, counting the tie margin and rounding (`2 * 2^-27`).
const NEED_32: f32 = 2.0 / 134_217_728.0;

/// The smallest S, depth bits and code width that keep `scene`'s error on
/// `viewport` under `bound`. Never panics: out-of-range input (non-finite, negative,
/// `near >= far`) gives the most precise settings with `meets_bound` false.
pub fn recommend(scene: &SceneBounds, viewport: Viewport, bound: &ErrorBound) -> Recommendation {
    let valid = scene.max_coordinate.is_finite()
        && scene.radius.is_finite()
        && scene.radius > 0.0
        && scene.near.is_finite()
        && scene.far.is_finite()
        && scene.near > 0.0
        && scene.far > scene.near
        && scene.min_depth_gap.is_finite()
        && scene.min_depth_gap >= 0.0
        && bound.edge_px.is_finite()
        && bound.edge_px > 0.0;
    let side = f32::from(viewport.width.max(viewport.height));
    // 26 fixed-point bits for the largest coordinate, about 2^-24 relative from the
    // f32 camera and the clip rows: 2^-26 + 2^-24 < 2^-23.
    let floor_px = if valid {
        (scene.max_coordinate.abs() / scene.radius).max(1.0) * side * (1.0 / 8_388_608.0)
    } else {
        f32::INFINITY
    };
    // Snapping: sqrt(2) 2^-(S+1) px. Coplanar faces tie only when snapping moves a
    // plane by less than the tie margin, 1/16 px: S >= 4.
    let coplanar = scene.coplanar_overlaps;
    // False for a NaN bound or floor as well.
    let fits = |snap: f32| snap + floor_px <= bound.edge_px;
    let mut s = 0;
    let mut snap = core::f32::consts::SQRT_2 / 2.0;
    while s < MAX_SUBPIXEL_BITS && (!fits(snap) || (coplanar && snap > TIE_PX)) {
        s += 1;
        snap /= 2.0;
    }
    let edge_ok = valid && fits(snap);
    // Nearness per world unit at the farthest drawn distance: depth is scaled to
    // near..far (the distances drawn).
    let per_unit = if !valid {
        0.0
    } else if scene.orthographic {
        1.0 / (scene.far - scene.near)
    } else {
        scene.near / ((scene.far - scene.near) * scene.far)
    };
    // The smallest nearness difference between surfaces min_depth_gap apart.
    let gap = scene.min_depth_gap * per_unit;
    let separable = |need: f32| {
        if per_unit > 0.0 {
            need / per_unit
        } else {
            f32::INFINITY
        }
    };
    // Coplanar faces tie within 8 units of 2^-31 plus 1/16 of a plane's change per
    // pixel; a 16-bit sample's truncation (2^16 units) breaks such ties.
    let depth_bits = if gap >= NEED_16 && !coplanar { 16 } else { 32 };
    let depth_ok = valid && gap >= NEED_32;
    let layers = scene.max_layers.max(1).saturating_add(1);
    Recommendation {
        subpixel_bits: s,
        edge_error_px: snap + floor_px,
        floor_px,
        depth_bits,
        min_gap_q31: gap / Q31,
        separable_gap_16: separable(NEED_16),
        separable_gap_32: separable(NEED_32),
        code_words: layers.div_ceil(32),
        meets_bound: edge_ok && depth_ok,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const VP: Viewport = Viewport {
        width: 400,
        height: 240,
    };

    #[test]
    fn subpixel_bits_follow_the_bound() {
        let scene = SceneBounds::perspective(3.0, 1.0, 2.0, 4.0);
        let s = |edge_px| recommend(&scene, VP, &ErrorBound { edge_px }).subpixel_bits;
        assert_eq!(s(1.0), 0);
        assert_eq!(s(0.5), 1);
        assert_eq!(s(0.25), 2);
        assert_eq!(s(0.1), 3);
        assert_eq!(s(0.01), 7);
    }

    #[test]
    fn depth_bits_follow_near_far_and_gap() {
        let b = ErrorBound::default();
        let near_far = SceneBounds::perspective(3.0, 1.0, 2.0, 4.0);
        assert_eq!(recommend(&near_far, VP, &b).depth_bits, 16);
        let wide = SceneBounds::perspective(3.0, 1.0, 0.1, 1000.0);
        let r = recommend(&wide, VP, &b);
        assert_eq!(r.depth_bits, 32);
        assert!(
            !r.meets_bound,
            "1e-3 at 1000 with near 0.1 is below 32 bits"
        );
    }

    /// Issue 24, item 3: surfaces 1e-4 apart around 100 (drawn distances 99.99 to
    /// 100.01, whatever the camera's near) are told apart by 16-bit depth; drawn
    /// from 0.1 to 1000 they are not, and 32 bits say so too.
    #[test]
    fn depth_bits_follow_the_drawn_distances() {
        let b = ErrorBound::default();
        let close = SceneBounds::perspective(100.0, 20.0, 99.99, 100.01).with_min_depth_gap(1e-4);
        let r = recommend(&close, VP, &b);
        assert_eq!(r.depth_bits, 16);
        assert!(r.meets_bound && r.separable_gap_16 <= 1e-4, "{r:?}");
        let deep = SceneBounds::perspective(100.0, 20.0, 0.1, 1000.0).with_min_depth_gap(1e-4);
        let r = recommend(&deep, VP, &b);
        assert!(!r.meets_bound && r.separable_gap_32 > 1e-4, "{r:?}");
    }

    #[test]
    fn coplanar_faces_need_four_bits() {
        let scene = SceneBounds::perspective(3.0, 1.0, 2.0, 4.0).with_coplanar_overlaps(true);
        let r = recommend(&scene, VP, &ErrorBound { edge_px: 1.0 });
        assert_eq!(r.subpixel_bits, 4);
        assert_eq!(r.depth_bits, 32);
        assert!(r.meets_bound);
    }

    #[test]
    fn bad_input_is_not_a_panic() {
        let mut scene = SceneBounds::perspective(f32::NAN, 1.0, 2.0, 1.0);
        let r = recommend(&scene, VP, &ErrorBound { edge_px: -1.0 });
        assert!(!r.meets_bound);
        assert_eq!(r.subpixel_bits, MAX_SUBPIXEL_BITS);
        scene.max_layers = u32::MAX;
        assert_eq!(
            recommend(&scene, VP, &ErrorBound::default()).code_words,
            u32::MAX / 32 + 1
        );
    }
}
