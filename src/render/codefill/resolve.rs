//! Runs of pixels from the surface code: no face, one face, or the scan-line method
//! where two or more faces overlap.

use fixed::types::extra::LeEqU32;

use super::{ActiveFace, CodeFillRenderer, NO_FACE};

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
    pub(super) fn resolve(&self, xa: u16, xb: u16, out: &mut [u16]) -> u32 {
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
            _ => self.resolve_overlap(xa, xb, out),
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
    /// at most once).
    // Indexing: n < 8 = by_id.len() before an insertion (checked), and i <= n.
    #[allow(clippy::indexing_slicing)]
    pub(super) fn resolve_overlap(&self, xa: u16, xb: u16, out: &mut [u16]) -> u32 {
        // The covering faces in index order (insertion: a few faces), as slots of
        // the face table.
        let mut by_id = [(0u16, 0u16); 8];
        let mut n = 0;
        let mut fits = true;
        self.each_covering(|slot, face| {
            if n == by_id.len() {
                fits = false;
                return;
            }
            let mut i = n;
            while i > 0 && by_id[i - 1].0 > face.id {
                by_id[i] = by_id[i - 1];
                i -= 1;
            }
            by_id[i] = (face.id, slot);
            n += 1;
        });
        let faces = &self.faces;
        let winner = |x: u16| -> u16 {
            let (mut best, mut q, mut after) = (0u16, 0u32, 0u16);
            let mut take = |face: &ActiveFace| {
                let qf = face.plane.at(x);
                if best == 0 || qf > q.saturating_add(face.plane.tie) {
                    (best, q) = (face.id, qf);
                }
            };
            if fits {
                for &(_, slot) in by_id.iter().take(n) {
                    if let Some(face) = faces.get(usize::from(slot)) {
                        take(face);
                    }
                }
                return best;
            }
            // More than eight faces: take them in index order one by one.
            loop {
                let mut next: Option<&ActiveFace> = None;
                self.each_covering(|_, face| {
                    if face.id > after && next.is_none_or(|f| face.id < f.id) {
                        next = Some(face);
                    }
                });
                let Some(face) = next else { return best };
                after = face.id;
                take(face);
            }
        };
        let mut runs = 0;
        let mut x = xa;
        while x < xb {
            let id = winner(x);
            let last = xb - 1;
            let mut end = xb;
            if last > x && winner(last) != id {
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
