//! The fast engine's view: world positions to 16-bit screen coordinates with S
//! sub-pixel bits and a 32-bit depth scaled to the depth range the frame draws, in
//! `f32` set-up (IEEE basic operations only, so host and Cortex-M4F give the same
//! bits).
//!
//! Depth is "nearness", larger nearer: `1 / distance` under perspective (affine in
//! screen space), `-distance` under an orthographic projection. It is stored as a
//! 16.16 fixed-point `u32` whose integer part maps the nearness range of the
//! frame's vertices within near..far onto `MARGIN..=0xFFFF - MARGIN`, so that planes
//! evaluated a little beyond their corners stay in range.

use super::float_int::{to_i32, to_u32};
use crate::camera::{dot, Camera};
use crate::mesh::Viewpoint;
use crate::Viewport;

/// Integer depth units kept free below and above the frame's depth range.
const MARGIN: f32 = 256.0;

/// One vertex of the per-frame cache, 8 bytes: screen `x`, `y` in units of
/// `2^-S` px and the depth (16.16, larger nearer). `x == i16::MIN` marks a vertex
/// outside near..far or the guard box, whose faces and edges are clipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FastVertex {
    /// Screen x, `2^-S` px.
    pub x: i16,
    /// Screen y, `2^-S` px.
    pub y: i16,
    /// Depth, 16.16, larger nearer.
    pub d: u32,
}

impl FastVertex {
    /// All zero, for lent buffers in `static`s.
    pub const ZERO: Self = Self { x: 0, y: 0, d: 0 };
    /// The mark of a vertex that must be clipped.
    pub(super) const OUTSIDE: i16 = i16::MIN;
    /// The entry of a vertex that must be clipped.
    const OFF: Self = Self {
        x: Self::OUTSIDE,
        ..Self::ZERO
    };

    /// True when the vertex lies in near..far and the guard box.
    pub(super) fn inside(&self) -> bool {
        self.x != Self::OUTSIDE
    }

    /// `x` and `y` in one word: equal exactly when both are.
    #[inline(always)]
    pub(super) fn key(&self) -> u32 {
        u32::from(self.x as u16) | u32::from(self.y as u16) << 16
    }

    /// `x` and `y` in half sub-pixel units (`2^-(S+1)` px), where pixel centres
    /// are integers.
    pub(super) fn half(&self) -> (i32, i32) {
        (2 * i32::from(self.x), 2 * i32::from(self.y))
    }
}

/// A point in eye space: `x`, `y` scaled by the projection (`x_ndc = x / z` under
/// perspective, `x` under an orthographic projection), `z` the distance in front.
pub(super) type EyePoint = [f32; 3];

/// A point on screen before snapping: `x`, `y` in `2^-S` px, and nearness.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct ScreenPoint {
    pub x: f32,
    pub y: f32,
    pub q: f32,
}

/// The camera and screen of one frame.
#[derive(Debug, Clone, Copy)]
pub(super) struct ScreenMap {
    eye: [f32; 3],
    rows: [[f32; 3]; 3],
    perspective: bool,
    pub near: f32,
    pub far: f32,
    half_w: f32,
    half_h: f32,
    /// The guard box: `|x|, |y| <= limit` (`2^-S` px).
    pub limit: f32,
    q_far: f32,
    scale: f32,
    /// The distances the frame draws, within near..far.
    lo: f32,
    hi: f32,
    pub viewpoint: Viewpoint,
    pub s: u32,
}

/// The guard box's half-size in pixels for S sub-pixel bits: coordinates fit
/// `i16`, and every product of the edge and line steppers fits `i32` (see
/// `raster`).
pub(super) fn guard_px(s: u32) -> i32 {
    ((1i32 << (15 - s)) - 1).min(4096)
}

/// Whether [`ScreenMap::with_vertices`] transforms each position once (cores
/// without an FPU) or twice.
const ONE_TRANSFORM: bool = cfg!(all(target_arch = "arm", not(target_abi = "eabihf")));

