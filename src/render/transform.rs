//! World to screen in fixed point: the per-frame scales, clip coordinates, the
//! near/far and guard-band planes, homogeneous polygon clipping and projection.
//!
//! Scales, chosen per frame so nothing overflows: positions (vertices and eye) are
//! `round(p * 2^k)` with `|p| * 2^k < 2^26`; the clip rows are `round(r * 2^m)` with
//! entries below `2^30`; a clip coordinate `sum r_j (v_j - eye_j)` is below `2^59` in
//! `i64` and is stored as `i32` after a right shift by 29: one world unit along a
//! clip axis is `2^sigma`, `sigma = k + m - 29`.

use heapless::Vec;

use crate::camera::Camera;
use crate::Capacity;
use crate::{Error, GUARD_BAND_PX};

/// A vertex in clip coordinates (fixed point, `2^sigma` per unit): `x` and `y` are
/// `x_ndc * w` and `y_ndc * w`; `z` is the distance in front of the eye.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ClipVertex {
    /// `x_ndc * w`.
    pub x: i32,
    /// `y_ndc * w`.
    pub y: i32,
    /// Distance in front of the eye.
    pub z: i32,
}

/// A projected vertex: screen position with S sub-pixel bits, and its nearness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScreenVertex {
    /// Screen x, raw fixed-point bits (`x * 2^S`).
    pub x: i32,
    /// Screen y, raw fixed-point bits.
    pub y: i32,
    /// Nearness, affine in screen space, `Q1.31`, over the distances the frame draws
    /// (`lo..=hi`, see `FixedView::fit_depth`): from `2^31` at `lo` down to `2^25`
    /// at `hi`, as `lo (hi - distance) / ((hi - lo) distance)` under perspective and
    /// `(hi - distance) / (hi - lo)` under an orthographic projection. Larger is
    /// nearer.
    pub q: u32,
}

/// One vertex of the per-frame vertex cache, 16 bytes: its projection when it is
/// inside the view volume, else its clip coordinates, which clipping needs. (An
/// inside vertex's clip coordinates, needed where an edge or face beside it is
/// clipped, are made again from its position: the same integers.)
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ProjectedVertex {
    /// Screen `x`, `y` and the bits of `q` when `outside == 0`, else clip `x`, `y`, `z`.
    coords: [i32; 3],
    /// One bit per clip plane the vertex is outside of.
    outside: u8,
}

impl ProjectedVertex {
    /// All zero, for lent buffers (a `static` of them is `.bss`).
    pub const ZERO: Self = Self {
        coords: [0; 3],
        outside: 0,
    };

    /// The vertex at world position `p` in `view`.
    #[cfg(test)]
    pub(crate) fn new(view: &FixedView, p: [f32; 3]) -> Self {
        let mut v = Self::unprojected(view, p);
        v.project(view);
        v
    }

    /// The clip coordinates and outcode of world position `p`, not yet projected:
    /// the frame's depth range ([`FixedView::fit_depth`]) comes from these first.
    pub(crate) fn unprojected(view: &FixedView, p: [f32; 3]) -> Self {
        let clip = view.clip(p);
        Self {
            coords: [clip.x, clip.y, clip.z],
            outside: view.outcode(&clip),
        }
    }

    /// Clip distance in front of the eye of an [`unprojected`](Self::unprojected)
    /// vertex.
    pub(crate) fn clip_z(&self) -> i32 {
        self.coords[2]
    }

    /// Replaces the clip coordinates of an [`unprojected`](Self::unprojected)
    /// vertex inside the view volume by its projection (once, after the depth range
    /// is fitted); one outside keeps them.
    pub(crate) fn project(&mut self, view: &FixedView) {
        if self.outside == 0 {
            let [x, y, z] = self.coords;
            let v = view.project(&ClipVertex { x, y, z });
            self.coords = [v.x, v.y, v.q as i32];
        }
    }

    /// One bit per clip plane (near, far, then the guard band's four sides) the
    /// vertex is outside of; 0 inside the view volume.
    pub fn outside(&self) -> u8 {
        self.outside
    }

    /// Its projection; all zero for a vertex outside the view volume (see
    /// [`Self::outside`]), which has none.
    pub fn screen(&self) -> ScreenVertex {
        self.projection().unwrap_or_default()
    }

    /// Its projection, `None` outside the view volume.
    pub fn projection(&self) -> Option<ScreenVertex> {
        let [x, y, q] = self.coords;
        (self.outside == 0).then_some(ScreenVertex { x, y, q: q as u32 })
    }

