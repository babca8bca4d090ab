//! The facet-row span kernels: a facet's span(s) in the current row depth-tested
//! into the row, then its chains and planes stepped a row. The row loop's fast
//! path, run once a facet-row.
//!
//! Two forms compute the very same bits. The portable one, in Rust, is the
//! specification: the host and every other target run it. On cores with Thumb-2
//! and the DSP extension (Cortex-M4, M7) the kernels are assembly (`kernel.s`,
//! one function a layout), because compiled Rust keeps more values live than
//! Thumb-2 has registers and spills them a facet-row (`../shared/KERNEL-STUDY.md`).
//! The crate's `build.rs` picks them by the target's name (`thumbv7em-*`), so that
//! stable toolchains, which report no Arm target feature to `cfg`, take them too
//! (`cfg(pbuffer_dsp_kernels)`; `PBUFFER_NO_KERNELS=1` builds the twin instead).
//! [`twin_mismatches`] runs both on random records and rows; `scripts/firmware`
//! runs it under QEMU, checks by symbol that the M4 examples link the kernels, and
//! the firmware's frame hashes equal the host's.

use super::super::depth_row::cells;
use super::{Facet, Layout};

impl Facet {
    /// The span between the two chains' crossings, then both step a row and the
    /// depth a row: the row loop's fast path, when [`holds`](Self::holds). The
    /// layout picks a kernel with no field selected at run time.
    #[inline(always)]
    pub fn fill_span_row(&mut self, row: &mut [u32]) -> u32 {
        #[cfg(pbuffer_dsp_kernels)]
        {
            thumb::fill_span_row(self, row)
        }
        #[cfg(not(pbuffer_dsp_kernels))]
        {
            self.fill_span_row_portable(row)
        }
    }

    /// [`fill_span_row`](Self::fill_span_row) in Rust: the specification.
    #[inline(always)]
    pub(crate) fn fill_span_row_portable(&mut self, row: &mut [u32]) -> u32 {
        // Each layout its own copy: no select of fields at run time.
        match self.layout {
            Layout::First => self.fill_one::<false>(row),
            Layout::Second => self.fill_one::<true>(row),
            Layout::FirstLeft => self.fill_split_row::<false>(row),
            Layout::FirstRight => self.fill_split_row::<true>(row),
        }
    }

    /// One span with the first plane (`SECOND`: the second). Out of line, so
    /// that its few values stay in registers.
    #[inline(never)]
    fn fill_one<const SECOND: bool>(&mut self, row: &mut [u32]) -> u32 {
        let (lx, rx) = (self.left.x, self.right.x);
        let (d, a) = if SECOND {
            (self.drow2, self.a2)
        } else {
            (self.drow, self.a)
        };
        self.left.next_row();
        self.right.next_row();
        self.step_planes();
        let (l, r) = (lx >> 16, rx >> 16);
        let id = 0xFFFF - u32::from(self.face);
        super::run(row, l.min(r), l.max(r), d, a, id, self.tie)
    }

    /// A quad split at its diagonal: two spans, a plane each, the first plane's
    /// on the left (`SWAP`: on the right). Out of line, apart from the one-plane
    /// rows' registers.
    #[inline(never)]
    fn fill_split_row<const SWAP: bool>(&mut self, row: &mut [u32]) -> u32 {
        let (l, r) = (self.left.pixel(), self.right.pixel());
        let xd = self.diag.pixel();
        let ((d, a), (d2, a2)) = if SWAP {
            ((self.drow2, self.a2), (self.drow, self.a))
        } else {
            ((self.drow, self.a), (self.drow2, self.a2))
        };
        let (id, tie) = (0xFFFF - u32::from(self.face), self.tie);
        self.diag.next_row();
        self.left.next_row();
        self.right.next_row();
        self.step_planes();
        // Both spans clamped to the row at once, then cut at the diagonal.
        let x0 = l.min(r).max(0);
        let x1 = l.max(r).min(row.len() as i32);
        if x0 >= x1 {
            return 0;
        }
        let xd = xd.clamp(x0, x1);
        let (one, two) = row
            .get_mut(x0 as usize..x1 as usize)
            .unwrap_or_default()
            .split_at_mut((xd - x0) as usize);
        let spans = u32::from(!one.is_empty()) + u32::from(!two.is_empty());
        cells(one, d.wrapping_add(a.wrapping_mul(x0) as u32), a, id, tie);
        cells(
            two,
            d2.wrapping_add(a2.wrapping_mul(xd) as u32),
            a2,
            id,
            tie,
        );
        spans
    }
}

