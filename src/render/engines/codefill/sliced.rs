//! The other row representation: the surface code of every pixel, in machine words.
//! Each face active on the row holds one bit for the whole row (its place in the
//! active list); each of its crossings XORs that bit into the code of the crossing's
//! pixel, and a running XOR from the left, a word at a time, gives every pixel's code.
//! A bit per pixel marks the pixels crossed, so the running XOR visits only those:
//! no sort, work in proportion to the crossings times the code's words, and the
//! code is as wide as the faces active on the row. The buffer is cleared as it is
//! read; the frame clears it once before its first row.

use fixed::types::extra::LeEqU32;

use super::resolve::RowFaces;
use super::{CodeFillRenderer, Surfaces};
use crate::render::transform::ProjectedVertex;
use crate::render::FrameCtx;
use crate::Capacity;
use crate::Error;

impl<
        Frac: LeEqU32,
        const WORDS: usize,
        const FACES: usize,
        const EDGES: usize,
        const POLY: usize,
    > CodeFillRenderer<Frac, WORDS, FACES, EDGES, POLY>
{
    /// As [`scan_row`](Self::scan_row), with the row's codes in `codes` (width x
    /// words per pixel, then a bit per pixel), all zero on entry and on return.
    // The frame, the surfaces, the vertex cache and the face order stay apart here
    // and in `scan_row`: passed as one struct, suzanne-scanline's M4 frame took
    // 0.6 % more instructions.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn scan_row_sliced(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        fill: &Surfaces<'_>,
        vertices: &[ProjectedVertex],
        order: &[u32],
        y: u16,
        out: &mut [u16],
        codes: &mut [u32],
    ) -> Result<u32, Error> {
        self.enter_row(ctx, fill, vertices, order, y)?;
        let faces = RowFaces::new(ctx, fill, vertices, y);
        // The code is as wide as the faces active on the row.
        self.widest = self.widest.max(self.live.len());
        let width = out.len();
        let words = self.live.len().div_ceil(32);
        if self.live.len() > Self::CODE_BITS {
            // The frame fails with the width it needs (see `render`).
            self.step_row();
            return Ok(0);
        }
        // The codes of the row's pixels, then one bit per pixel: a crossing there.
        let need = width * words + width.div_ceil(32);
        let Some(codes) = codes.get_mut(..need) else {
            return Err(Error::CapacityExceeded {
                what: Capacity::RowCodes,
                needed: need,
                capacity: codes.len(),
            });
        };
        let (codes, crossed) = codes.split_at_mut(width * words);
        for (bit, &slot) in self.live.iter().enumerate() {
            if let Some(face) = self.faces.get_mut(usize::from(slot)) {
                face.bit = bit as u16;
            }
            if let Some(owner) = self
                .owner
                .get_mut(bit / 32)
                .and_then(|o| o.get_mut(bit % 32))
            {
                *owner = slot;
            }
        }
        let row = i32::from(y);
        self.edges.set_row(row, ctx.s, width as u16);
        for k in 0..self.edges.len() {
            let Some(e) = self.edges.get(k) else { break };
            let x = usize::from(e.x);
            if e.edge.first > row || x >= width {
                continue;
            }
            let bit = self.faces.get(usize::from(e.face)).map_or(0, |f| f.bit);
            if let Some(word) = codes.get_mut(x * words + usize::from(bit / 32)) {
                *word ^= 1 << (bit % 32);
            }
            if let Some(word) = crossed.get_mut(x / 32) {
                *word |= 1 << (x % 32);
            }
        }
        // The running XOR over the pixels crossed only (work grows with the
        // crossings, not the width); each is cleared as it is read, so the buffer is
        // all zero again for the next row whatever its code width.
        self.code = [0; WORDS];
        self.inside = 0;
        let (mut xa, mut runs) = (0usize, 0u32);
        for (w, word) in crossed.iter_mut().enumerate() {
            let mut pixels = core::mem::take(word);
            while pixels != 0 {
                let x = 32 * w + pixels.trailing_zeros() as usize;
                pixels &= pixels - 1;
                let Some(toggles) = codes.get_mut(x * words..(x + 1) * words) else {
                    continue;
                };
                if toggles.iter().all(|&t| t == 0) {
                    continue;
                }
                if x > xa {
                    runs += self.resolve(&faces, xa as u16, x as u16, out);
                    xa = x;
                }
                // `resolve` tells only none, one and more apart (the code cannot
                // exceed its capacity here): no count of bits (no instruction for it
                // on a Cortex-M4).
                let (mut set, mut single) = (0, false);
                for (c, t) in self.code.iter_mut().zip(toggles.iter_mut()) {
                    *c ^= core::mem::take(t);
                    if *c != 0 {
                        set += 1;
                        single = *c & (*c - 1) == 0;
                    }
                }
                self.inside = match set {
                    0 => 0,
                    1 if single => 1,
                    _ => 2,
                };
            }
        }
        if xa < width {
            runs += self.resolve(&faces, xa as u16, width as u16, out);
        }
        self.step_row();
        Ok(runs)
    }
}
