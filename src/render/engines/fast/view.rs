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

impl ScreenMap {
    /// The map for `camera` on `viewport` with `s` sub-pixel bits; depth scaled to
    /// the distances of `positions` within near..far.
    pub fn new(camera: &Camera, viewport: Viewport, s: u32, positions: &[[f32; 3]]) -> Self {
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
        for p in positions {
            let z = dot(rows[2], sub(*p, eye)).clamp(near, far);
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
        ((q - self.q_far) * self.scale + MARGIN * 65536.0) as u32
    }

    /// A screen point inside the guard box, snapped.
    pub fn snap(&self, p: ScreenPoint) -> FastVertex {
        FastVertex {
            x: round(p.x) as i16,
            y: round(p.y) as i16,
            d: self.depth(p.q),
        }
    }

    /// The cache entry of world position `p`.
    pub fn vertex(&self, p: [f32; 3]) -> FastVertex {
        let e = self.eye_space(p);
        if !(e[2] >= self.near && e[2] <= self.far) {
            return FastVertex {
                x: FastVertex::OUTSIDE,
                ..FastVertex::ZERO
            };
        }
        let sp = self.screen(e);
        if !(sp.x.abs() <= self.limit && sp.y.abs() <= self.limit) {
            return FastVertex {
                x: FastVertex::OUTSIDE,
                ..FastVertex::ZERO
            };
        }
        self.snap(sp)
    }
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `floor(x + 0.5)` for `|x| < 2^30`.
fn round(x: f32) -> i32 {
    let y = x + 0.5;
    let i = y as i32;
    if (i as f32) > y {
        i - 1
    } else {
        i
    }
}