/// The assembly kernels (Thumb-2 with DSP) and their one entry point.
#[cfg(pbuffer_dsp_kernels)]
#[allow(unsafe_code)]
mod thumb {
    use core::mem::offset_of;

    use super::super::super::step::EdgeStep;
    use super::{Facet, Layout};

    // Each kernel: r0 the facet, r1 the row's first cell, r2 the row's length;
    // returns the spans filled (r0). AAPCS: r4-r11 saved and restored.
    core::arch::global_asm!(
        include_str!("kernel.s"),
        LX = const offset_of!(Facet, left) + offset_of!(EdgeStep, x),
        RX = const offset_of!(Facet, right) + offset_of!(EdgeStep, x),
        DX = const offset_of!(Facet, diag) + offset_of!(EdgeStep, x),
        DROW = const offset_of!(Facet, drow),
        DROW2 = const offset_of!(Facet, drow2),
        A = const offset_of!(Facet, a),
        A2 = const offset_of!(Facet, a2),
        TIE = const offset_of!(Facet, tie),
        FACE = const offset_of!(Facet, face),
    );

    // The stepped pairs are read as double words: each second field follows its
    // first (`x, dx`; `drow, b`).
    const _: () = {
        assert!(offset_of!(EdgeStep, dx) == offset_of!(EdgeStep, x) + 4);
        assert!(offset_of!(Facet, b) == offset_of!(Facet, drow) + 4);
        assert!(offset_of!(Facet, b2) == offset_of!(Facet, drow2) + 4);
    };

    extern "C" {
        fn pbuffer_fill_one_first(facet: *mut u8, row: *mut u32, len: usize) -> u32;
        fn pbuffer_fill_one_second(facet: *mut u8, row: *mut u32, len: usize) -> u32;
        fn pbuffer_fill_split_first_left(facet: *mut u8, row: *mut u32, len: usize) -> u32;
        fn pbuffer_fill_split_first_right(facet: *mut u8, row: *mut u32, len: usize) -> u32;
    }

    /// [`Facet::fill_span_row`] in assembly.
    #[inline(always)]
    pub(super) fn fill_span_row(facet: &mut Facet, row: &mut [u32]) -> u32 {
        let kernel = match facet.layout {
            Layout::First => pbuffer_fill_one_first,
            Layout::Second => pbuffer_fill_one_second,
            Layout::FirstLeft => pbuffer_fill_split_first_left,
            Layout::FirstRight => pbuffer_fill_split_first_right,
        };
        // SAFETY: the kernel reads and writes the facet's fields only at the
        // `offset_of!` offsets above (`facet` is a unique `&mut`), and writes the
        // row's cells only in `x0..x1`, where it clamps `0 <= x0 <= x1 <= len`
        // (signed compares; a slice's length is below 2^31 here, as the row's is
        // at most the guard box's 4,096 px). It keeps the AAPCS: r4-r11 and the
        // stack are restored, and it touches no other memory.
        unsafe { kernel((facet as *mut Facet).cast(), row.as_mut_ptr(), row.len()) }
    }
}

/// Runs `rounds` random facet-rows through both forms of the span kernel (the
/// assembly one where the target has it, else the portable one twice) and
/// returns how many differed: in the row, the record, or the spans returned.
/// Rows of `width` cells (at most 256); records with spans partly outside the
/// row, diagonals anywhere, every layout.
pub fn twin_mismatches(seed: u32, rounds: u32, width: usize) -> u32 {
    let mut rng = Random(seed | 1);
    let width = width.min(MOST);
    let mut bad = 0;
    for _ in 0..rounds {
        let (mut f, mut row) = rng.facet_row(width);
        let (mut f2, mut row2) = (f, row);
        let cells = row.get_mut(..width).unwrap_or_default();
        let cells2 = row2.get_mut(..width).unwrap_or_default();
        let spans = f.fill_span_row(cells);
        let spans2 = f2.fill_span_row_portable(cells2);
        bad += u32::from(spans != spans2 || f != f2 || row != row2);
    }
    bad
}

/// The widest row [`twin_mismatches`] draws (on the stack twice).
const MOST: usize = 256;

/// xorshift32.
struct Random(u32);