    /// Its clip coordinates: kept for a vertex outside the view volume, made again
    /// from its world position `p` for one inside.
    pub(crate) fn clip(&self, view: &FixedView, p: [f32; 3]) -> ClipVertex {
        if self.outside == 0 {
            return view.clip(p);
        }
        let [x, y, z] = self.coords;
        ClipVertex { x, y, z }
    }
}

/// The nearness of the farthest drawn distance: a margin below it, so that a
/// nearness minus a tie stays positive.
const Q_FLOOR: i64 = 1 << 25;
/// Nearness units from the farthest to the nearest drawn distance.
const Q_SPAN: i64 = (1 << 31) - Q_FLOOR;

/// Clip units by which the rounding of positions, of the rotation's products and
/// of the eye may move a vertex's distance, for two vertices together.
const GRID_UNITS: f32 = 4.0;
/// Units of nearness the projection's rounding may add.
const Q_ROUNDING: u32 = 8;

/// How far the clip grid's rounding may move a point's nearness `q`: [`GRID_UNITS`]
/// clip units of distance, converted at the point's own distance (under perspective
/// nearness changes as `1/z`, so far points get the finer steps that the frame's
/// depth range gives them there), plus the projection's rounding.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct DepthGrid {
    offset: f32,
    scale: f32,
    flat: f32,
}

impl DepthGrid {
    /// The uncertainty of nearness `q`, in nearness units.
    pub fn slack(&self, q: u32) -> u32 {
        let u = q as f32 + self.offset;
        let slack = self.flat + self.scale * u * u;
        (slack.min(Q_SPAN as f32) as u32).saturating_add(Q_ROUNDING)
    }
}

/// Planes, in clipping order: near, far, then the guard band's four sides.
const PLANES: usize = 6;

/// The fixed-point view of one frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FixedView {
    rows: [[i64; 3]; 3],
    eye: [i64; 3],
    pos_scale: f32,
    perspective: bool,
    /// 1.0 in clip units (the orthographic `w`).
    one: i64,
    near: i64,
    far: i64,
    /// The distances the frame draws (clip units, within near..far): nearness
    /// spans its whole range between them.
    z_lo: i64,
    z_hi: i64,
    /// `2^sigma`: clip units per world unit.
    unit: f32,
    /// Guard-band half-size in NDC units.
    guard: i64,
    /// Screen size times 2^S, for projection.
    width_s: i64,
    height_s: i64,
}

/// `2^e >= |x|`: the exponent of the smallest power of two not below `x` (> 0).
fn ceil_log2(x: f32) -> i32 {
    let bits = x.to_bits();
    let exp = ((bits >> 23) & 0xFF) as i32 - 127;
    if bits & 0x7F_FFFF == 0 {
        exp
    } else {
        exp + 1
    }
}

/// `2^e` as f32 for `|e| <= 126`.
fn pow2(e: i32) -> f32 {
    f32::from_bits(((e.clamp(-126, 127) + 127) as u32) << 23)
}

/// `x` rounded to the nearest integer, saturating.
fn round_i64(x: f32) -> i64 {
    (if x >= 0.0 { x + 0.5 } else { x - 0.5 }) as i64
}

/// `n / d` rounded to nearest (ties away from zero), for `d > 0`.
pub(crate) fn div_round(n: i64, d: i64) -> i64 {
    if d <= 0 {
        return 0;
    }
    let q = n.div_euclid(d);
    let r = n.rem_euclid(d);
    if 2 * r >= d {
        q + 1
    } else {
        q
    }
}

impl FixedView {
    /// Sets up the frame: `max_abs` is the largest absolute vertex coordinate.
    pub fn new(
        camera: &Camera,
        max_abs: f32,
        width: u16,
        height: u16,
        s: u32,
    ) -> Result<Self, Error> {
        let eye = camera.eye();
        let magnitude = eye.iter().fold(max_abs, |m, c| m.max(c.abs())).max(1e-30);
        let k = 26 - ceil_log2(magnitude);
        let aspect = f32::from(width.max(1)) / f32::from(height.max(1));
        let rows_f = camera.clip_rows(aspect);
        let max_r = rows_f.iter().flatten().fold(0.0f32, |m, r| m.max(r.abs()));
        let m = 30 - ceil_log2(max_r.max(1e-30)) - 1;
        let sigma = k + m - 29;
        if !(1..=60).contains(&sigma) || !(-100..=100).contains(&k) || !(-100..=100).contains(&m) {
            return Err(Error::OutOfRange);
        }
        let (pos_scale, row_scale) = (pow2(k), pow2(m));
        let mut rows = [[0i64; 3]; 3];
        for (dst, src) in rows.iter_mut().zip(rows_f) {
            for (d, r) in dst.iter_mut().zip(src) {
                *d = round_i64(r * row_scale);
            }
        }
        let one = 1i64 << sigma;
        let unit = f64::from(pow2(sigma.min(126)));
        let (near, far) = camera.near_far();
        let to_clip = |d: f32| (f64::from(d) * unit).min(f64::from(i32::MAX)) as i64;
        let guard = i64::from(GUARD_BAND_PX) / i64::from(width.max(height).max(1)) - 1;
        let (near, far) = (to_clip(near).max(1), to_clip(far));
        Ok(Self {
            rows,
            eye: eye.map(|e| round_i64(e * pos_scale)),
            pos_scale,
            perspective: camera.is_perspective(),
            one,
            near,
            far,
            z_lo: near,
            z_hi: far,
            unit: pow2(sigma.min(126)),
            guard: guard.max(1),
            width_s: i64::from(width) << s,
            height_s: i64::from(height) << s,
        })
    }

