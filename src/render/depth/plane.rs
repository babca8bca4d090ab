//! The nearness plane of a face in screen space ([`DepthPlane`]), exact from its
//! snapped corners, and its value along a row ([`RowPlane`]): the depth that every
//! engine, the line test and picking compare. Depth is the nearness `q` of
//! [`ScreenVertex`], affine in screen space, so each face's depth is a plane: exact at
//! the start of each span, then one add a pixel.

use crate::render::transform::ScreenVertex;

/// Fraction bits of the per-pixel depth step.
pub(crate) const STEP_BITS: u32 = 16;

/// Units of `2^-31` nearness that the projection's rounding may put between two
/// faces through the same points.
const TIE_ROUNDING: u32 = 8;

/// The nearness plane of one face in screen space, in half sub-pixel units
/// (`2^-(S+1)` px): `q(X, Y) = q0 + (a (X - x0) + b (Y - y0)) / den`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct DepthPlane {
    x0: i64,
    y0: i64,
    q0: i64,
    a: i64,
    b: i64,
    den: i64,
    /// Sub-pixel bits.
    s: u32,
    /// Fast form for spans, `STEP_BITS` fraction bits: nearness at the centre of
    /// pixel (`i0`, `j0`) and its change per pixel along x and y.
    i0: i64,
    j0: i64,
    q_ref: i64,
    dq_dx: i64,
    dq_dy: i64,
    /// The vertices' nearness range: the plane is never extrapolated beyond it
    /// (a steep sliver's plane at a pixel centre just outside it would be).
    q_min: i64,
    q_max: i64,
}

impl DepthPlane {
    /// The plane through the fan triangle (v0, vi, vi+1) of largest area; `None`
    /// when every fan triangle is degenerate (the face covers no pixel anyway).
    pub fn new(poly: &[ScreenVertex], s: u32) -> Option<Self> {
        let v0 = poly.first()?;
        let (x0, y0, q0) = half_units(v0);
        let mut best: Option<(i64, Self)> = None;
        for pair in poly.get(1..)?.windows(2) {
            let [v1, v2] = pair else { continue };
            let (a, b, den) = plane_through(v0, v1, v2);
            if den == 0 || best.is_some_and(|(area, _)| area >= den.abs()) {
                continue;
            }
            let plane = Self {
                x0,
                y0,
                q0,
                a,
                b,
                den,
                s,
                i0: 0,
                j0: 0,
                q_ref: 0,
                dq_dx: 0,
                dq_dy: 0,
                q_min: 0,
                q_max: 0,
            };
            best = Some((den.abs(), plane));
        }
        let (_, mut plane) = best?;
        let (q_min, q_max) = poly
            .iter()
            .fold((u32::MAX, 0), |(lo, hi), v| (lo.min(v.q), hi.max(v.q)));
        plane.q_min = i64::from(q_min) << STEP_BITS;
        plane.q_max = i64::from(q_max) << STEP_BITS;
        // The fast form, set up once per face: one exact evaluation and two slopes.
        // Steeper than 2^47 per pixel leaves the Q1.31 range within a pixel anyway.
        let limit = 1i128 << 47;
        let per_pixel = |c: i64| {
            // 64-bit when it fits (most faces): a 128-bit divide is a long library
            // call on a Cortex-M4.
            let shift = s + 1 + STEP_BITS;
            if c.unsigned_abs() < 1u64 << (62 - shift) {
                let q = (c << shift).checked_div_euclid(plane.den).unwrap_or(0);
                return q.clamp(-(1i64 << 47), 1i64 << 47);
            }
            (i128::from(c) << shift)
                .checked_div_euclid(i128::from(plane.den))
                .unwrap_or(0)
                .clamp(-limit, limit) as i64
        };
        plane.dq_dx = per_pixel(plane.a);
        plane.dq_dy = per_pixel(plane.b);
        plane.i0 = x0 >> (s + 1);
        plane.j0 = y0 >> (s + 1);
        let centre = |k: i64| (2 * k + 1) << s;
        plane.q_ref = plane.plane_at(centre(plane.i0), centre(plane.j0)) << STEP_BITS;
        Some(plane)
    }

    /// Nearness at a point in half sub-pixel units, clamped to the range of the
    /// face's vertices: from the fast form (multiplies and a shift, no division),
    /// within `2^-(31 + STEP_BITS)` per pixel of distance of the exact plane.
    pub fn at(&self, x: i64, y: i64) -> u32 {
        (self.unclamped(x, y).clamp(self.q_min, self.q_max) >> STEP_BITS) as u32
    }

    /// The range of nearness over the face's vertices, which holds every value of
    /// [`at`](Self::at).
    pub fn span(&self) -> u32 {
        u32::try_from((self.q_max - self.q_min) >> STEP_BITS).unwrap_or(u32::MAX)
    }