impl Random {
    fn next(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }

    /// A record and a row: every other one with flat planes and cells one off,
    /// on or one under their entries (the compare's boundary).
    fn facet_row(&mut self, width: usize) -> (Facet, [u32; MOST]) {
        let mut f = Facet::EMPTY;
        let w = width as u32 + 64;
        let mut x = || ((self.next() % w) as i32 - 32) << 16 | (self.next() & 0xFFFF) as i32;
        (f.left.x, f.right.x, f.diag.x) = (x(), x(), x());
        let mut step = || (self.next() as i32) >> 12;
        (f.left.dx, f.right.dx, f.diag.dx) = (step(), step(), step());
        (f.drow, f.drow2) = (self.next(), self.next());
        let mut word = || self.next() as i32;
        (f.b, f.b2, f.a, f.a2) = (word(), word(), word(), word());
        f.tie = self.next() >> 9;
        f.face = self.next() as u16;
        f.layout = match self.next() % 4 {
            0 => Layout::First,
            1 => Layout::Second,
            2 => Layout::FirstLeft,
            _ => Layout::FirstRight,
        };
        let close = self.next() % 2 == 0;
        if close {
            (f.a, f.a2, f.drow2) = (0, 0, f.drow);
        }
        let id = 0xFFFF - u32::from(f.face);
        let entry = (f.drow.wrapping_sub(f.tie) & 0xFFFF_0000) | id;
        let mut row = [0u32; MOST];
        for c in row.iter_mut() {
            *c = match self.next() % 4 {
                0 => 0,
                _ if close => entry.wrapping_add(self.next() % 3).wrapping_sub(1),
                _ => self.next(),
            };
        }
        (f, row)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kernel read cell by cell from its specification: the span between
    /// the chains' pixels clamped to the row; left of the diagonal the first
    /// plane (`FirstLeft`) or the second (`FirstRight`); a cell takes the entry
    /// `(depth - tie) & 0xFFFF0000 | (0xFFFF - face)`, plus the tie, when greater.
    fn cell_by_cell(f: &Facet, row: &mut [u32]) -> (Facet, u32) {
        let (l, r, xd) = (f.left.x >> 16, f.right.x >> 16, f.diag.x >> 16);
        let (x0, x1) = (l.min(r).max(0), l.max(r).min(row.len() as i32));
        let split = matches!(f.layout, Layout::FirstLeft | Layout::FirstRight);
        let xd = if x0 < x1 { xd.clamp(x0, x1) } else { xd };
        let first = (f.drow, f.a);
        let second = (f.drow2, f.a2);
        for x in x0..x1 {
            let (d, a) = match f.layout {
                Layout::First => first,
                Layout::Second => second,
                Layout::FirstLeft if x < xd => first,
                Layout::FirstLeft => second,
                Layout::FirstRight if x < xd => second,
                Layout::FirstRight => first,
            };
            let depth = d.wrapping_add(a.wrapping_mul(x) as u32).wrapping_sub(f.tie);
            let entry = depth & 0xFFFF_0000 | (0xFFFF - u32::from(f.face));
            let cell = &mut row[x as usize];
            if entry > *cell {
                *cell = entry.wrapping_add(f.tie);
            }
        }
        let spans = match (x0 < x1, split) {
            (false, _) => 0,
            (true, false) => 1,
            (true, true) => u32::from(x0 < xd) + u32::from(xd < x1),
        };
        let mut g = *f;
        g.left.x = g.left.x.wrapping_add(g.left.dx);
        g.right.x = g.right.x.wrapping_add(g.right.dx);
        if split {
            g.diag.x = g.diag.x.wrapping_add(g.diag.dx);
        }
        g.drow = g.drow.wrapping_add(g.b as u32);
        g.drow2 = g.drow2.wrapping_add(g.b2 as u32);
        (g, spans)
    }

    #[test]
    fn the_portable_kernel_is_its_cell_by_cell_specification() {
        let mut rng = Random(20261128);
        for width in [1, 7, 40, 256] {
            for _ in 0..3000 {
                let (mut f, mut row) = rng.facet_row(width);
                let mut expected = row;
                let (g, spans) = cell_by_cell(&f, &mut expected[..width]);
                assert_eq!(f.fill_span_row_portable(&mut row[..width]), spans);
                assert_eq!((f, row), (g, expected));
            }
        }
    }
}