    /// Fits the depth scale to the clip distances `zs` of the frame's vertices
    /// (clamped to near..far): nearness then spans its whole `Q1.31` range between
    /// the nearest and the farthest of them, so that surfaces close together far
    /// from the eye get the precision the scene has there, whatever near and far are.
    pub fn fit_depth(&mut self, zs: impl Iterator<Item = i32>) {
        let (mut lo, mut hi) = (i64::MAX, i64::MIN);
        for z in zs {
            // max then min: a far below near (rounded so) must not panic.
            let z = i64::from(z).max(self.near).min(self.far);
            (lo, hi) = (lo.min(z), hi.max(z));
        }
        if lo <= hi {
            (self.z_lo, self.z_hi) = (lo, hi);
        }
    }

    /// How far the clip grid may put a point's nearness from the true one, as a
    /// function of the nearness (see [`DepthGrid`]).
    pub fn depth_grid(&self) -> DepthGrid {
        let (lo, hi) = (self.z_lo as f32, self.z_hi as f32);
        if hi <= lo {
            return DepthGrid::default();
        }
        let span = Q_SPAN as f32;
        if self.perspective {
            // u = q - Q_FLOOR + Q_SPAN lo / (hi - lo) = Q_SPAN lo hi / ((hi - lo) z),
            // and |dq/dz| = u^2 (hi - lo) / (Q_SPAN lo hi).
            let lo = lo.max(1.0);
            DepthGrid {
                offset: span * lo / (hi - lo) - Q_FLOOR as f32,
                scale: GRID_UNITS * (hi - lo) / (span * lo * hi),
                flat: 0.0,
            }
        } else {
            DepthGrid {
                offset: 0.0,
                scale: 0.0,
                flat: GRID_UNITS * span / (hi - lo),
            }
        }
    }

    /// The world distance that one step of a `bits`-bit depth sample stands for at
    /// the nearest and the farthest drawn distance (never finer than the clip grid).
    pub fn depth_steps(&self, bits: u32) -> (f32, f32) {
        let (lo, hi) = (self.z_lo as f32, self.z_hi as f32);
        // Nearness units per sample step (a 16-bit sample keeps the top bits), as a
        // share of the drawn range.
        let sample = pow2(32 - bits.clamp(1, 32) as i32) / Q_SPAN as f32;
        let grid = 1.0 / self.unit;
        if hi <= lo {
            return (grid, grid);
        }
        let world = |clip: f32| (clip / self.unit).max(grid);
        if self.perspective {
            // q = Q_FLOOR + Q_SPAN lo (hi - z) / ((hi - lo) z): dz = (hi - lo) z^2 /
            // (Q_SPAN lo hi) a unit.
            let step = |z: f32| world(sample * (hi - lo) * z * z / (lo * hi));
            (step(lo), step(hi))
        } else {
            let step = world(sample * (hi - lo));
            (step, step)
        }
    }

    /// Clip coordinates of a world position.
    // Indexing: i in 0..3 on arrays of 3.
    #[allow(clippy::indexing_slicing)]
    pub fn clip(&self, p: [f32; 3]) -> ClipVertex {
        let d = [0, 1, 2].map(|i| round_i64(p[i] * self.pos_scale) - self.eye[i]);
        let c = self
            .rows
            .map(|r| ((r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) >> 29) as i32);
        ClipVertex {
            x: c[0],
            y: c[1],
            z: c[2],
        }
    }

    fn w(&self, v: &ClipVertex) -> i64 {
        if self.perspective {
            i64::from(v.z)
        } else {
            self.one
        }
    }

