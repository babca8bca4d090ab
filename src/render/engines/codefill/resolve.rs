//! Runs of pixels from the surface code: no face, one face, or the scan-line method
//! where two or more faces overlap.

use fixed::types::extra::LeEqU32;

use super::{ActiveFace, CodeFillRenderer, Surfaces, NO_FACE};
use crate::mesh::Mesh;
use crate::render::depth::fan::fan_depth_at;
use crate::render::depth::fan::ROUNDING;
use crate::render::transform::ProjectedVertex;
use crate::render::FrameCtx;

impl<
        Frac: LeEqU32,
        const WORDS: usize,
        const FACES: usize,
        const EDGES: usize,
        const POLY: usize,
    > CodeFillRenderer<Frac, WORDS, FACES, EDGES, POLY>
{
    /// The face holding code bit `bit`.
    pub(super) fn owner(&self, bit: usize) -> &ActiveFace {
        let f = self
            .owner
            .get(bit / 32)
            .and_then(|w| w.get(bit % 32))
            .copied()
            .unwrap_or(0);
        self.faces.get(usize::from(f)).unwrap_or(&NO_FACE)
    }

    /// Writes the ids of pixels `xa .. xb` of the current row from the code;
    /// returns the runs written.
    pub(super) fn resolve(&self, row: &RowFaces<'_>, xa: u16, xb: u16, out: &mut [u16]) -> u32 {
        let Some(run) = out.get_mut(usize::from(xa)..usize::from(xb)) else {
            return 0;
        };
        match self.inside {
            0 => {
                run.fill(0);
                1
            }
            1 => {
                let bit = self
                    .code
                    .iter()
                    .enumerate()
                    .find(|(_, w)| **w != 0)
                    .map_or(0, |(k, w)| 32 * k + w.trailing_zeros() as usize);
                run.fill(self.owner(bit).id);
                1
            }
            // Faces beyond the code: the frame fails with the width it needs.
            n if n > Self::CODE_BITS => 0,
            // Depth order: the priority encoder.
            _ if self.priority => {
                run.fill(self.nearest_covering());
                1
            }
            _ => self.resolve_overlap(row, xa, xb, out),
        }
    }

    /// Depth order: the id of the nearest face covering the run, from the lowest bit
    /// set. A face whose fragments may overlap (`fold`) covers the run only if an odd
    /// number of its fragments do; otherwise its bits are dropped and the next
    /// lowest decides.
    fn nearest_covering(&self) -> u16 {
        let mut code = self.code;
        loop {
            let Some(bit) = code
                .iter()
                .enumerate()
                .find(|(_, w)| **w != 0)
                .map(|(k, w)| 32 * k + w.trailing_zeros() as usize)
            else {
                return 0;
            };
            let face = self.owner(bit);
            if !face.fold {
                return face.id;
            }
            let mut odd = false;
            for (k, word) in code.iter_mut().enumerate() {
                let mut bits = *word;
                while bits != 0 {
                    let b = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    if self.owner(32 * k + b).id == face.id {
                        odd = !odd;
                        *word &= !(1 << b);
                    }
                }
            }
            if odd {
                return face.id;
            }
        }
    }

    /// The scan-line method on a run covered by two or more faces. At a pixel the
    /// faces are taken in index order, as the Z-buffer receives them: a later face
    /// wins when nearer by more than a tie. The winner at the run's start holds
    /// until the winner changes, found by bisection (two planes along a row cross
    /// at most once). A face that is not planar ([`ActiveFace::bend`]) takes the
    /// depth of its fan triangle at the pixel (with its plane's tie margin) where its
    /// plane, off by up to its bend, could decide otherwise; a fan depth is
    /// piecewise, so a run with such a face is decided pixel by pixel. Where one
    /// face is nearer than the others by their ranges alone ([`nearest_by_range`]),
    /// no depth is taken. Every pixel thus gets the same face however the run was
    /// cut (the two row representations cut runs at different places).
    // Indexing: n < 8 = cover.len() before an insertion (checked), and i <= n.
    #[allow(clippy::indexing_slicing)]
    pub(super) fn resolve_overlap(
        &self,
        row: &RowFaces<'_>,
        xa: u16,
        xb: u16,
        out: &mut [u16],
    ) -> u32 {
        // The covering faces in index order (insertion: a few faces).
        let mut cover = [&NO_FACE; 8];
        let mut n = 0;
        let mut fits = true;
        let mut bent = false;
        self.each_covering(|_, face| {
            bent |= face.bend > 0;
            if n == cover.len() {
                fits = false;
                return;
            }
            let mut i = n;
            while i > 0 && cover[i - 1].id > face.id {
                cover[i] = cover[i - 1];
                i -= 1;
            }
            cover[i] = face;
            n += 1;
        });
        let cover = &cover[..n];
        if fits {
            if let Some(id) = nearest_by_range(cover) {
                if let Some(run) = out.get_mut(usize::from(xa)..usize::from(xb)) {
                    run.fill(id);
                }
                return 1;
            }
        }
        let winner = |x: u16| -> u16 {
            if !fits {
                return self.nearest_one_by_one(row, x);
            }
            let mut at = [0u32; 8];
            for (q, face) in at.iter_mut().zip(cover) {
                *q = face.plane.at(x);
            }
            // A fan triangle is within its face's bend of the plane (plus the
            // rounding): where every gap to a bent face is wider than both bends and
            // the tie, the planes decide as the fan triangles would.
            if bent && !planes_decide(cover, &at) {
                for (q, face) in at.iter_mut().zip(cover) {
                    if face.bend > 0 {
                        if let Some(fan) = row.fan_depth(usize::from(face.id - 1), x) {
                            *q = fan;
                        }
                    }
                }
            }
            let mut nearest = Nearest::NONE;
            for (&q, face) in at.iter().zip(cover) {
                nearest.offer(face, q);
            }
            nearest.id
        };
        let mut runs = 0;
        let mut x = xa;
        while x < xb {
            let id = winner(x);
            let last = xb - 1;
            let mut end = xb;
            if bent {
                // A fan depth is piecewise (a fan triangle each, the nearest where
                // they overlap): the winner can change more than once along the run,
                // so each pixel is asked (bisection would depend on where the run
                // was cut, and the two row representations cut runs apart).
                end = x + 1;
                while end < xb && winner(end) == id {
                    end += 1;
                }
            } else if last > x && winner(last) != id {
                let (mut lo, mut hi) = (x, last);
                while hi - lo > 1 {
                    let mid = lo + (hi - lo) / 2;
                    if winner(mid) == id {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                end = hi;
            }
            if let Some(run) = out.get_mut(usize::from(x)..usize::from(end)) {
                run.fill(id);
            }
            runs += 1;
            x = end;
        }
        runs
    }

    /// The nearest face at pixel `x` when more faces cover it than
    /// `resolve_overlap` holds: taken in index order one by one, each with the
    /// depth of its fan triangle where it is not planar.
    fn nearest_one_by_one(&self, row: &RowFaces<'_>, x: u16) -> u16 {
        let (mut nearest, mut after) = (Nearest::NONE, 0u16);
        loop {
            let mut next: Option<&ActiveFace> = None;
            self.each_covering(|_, face| {
                if face.id > after && next.is_none_or(|f| face.id < f.id) {
                    next = Some(face);
                }
            });
            let Some(face) = next else {
                return nearest.id;
            };
            after = face.id;
            let fan = (face.bend > 0)
                .then(|| row.fan_depth(usize::from(face.id - 1), x))
                .flatten();
            nearest.offer(face, fan.unwrap_or_else(|| face.plane.at(x)));
        }
    }

    /// Calls `f` on each face whose bit is set in the code, with its slot in the
    /// face table.
    // Indexing: trailing_zeros of a non-zero u32 is < 32 on [u16; 32].
    #[allow(clippy::indexing_slicing)]
    pub(super) fn each_covering<'a>(&'a self, mut f: impl FnMut(u16, &'a ActiveFace)) {
        for (owners, &word) in self.owner.iter().zip(self.code.iter()) {
            let mut bits = word;
            while bits != 0 {
                let slot = owners[bits.trailing_zeros() as usize];
                bits &= bits - 1;
                f(slot, self.faces.get(usize::from(slot)).unwrap_or(&NO_FACE));
            }
        }
    }
}

/// The nearest face so far at one pixel, the faces offered in index order as the
/// Z-buffer receives them: a later face wins when nearer by more than its tie.
struct Nearest {
    /// 1 + face index, 0 for none yet.
    id: u16,
    q: u32,
}

impl Nearest {
    const NONE: Self = Self { id: 0, q: 0 };

    fn offer(&mut self, face: &ActiveFace, q: u32) {
        if self.id == 0 || q > self.q.saturating_add(face.plane.tie) {
            (self.id, self.q) = (face.id, q);
        }
    }
}

/// The face that wins at every pixel of a run, when its range of nearness lies
/// above every other covering face's by more than its tie; `None` otherwise.
/// Offered in index order ([`Nearest`]), that face takes a pixel from any face
/// before it and keeps it from any after, whatever the depths: a face's depth at a
/// pixel lies in its range, whether its plane's (clamped to its polygon's vertices)
/// or its fan triangle's (clamped to the corners, which for a face wholly in view
/// are its polygon's vertices). A clipped face that is not planar (`bend` is
/// `u32::MAX`) has corners outside its polygon: no answer then.
fn nearest_by_range(cover: &[&ActiveFace]) -> Option<u16> {
    let mut w = *cover.first()?;
    let mut clipped_bent = false;
    for f in cover {
        if f.plane.min_q() > w.plane.min_q() {
            w = f;
        }
        clipped_bent |= f.bend == u32::MAX;
    }
    let (floor, tie) = (u64::from(w.plane.min_q()), u64::from(w.plane.tie));
    // Two faces of equal floor both fail the test, whichever is `w`.
    let above = |f: &&ActiveFace| core::ptr::eq(*f, w) || u64::from(f.plane.max_q()) + tie < floor;
    (!clipped_bent && cover.iter().all(above)).then_some(w.id)
}

/// Whether the planes' depths `at` of the faces `cover` decide as any depths within
/// their bends would: every gap between two faces, one of them bent, is wider than
/// their bends, the larger tie and the rounding.
fn planes_decide(cover: &[&ActiveFace], at: &[u32]) -> bool {
    let faces = cover.iter().zip(at);
    faces.clone().enumerate().all(|(i, (fi, &qi))| {
        faces.clone().skip(i + 1).all(|(fj, &qj)| {
            let bends = fi.bend.saturating_add(fj.bend);
            let tie = fi.plane.tie.max(fj.plane.tie);
            bends == 0 || qi.abs_diff(qj) > bends.saturating_add(tie).saturating_add(ROUNDING)
        })
    })
}

/// What `resolve_overlap` needs to find a fan triangle's depth on the current row.
#[derive(Debug, Clone, Copy)]
pub(super) struct RowFaces<'a> {
    pub mesh: &'a Mesh<'a>,
    pub vertices: &'a [ProjectedVertex],
    pub s: u32,
    pub y: u16,
}

impl<'a> RowFaces<'a> {
    /// Row `y` of the surfaces `fill`, whose vertices are `vertices`.
    pub fn new(
        ctx: &FrameCtx<'_, '_>,
        fill: &Surfaces<'a>,
        vertices: &'a [ProjectedVertex],
        y: u16,
    ) -> Self {
        Self {
            mesh: fill.mesh,
            vertices,
            s: ctx.s,
            y,
        }
    }

    /// See [`fan_depth_at`].
    fn fan_depth(&self, f: usize, x: u16) -> Option<u32> {
        fan_depth_at(self.mesh, self.vertices, f, self.s, (x, self.y))
    }
}

#[cfg(test)]
mod tests {
    use super::{nearest_by_range, ActiveFace, Nearest, NO_FACE};
    use crate::render::depth::plane::DepthPlane;
    use crate::render::transform::ScreenVertex;

    /// xorshift, so a failure can be replayed.
    struct Dice(u64);

    impl Dice {
        fn below(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0 % n
        }
    }

    /// A triangle face over a 64-pixel-wide row, S = 4, its nearness around `base`.
    fn face(dice: &mut Dice, id: u16, base: u32) -> Option<ActiveFace> {
        let mut corner = || ScreenVertex {
            x: dice.below(64 << 4) as i32,
            y: dice.below(16 << 4) as i32,
            q: base + dice.below(1 << 20) as u32,
        };
        let poly = [corner(), corner(), corner()];
        let plane = DepthPlane::new(&poly, 4)?.row_plane(dice.below(16) as u16);
        let bend = match dice.below(4) {
            0 => u32::MAX,
            1 => dice.below(1 << 12) as u32,
            _ => 0,
        };
        Some(ActiveFace {
            id,
            bend,
            plane,
            ..NO_FACE
        })
    }

    /// Rule: where `nearest_by_range` names a face, the per-pixel method (faces
    /// offered in index order) names it too at every pixel of the run, from the
    /// planes there and from any depths within the faces' ranges (as fan triangles
    /// give); a clipped face that is not planar is never decided by ranges.
    #[test]
    fn a_run_decided_by_ranges_is_every_pixels_nearest() {
        let mut dice = Dice(0x9E37_79B9_7F4A_7C15);
        let (mut decided, mut undecided) = (0, 0);
        for _ in 0..4000 {
            let n = 2 + dice.below(3) as usize;
            let mut faces = [NO_FACE; 4];
            let mut made = 0;
            for _ in 0..n {
                let base = (1 << 24) + (dice.below(4) as u32) * (3 << 19);
                if let Some(f) = face(&mut dice, 1 + made as u16, base) {
                    faces[made] = f;
                    made += 1;
                }
            }
            let cover: [&ActiveFace; 4] = [&faces[0], &faces[1], &faces[2], &faces[3]];
            let cover = &cover[..made];
            let Some(id) = nearest_by_range(cover) else {
                undecided += 1;
                continue;
            };
            decided += 1;
            assert!(cover.iter().all(|f| f.bend != u32::MAX));
            for x in 0..64u16 {
                let mut by_plane = Nearest::NONE;
                let mut by_any = Nearest::NONE;
                for f in cover {
                    by_plane.offer(f, f.plane.at(x));
                    let (lo, hi) = (f.plane.min_q(), f.plane.max_q());
                    let q = lo + dice.below(u64::from(hi - lo) + 1) as u32;
                    by_any.offer(f, q);
                }
                assert_eq!((by_plane.id, by_any.id), (id, id));
            }
        }
        // Both outcomes are exercised, so the rule is tested, not skipped.
        assert!(decided > 500 && undecided > 500, "{decided} / {undecided}");
    }
}
