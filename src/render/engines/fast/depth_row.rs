//! One row of nearest-face entries, `depth << 16 | (0xFFFF - face)`: the depth
//! test of a facet's span (one unsigned compare a pixel) and the row's clearing.

/// Depth-tests pixels `x0..x1` of `row` (clamped to it) against the entries of a
/// plane at `drow` (column 0) stepping `a` a pixel: 1 when any pixel was tested.
#[inline(always)]
pub(super) fn run(row: &mut [u32], x0: i32, x1: i32, drow: u32, a: i32, id: u32, tie: u32) -> u32 {
    let x0 = x0.max(0);
    let x1 = x1.min(row.len() as i32);
    if x0 >= x1 {
        return 0;
    }
    let d = drow.wrapping_add(a.wrapping_mul(x0) as u32);
    // x0 < x1 <= row.len(): the range is in bounds.
    cells(
        row.get_mut(x0 as usize..x1 as usize).unwrap_or_default(),
        d,
        a,
        id,
        tie,
    );
    1
}

/// Depth-tests `row_cells`, the first at depth `d`, stepping `a` a pixel. Most
/// spans of a small mesh are one or two pixels: those need no loop.
#[inline(always)]
pub(super) fn cells(row_cells: &mut [u32], d: u32, a: i32, id: u32, tie: u32) {
    match row_cells {
        [] => {}
        [c] => take(c, d.wrapping_sub(tie), id, tie),
        [c0, c1] => {
            let behind = d.wrapping_sub(tie);
            take(c0, behind, id, tie);
            take(c1, behind.wrapping_add(a as u32), id, tie);
        }
        more => depth_span(more, d, a as u32, id, tie),
    }
}

/// Depth-tests one cell against the entry made from `behind` (the depth minus the
/// tie): see [`depth_span`].
#[inline(always)]
fn take(c: &mut u32, behind: u32, id: u32, tie: u32) {
    let e = (behind & 0xFFFF_0000) | id;
    if e > *c {
        *c = e.wrapping_add(tie);
    }
}

/// Depth-tests `cells` against the facet entries `(d & 0xFFFF_0000) | id`, `d`
/// stepping by `a` a pixel. The row's facets come in the order of their face
/// index, so the nearest so far has a lower (or the same) index: the facet takes a
/// pixel only when nearer by more than its `tie`, and one compare a pixel does it.
#[inline(always)]
fn depth_span(cells: &mut [u32], d: u32, a: u32, id: u32, tie: u32) {
    // Depths lie in 2^24..2^32 - 2^24 and the tie below 2^23: no wrap. The tie is
    // whole depth units, so `(d & 0xFFFF_0000) | id` is the compared entry plus
    // the tie.
    let mut behind = d.wrapping_sub(tie);
    let mut pairs = cells.chunks_exact_mut(2);
    for pair in &mut pairs {
        if let [c0, c1] = pair {
            let e0 = (behind & 0xFFFF_0000) | id;
            let e1 = (behind.wrapping_add(a) & 0xFFFF_0000) | id;
            if e0 > *c0 {
                *c0 = e0.wrapping_add(tie);
            }
            if e1 > *c1 {
                *c1 = e1.wrapping_add(tie);
            }
            behind = behind.wrapping_add(a.wrapping_mul(2));
        }
    }
    if let [c] = pairs.into_remainder() {
        let e = (behind & 0xFFFF_0000) | id;
        if e > *c {
            *c = e.wrapping_add(tie);
        }
    }
}

/// Clears a row of nearest-face entries (0: none) or of line mask words, eight
/// words a store run (the library's `memset` is slower on the Cortex-M4: the
/// masks' `fill(0)` cost suzanne's frame 1.3 %, measured).
pub(super) fn clear_row(row: &mut [u32]) {
    let mut chunks = row.chunks_exact_mut(8);
    for chunk in &mut chunks {
        chunk.copy_from_slice(&[0; 8]);
    }
    for cell in chunks.into_remainder() {
        *cell = 0;
    }
}