    /// Signed distance to plane `i` (inside >= 0).
    fn distance(&self, v: &ClipVertex, plane: usize) -> i64 {
        let gw = self.guard * self.w(v);
        let (x, y, z) = (i64::from(v.x), i64::from(v.y), i64::from(v.z));
        match plane {
            0 => z - self.near,
            1 => self.far - z,
            2 => x + gw,
            3 => gw - x,
            4 => y + gw,
            _ => gw - y,
        }
    }

    /// The planes `v` is outside of, one bit each.
    pub fn outcode(&self, v: &ClipVertex) -> u8 {
        (0..PLANES).fold(0, |acc, i| acc | (u8::from(self.distance(v, i) < 0) << i))
    }

    /// Projects a vertex inside every plane.
    pub fn project(&self, v: &ClipVertex) -> ScreenVertex {
        let w = self.w(v).max(1);
        let (x, y, z) = (i64::from(v.x), i64::from(v.y), i64::from(v.z));
        let sx = div_round((x + w) * self.width_s, 2 * w);
        let sy = div_round((w - y) * self.height_s, 2 * w);
        let (lo, hi) = (self.z_lo, self.z_hi);
        let z = z.max(lo).min(hi);
        let q = if hi <= lo {
            Q_FLOOR
        } else {
            // 2^31 at the nearest drawn distance, Q_FLOOR at the farthest; under
            // perspective affine in 1/z (so in screen space):
            // Q_FLOOR + Q_SPAN lo (hi - z) / ((hi - lo) z).
            let t = (hi - z) * Q_SPAN / (hi - lo).max(1);
            Q_FLOOR
                + if self.perspective {
                    t * lo / z.max(1)
                } else {
                    t
                }
        };
        ScreenVertex {
            x: sx as i32,
            y: sy as i32,
            q: q.clamp(0, 1 << 31) as u32,
        }
    }

    /// The point on segment `a`-`b` on plane `i` (`a` inside, `b` outside).
    fn intersect(&self, a: &ClipVertex, b: &ClipVertex, plane: usize) -> ClipVertex {
        let (da, db) = (
            i128::from(self.distance(a, plane)),
            i128::from(self.distance(b, plane)),
        );
        let den = da - db;
        let lerp = |p: i32, q: i32| -> i32 {
            if den == 0 {
                return p;
            }
            let n = (i128::from(q) - i128::from(p)) * da;
            let t = n.checked_div_euclid(den).unwrap_or(0);
            (i128::from(p) + t) as i32
        };
        ClipVertex {
            x: lerp(a.x, b.x),
            y: lerp(a.y, b.y),
            z: lerp(a.z, b.z),
        }
    }

    /// Clips segment `a`-`b` against the planes in `outside`; `None` when nothing
    /// of it is inside. Each new end is computed from the inside end, as for
    /// polygons, so an edge shared by a face and a line clips to the same point.
    pub fn clip_segment(
        &self,
        mut a: ClipVertex,
        mut b: ClipVertex,
        outside: u8,
    ) -> Option<(ClipVertex, ClipVertex)> {
        for plane in (0..PLANES).filter(|i| outside & (1 << i) != 0) {
            let (ina, inb) = (self.distance(&a, plane) >= 0, self.distance(&b, plane) >= 0);
            match (ina, inb) {
                (false, false) => return None,
                (false, true) => a = self.intersect(&b, &a, plane),
                (true, false) => b = self.intersect(&a, &b, plane),
                (true, true) => {}
            }
        }
        Some((a, b))
    }

    /// Clips a polygon against the planes in `outside` (Sutherland-Hodgman), in place.
    /// Fails when a clipped polygon would exceed `N` vertices.
    pub fn clip_polygon<const N: usize>(
        &self,
        poly: &mut Vec<ClipVertex, N>,
        outside: u8,
    ) -> Result<(), Error> {
        for plane in (0..PLANES).filter(|i| outside & (1 << i) != 0) {
            let mut out: Vec<ClipVertex, N> = Vec::new();
            let n = poly.len();
            let mut needed = 0usize;
            for i in 0..n {
                let (Some(a), Some(b)) = (poly.get(i), poly.get((i + 1) % n)) else {
                    continue;
                };
                let (ina, inb) = (self.distance(a, plane) >= 0, self.distance(b, plane) >= 0);
                if ina {
                    needed += 1;
                    let _ = out.push(*a);
                }
                if ina != inb {
                    let p = if ina {
                        self.intersect(a, b, plane)
                    } else {
                        self.intersect(b, a, plane)
                    };
                    needed += 1;
                    let _ = out.push(p);
                }
            }
            if needed > N {
                return Err(Error::CapacityExceeded {
                    what: Capacity::ClippedFaceCorners,
                    needed,
                    capacity: N,
                });
            }
            *poly = out;
        }
        Ok(())
    }
}