    /// Nearness at a point as [`at`](Self::at) finds it, before the clamp to the
    /// vertices' range, in units of `2^-STEP_BITS`: the plane extended past them.
    pub fn unclamped(&self, x: i64, y: i64) -> i64 {
        let centre = |k: i64| (2 * k + 1) << self.s;
        let (dx, dy) = (x - centre(self.i0), y - centre(self.j0));
        let shift = self.s + 1;
        match self
            .dq_dx
            .checked_mul(dx)
            .zip(self.dq_dy.checked_mul(dy))
            .and_then(|(u, v)| u.checked_add(v))
        {
            Some(n) => self.q_ref.saturating_add(n >> shift),
            None => {
                let n = i128::from(self.dq_dx) * i128::from(dx)
                    + i128::from(self.dq_dy) * i128::from(dy);
                let q = i128::from(self.q_ref) + (n >> shift);
                q.clamp(i128::from(i64::MIN), i128::from(i64::MAX)) as i64
            }
        }
    }

    /// The plane's nearness at a point, unclamped.
    fn plane_at(&self, x: i64, y: i64) -> i64 {
        let coefficients = (self.a, self.b, self.den);
        exact_at(self.q0, coefficients, x - self.x0, y - self.y0)
    }

    /// Depth difference within which this face and an earlier one tie (the earlier,
    /// lower index wins, [conventions](crate::conventions)): the uncertainty of a plane
    /// through vertices snapped to the sub-pixel grid ([`Self::snap_change`]) plus
    /// the rounding of the vertices' nearness. Exactly coplanar faces then tie, and
    /// two faces a depth apart that the grid can tell are ordered by it.
    pub fn tie(&self) -> u32 {
        self.snap_change().saturating_add(TIE_ROUNDING)
    }

    /// How much snapping may move the plane's nearness at a point: each corner of
    /// this face and of one it is compared with moves up to `2^-(S+1)` px along each
    /// axis, so together up to the change over `2^-S` px: a 256th of a pixel's
    /// change at S = 8, so finer grids resolve closer surfaces. Never more than a
    /// sixteenth: wider at coarse grids (S < 4) put more face ids of random scenes
    /// against the f64 reference than it took away (`engines_agree`: 508 far
    /// differences instead of 139).
    pub fn snap_change(&self) -> u32 {
        self.change_per_pixel() >> self.s.clamp(4, 31)
    }

    /// How much the nearness changes over one pixel (the L1 norm of the gradient).
    pub fn change_per_pixel(&self) -> u32 {
        let sum = (self.dq_dx.unsigned_abs() + self.dq_dy.unsigned_abs()) >> STEP_BITS;
        sum.min(1 << 31) as u32
    }

    /// The plane at the centre of pixel (`x`, `y`) ([`STEP_BITS`] fraction bits,
    /// unclamped), its step a pixel right and the range it is clamped to: for a loop
    /// that adds the step a pixel.
    #[inline]
    pub fn span_start(&self, x: u16, y: u16) -> (i64, i64, (i64, i64)) {
        (self.at_pixel(x, y), self.dq_dx, (self.q_min, self.q_max))
    }

    /// Nearness at the centre of pixel (i, j), with `STEP_BITS` fraction bits:
    /// evaluated afresh from the plane (no error carried from other spans), within
    /// a few units of `2^-(31 + STEP_BITS)` per pixel of distance from the face.
    fn at_pixel(&self, i: u16, j: u16) -> i64 {
        let (di, dj) = (i64::from(i) - self.i0, i64::from(j) - self.j0);
        self.q_ref
            .saturating_add(self.dq_dx.saturating_mul(di))
            .saturating_add(self.dq_dy.saturating_mul(dj))
    }
}

/// A vertex in half sub-pixel units, with its nearness: `(x, y, q)`.
pub(crate) fn half_units(v: &ScreenVertex) -> (i64, i64, i64) {
    (2 * i64::from(v.x), 2 * i64::from(v.y), i64::from(v.q))
}

/// The plane through three vertices as `(a, b, den)` of
/// `q(X, Y) = q0 + (a (X - x0) + b (Y - y0)) / den`, where `(x0, y0, q0)` is
/// [`half_units`] of `v0`; `den` (twice the signed area) is 0 when they have no area.
pub(crate) fn plane_through(
    v0: &ScreenVertex,
    v1: &ScreenVertex,
    v2: &ScreenVertex,
) -> (i64, i64, i64) {
    let [(x0, y0, q0), (x1, y1, q1), (x2, y2, q2)] = [v0, v1, v2].map(half_units);
    let (dx1, dy1, dq1) = (x1 - x0, y1 - y0, q1 - q0);
    let (dx2, dy2, dq2) = (x2 - x0, y2 - y0, q2 - q0);
    // In 64 bits: inside the guard band coordinate differences are below 2^28
    // half-units and nearness differences below 2^32, so every product is below
    // 2^60 (wrapping ops only spare the overflow checks).
    let cross = |a: i64, b: i64, c: i64, d: i64| a.wrapping_mul(b).wrapping_sub(c.wrapping_mul(d));
    (
        cross(dq1, dy2, dq2, dy1),
        cross(dq2, dx1, dq1, dx2),
        cross(dx1, dy2, dx2, dy1),
    )
}

