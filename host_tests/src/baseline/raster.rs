//! The paper's per-pixel test: fan triangles and DDA edges into the frame buffers.

use super::pattern::PatternTable;
use crate::frame::ModeSpec;

/// The buffers of the paper plus the id buffer.
pub(super) struct Buffers {
    pub(super) w: usize,
    pub(super) h: usize,
    pub(super) depth: Vec<f32>,
    pub(super) ids: Vec<u32>,
    pub(super) frame: Vec<u8>,
    pub(super) lines: Vec<u8>,
}

/// Rasterizes one screen triangle (x, y, depth) as an interior of face `id`.
pub(super) fn raster_triangle(
    b: &mut Buffers,
    tri: [[f32; 3]; 3],
    id: u32,
    pattern: &PatternTable,
    erase: bool,
) {
    let [p0, mut p1, mut p2] = tri;
    let area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
    if area == 0.0 || !area.is_finite() {
        return;
    }
    if area < 0.0 {
        std::mem::swap(&mut p1, &mut p2);
    }
    let area = area.abs();
    let min_x = p0[0].min(p1[0]).min(p2[0]);
    let max_x = p0[0].max(p1[0]).max(p2[0]);
    let min_y = p0[1].min(p1[1]).min(p2[1]);
    let max_y = p0[1].max(p1[1]).max(p2[1]);
    // Pixel centres i + 0.5 in [min, max].
    let x0 = ((min_x - 0.5).ceil().max(0.0)) as usize;
    let x1 = ((max_x - 0.5).floor().min(b.w as f32 - 1.0)) as isize;
    let y0 = ((min_y - 0.5).ceil().max(0.0)) as usize;
    let y1 = ((max_y - 0.5).floor().min(b.h as f32 - 1.0)) as isize;
    if x1 < x0 as isize || y1 < y0 as isize {
        return;
    }
    let (x1, y1) = (x1 as usize, y1 as usize);
    // Edge function of a -> b, positive inside; (A, B, C): E = A x + B y + C.
    let edge = |a: [f32; 3], c: [f32; 3]| {
        let (dx, dy) = (c[0] - a[0], c[1] - a[1]);
        let top_left = dy < 0.0 || (dy == 0.0 && dx > 0.0);
        (-dy, dx, dy * a[0] - dx * a[1], top_left)
    };
    let e = [edge(p1, p2), edge(p2, p0), edge(p0, p1)];
    // Depth plane: d = d0 * w0 + d1 * w1 + d2 * w2 with w the normalized edge values.
    let inv = 1.0 / area;
    let (da, db, dc) = (p0[2], p1[2], p2[2]);
    let ddx = (e[0].0 * da + e[1].0 * db + e[2].0 * dc) * inv;
    let ddy = (e[0].1 * da + e[1].1 * db + e[2].1 * dc) * inv;
    let dd0 = (e[0].2 * da + e[1].2 * db + e[2].2 * dc) * inv;
    let inside = |v: f32, tl: bool| v > 0.0 || (v == 0.0 && tl);
    for y in y0..=y1 {
        let cy = y as f32 + 0.5;
        let cx = x0 as f32 + 0.5;
        let mut w0 = e[0].0 * cx + e[0].1 * cy + e[0].2;
        let mut w1 = e[1].0 * cx + e[1].1 * cy + e[1].2;
        let mut w2 = e[2].0 * cx + e[2].1 * cy + e[2].2;
        let mut d = dd0 + ddx * cx + ddy * cy;
        let row = y * b.w;
        for x in x0..=x1 {
            if inside(w0, e[0].3) && inside(w1, e[1].3) && inside(w2, e[2].3) {
                let i = row + x;
                // The paper's this_Algorithm for an interior pixel (nearer = smaller d).
                if d < b.depth[i] {
                    b.depth[i] = d;
                    b.ids[i] = id + 1;
                    if erase && pattern.value(x, y) == 0 {
                        b.frame[i] = 0;
                    }
                }
            }
            w0 += e[0].0;
            w1 += e[1].0;
            w2 += e[2].0;
            d += ddx;
        }
    }
}

/// DDA along a screen segment: one pixel per centre along the major axis; each pixel
/// goes through the paper's boundary-pixel test.
pub(super) fn draw_edge(
    b: &mut Buffers,
    s0: [f32; 3],
    s1: [f32; 3],
    own: &[u32],
    pattern: &PatternTable,
    mode: ModeSpec,
    eps: f32,
) {
    let (dx, dy) = (s1[0] - s0[0], s1[1] - s0[1]);
    let x_major = dx.abs() >= dy.abs();
    let (a0, a1, len) = if x_major {
        (s0[0], s1[0], dx)
    } else {
        (s0[1], s1[1], dy)
    };
    if len == 0.0 || !len.is_finite() {
        return;
    }
    let limit = if x_major { b.w } else { b.h } as f32;
    let lo = ((a0.min(a1) - 0.5).ceil().max(0.0)) as isize;
    let hi = ((a0.max(a1) - 0.5).floor().min(limit - 1.0)) as isize;
    if hi < lo {
        return;
    }
    let (minor0, dminor) = if x_major {
        (s0[1], dy / dx)
    } else {
        (s0[0], dx / dy)
    };
    let dd = (s1[2] - s0[2]) / len;
    let start = lo as f32 + 0.5 - a0;
    let mut m = minor0 + start * dminor;
    let mut d = s0[2] + start * dd;
    let other_limit = if x_major { b.h } else { b.w };
    let erase_on = matches!(mode, ModeSpec::Surfaces | ModeSpec::SurfacesDashed);
    for a in lo..=hi {
        let mf = m.floor();
        m += dminor;
        let dd_here = d;
        d += dd;
        if mf < 0.0 || mf >= other_limit as f32 {
            continue;
        }
        let (x, y) = if x_major {
            (a as usize, mf as usize)
        } else {
            (mf as usize, a as usize)
        };
        let i = y * b.w + x;
        let id = b.ids[i];
        let hidden = b.depth[i] < dd_here - eps && !(id != 0 && own.contains(&(id - 1)));
        let draw = match mode {
            ModeSpec::Wireframe => true,
            ModeSpec::Hidden | ModeSpec::Surfaces => !hidden,
            ModeSpec::Dashed | ModeSpec::SurfacesDashed => !hidden || pattern.value(x, y) != 0,
        };
        if hidden {
            if b.lines[i] == 0 {
                b.lines[i] = 2;
            }
        } else {
            b.lines[i] = 1;
        }
        if mode == ModeSpec::Surfaces {
            continue;
        }
        if draw {
            b.frame[i] = u8::from(!erase_on);
        }
    }
}