impl ScreenMap {
    /// The map for `camera` on `viewport` with `s` sub-pixel bits, depth scaled to
    /// the distances of `positions` within near..far, and the vertex cache
    /// `cache` (one entry a position, as far as it reaches) made with it.
    ///
    /// On a core without an FPU each position is taken to eye space and the
    /// screen once: its distance counted into the depth range, its nearness kept
    /// in its entry's depth until the range is known (a second soft-float
    /// transform cost the panel's frame 4 % there). With an FPU the distances
    /// come first, then each entry whole: fewer instructions than keeping the
    /// nearness (suzanne's M4 frame 0.5 % fewer). The same `f32` operations
    /// either way, so the same entries.
    pub fn with_vertices(
        camera: &Camera,
        viewport: Viewport,
        s: u32,
        positions: &[[f32; 3]],
        cache: &mut [FastVertex],
    ) -> Self {
        let (w, h) = (f32::from(viewport.width), f32::from(viewport.height));
        let aspect = if h > 0.0 { w / h } else { 1.0 };
        let rows = camera.clip_rows(aspect);
        let (near, far) = camera.near_far();
        let eye = camera.eye();
        let unit = (1u32 << s) as f32;
        let mut map = Self {
            eye,
            rows,
            perspective: camera.is_perspective(),
            near,
            far,
            half_w: 0.5 * w * unit,
            half_h: 0.5 * h * unit,
            limit: guard_px(s) as f32 * unit,
            q_far: 0.0,
            scale: 0.0,
            lo: near,
            hi: far,
            viewpoint: camera.viewpoint(),
            s,
        };
        // The distances the frame draws: its vertices', clamped to near..far.
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for (i, p) in positions.iter().enumerate() {
            let z = if ONE_TRANSFORM {
                let e = map.eye_space(*p);
                if let Some(slot) = cache.get_mut(i) {
                    *slot = map.unscaled(e);
                }
                e[2]
            } else {
                dot(rows[2], sub(*p, eye))
            };
            let z = z.clamp(near, far);
            lo = lo.min(z);
            hi = hi.max(z);
        }
        if lo > hi {
            (lo, hi) = (near, far);
        }
        (map.lo, map.hi) = (lo, hi);
        let (q_near, q_far) = (map.nearness(lo), map.nearness(hi));
        let span = q_near - q_far;
        let scale = (65536.0 - 2.0 * MARGIN) * 65536.0 / span;
        map.q_far = q_far;
        map.scale = if span > 0.0 && scale.is_finite() {
            scale
        } else {
            0.0
        };
        for (v, p) in cache.iter_mut().zip(positions) {
            if !ONE_TRANSFORM {
                *v = map.vertex(*p);
            } else if v.inside() {
                v.d = map.depth(f32::from_bits(v.d));
            }
        }
        map
    }

    /// The world distance one step of the row's 16-bit depth stands for at the
    /// nearest and the farthest drawn distance (never finer than `f32` there).
    pub fn depth_steps(&self) -> (f32, f32) {
        let units = 65536.0 - 2.0 * MARGIN;
        let span = self.nearness(self.lo) - self.nearness(self.hi);
        let step = |z: f32| {
            let dz = if self.perspective {
                z * z * span / units
            } else {
                span / units
            };
            dz.max(z.abs() * f32::EPSILON)
        };
        (step(self.lo), step(self.hi))
    }

    fn nearness(&self, z: f32) -> f32 {
        if self.perspective {
            1.0 / z
        } else {
            -z
        }
    }

    /// Eye-space point of world position `p`.
    pub fn eye_space(&self, p: [f32; 3]) -> EyePoint {
        let d = sub(p, self.eye);
        [
            dot(self.rows[0], d),
            dot(self.rows[1], d),
            dot(self.rows[2], d),
        ]
    }

    /// The screen point of an eye-space point with `z > 0`.
    pub fn screen(&self, e: EyePoint) -> ScreenPoint {
        let (k, q) = if self.perspective {
            let inv = 1.0 / e[2];
            (inv, inv)
        } else {
            (1.0, -e[2])
        };
        ScreenPoint {
            x: self.half_w + e[0] * k * self.half_w,
            y: self.half_h - e[1] * k * self.half_h,
            q,
        }
    }

    /// The 16.16 depth of nearness `q`.
    pub fn depth(&self, q: f32) -> u32 {
        to_u32((q - self.q_far) * self.scale + MARGIN * 65536.0)
    }

    /// A screen point inside the guard box, snapped.
    pub fn snap(&self, p: ScreenPoint) -> FastVertex {
        FastVertex {
            x: round(p.x) as i16,
            y: round(p.y) as i16,
            d: self.depth(p.q),
        }
    }

    /// The screen point of eye-space point `e`, when it lies in near..far and
    /// the guard box.
    #[inline(always)]
    fn on_screen(&self, e: EyePoint) -> Option<ScreenPoint> {
        if !(e[2] >= self.near && e[2] <= self.far) {
            return None;
        }
        let sp = self.screen(e);
        (sp.x.abs() <= self.limit && sp.y.abs() <= self.limit).then_some(sp)
    }

    /// The cache entry of world position `p`.
    fn vertex(&self, p: [f32; 3]) -> FastVertex {
        match self.on_screen(self.eye_space(p)) {
            Some(sp) => self.snap(sp),
            None => FastVertex::OFF,
        }
    }

    /// The cache entry of eye-space point `e` with its nearness's bits in
    /// place of its depth (see [`with_vertices`](Self::with_vertices)).
    fn unscaled(&self, e: EyePoint) -> FastVertex {
        match self.on_screen(e) {
            Some(sp) => FastVertex {
                x: round(sp.x) as i16,
                y: round(sp.y) as i16,
                d: sp.q.to_bits(),
            },
            None => FastVertex::OFF,
        }
    }
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `floor(x + 0.5)` for `|x| < 2^30`.
fn round(x: f32) -> i32 {
    let y = x + 0.5;
    let i = to_i32(y);
    if (i as f32) > y {
        i - 1
    } else {
        i
    }
}