/// `q0 + (a dx + b dy) / den` (Euclidean division), the plane of [`plane_through`]
/// at an offset from its first vertex; `q0` when `den` is 0.
pub(crate) fn exact_at(q0: i64, (a, b, den): (i64, i64, i64), dx: i64, dy: i64) -> i64 {
    // 64-bit when it fits (most faces): a 128-bit divide is a long library call on a
    // Cortex-M4, and its temporaries take stack.
    match a
        .checked_mul(dx)
        .zip(b.checked_mul(dy))
        .and_then(|(u, v)| u.checked_add(v))
    {
        Some(n) => q0 + n.checked_div_euclid(den).unwrap_or(0),
        None => wide_at(q0, (a, b, den), dx, dy),
    }
}

/// [`exact_at`] in 128 bits, clamped to +-2^40.
#[cold]
#[inline(never)]
fn wide_at(q0: i64, (a, b, den): (i64, i64, i64), dx: i64, dy: i64) -> i64 {
    let n = i128::from(a) * i128::from(dx) + i128::from(b) * i128::from(dy);
    let q = i128::from(q0) + n.checked_div_euclid(i128::from(den)).unwrap_or(0);
    q.clamp(-(1 << 40), 1 << 40) as i64
}

/// One face's nearness along one row, `q(x) = row_q + dq_dx x`, moved down a row by
/// `dq_dy`: the same values the Z-buffer's `FaceSpans` steps to, without a depth buffer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct RowPlane {
    /// See [`DepthPlane::tie`].
    pub tie: u32,
    row_q: i64,
    dq_dx: i64,
    dq_dy: i64,
    /// The vertices' range of nearness, as 32-bit samples (the plane's own range is
    /// these shifted by `STEP_BITS`: clamping before or after the shift is the same).
    q_min: u32,
    q_max: u32,
}

impl RowPlane {
    /// Nearness 0 everywhere.
    pub const ZERO: Self = Self {
        tie: 0,
        row_q: 0,
        dq_dx: 0,
        dq_dy: 0,
        q_min: 0,
        q_max: 0,
    };

    /// Nearness at the centre of pixel `x` of the row, as a 32-bit depth sample.
    #[inline]
    pub fn at(&self, x: u16) -> u32 {
        // No wrap can happen: |dq_dx| <= 2^47, x < 2^13 and |row_q| < 2^62 (see
        // `DepthPlane::new`); wrapping ops only spare the overflow checks.
        let q = self
            .row_q
            .wrapping_add(self.dq_dx.wrapping_mul(i64::from(x)));
        self.sample(q)
    }

    /// Moves to the next row.
    #[inline]
    pub fn step(&mut self) {
        self.row_q = self.row_q.wrapping_add(self.dq_dy);
    }

    /// Nearness at the centre of pixel (`x`, `y`) of a plane made for row 0
    /// (`row_plane(0)`): the same value as `at(x)` after `y` steps, and as
    /// the Z-buffer's `FaceSpans` gives the pixel (no wrap, as in [`at`](Self::at)).
    #[inline]
    pub fn at_xy(&self, x: u16, y: u16) -> u32 {
        self.sample(self.start_and_step(x, y).0)
    }

    /// The largest nearness the plane takes anywhere (its vertices' largest).
    #[inline]
    pub fn max_q(&self) -> u32 {
        self.q_max
    }

    /// The smallest nearness the plane takes anywhere (its vertices' smallest).
    #[inline]
    pub fn min_q(&self) -> u32 {
        self.q_min
    }

    /// The plane's value (`STEP_BITS` fraction bits, unclamped) at the centre of
    /// pixel (`x`, `y`) of a plane made for row 0, and its step a pixel right: for a
    /// loop that adds the step a pixel (no wrap, as in [`at`](Self::at)).
    #[inline]
    pub fn start_and_step(&self, x: u16, y: u16) -> (i64, i64) {
        let q = self
            .row_q
            .wrapping_add(self.dq_dy.wrapping_mul(i64::from(y)))
            .wrapping_add(self.dq_dx.wrapping_mul(i64::from(x)));
        (q, self.dq_dx)
    }

    /// The 32-bit sample of plane value `q`, clamped to the vertices' range.
    #[inline(always)]
    pub fn sample(&self, q: i64) -> u32 {
        // max then min: no panic path (clamp asserts its bounds are ordered).
        (q >> STEP_BITS)
            .max(i64::from(self.q_min))
            .min(i64::from(self.q_max)) as u32
    }
}

impl DepthPlane {
    /// The plane along row `y`.
    pub fn row_plane(&self, y: u16) -> RowPlane {
        RowPlane {
            tie: self.tie(),
            row_q: self.at_pixel(0, y),
            dq_dx: self.dq_dx,
            dq_dy: self.dq_dy,
            q_min: (self.q_min >> STEP_BITS) as u32,
            q_max: (self.q_max >> STEP_BITS) as u32,
        }
    }
}
