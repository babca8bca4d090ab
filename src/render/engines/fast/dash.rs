//! Hidden lines dashed along each edge ([`Dashes::Along`]): the dash pattern is
//! measured in pixels along the edge from one end, the anchor (the edge's end
//! `a`, at its unclipped projected position), so the dashes do not crawl as the
//! model turns.
//!
//! A line's phase is kept in turns of the pattern, `2^-32` of a period a unit:
//! the phase at pixel centre `k` along the major axis is `at0 + k step`
//! (wrapping: the period is exactly `2^32`), so the line stepper decides a hidden
//! pixel with one multiply, one add and one compare, and the visible pixels pay
//! nothing. `step` is the Euclidean length of one pixel of the major axis,
//! `sqrt(1 + slope^2)` px, in turns.

use super::baked::BakedMesh;
use super::edge::CompactEdge;
use super::float_int::{to_i32, to_u32};
use super::view::{FastVertex, ScreenMap};
use crate::render::{Dashes, Settings};

/// One frame's dashes along the edges: the dash's share of the period, in turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Dashing {
    /// A pixel whose phase is below `on` is on a dash.
    pub on: u32,
    /// Dash plus gap, px (> 0).
    period: u32,
}

impl Dashing {
    /// The dashing of `settings`: `None` for the screen pattern. Dashes without
    /// a gap are solid: no pixel is in a gap.
    pub fn of(settings: &Settings) -> Option<Self> {
        match settings.dashes {
            Dashes::Screen => None,
            Dashes::Along { dash, gap: 0 } => Some(Self {
                on: SOLID,
                period: u32::from(dash).max(1),
            }),
            Dashes::Along { dash, gap } => {
                let period = u32::from(dash) + u32::from(gap);
                // 24 bits of the share are plenty (one 32-bit division a frame).
                let on = ((u32::from(dash) << 24) / period) << 8;
                Some(Self { on, period })
            }
        }
    }

    /// For the screen pattern's copy of the frame loop, which never reads it.
    pub const NONE: Self = Self { on: 0, period: 1 };
}

/// Line masks a row needs: visible and hidden, and the gaps with dashes along
/// the edges.
pub(super) const fn line_masks(along: bool) -> usize {
    if along {
        3
    } else {
        2
    }
}

/// The `on` of dashes without a gap (solid hidden lines).
const SOLID: u32 = u32::MAX;

/// A feature line's dash phase along its edge ([`Dashes::Along`]), in turns of
/// the dash pattern: `at0 + k step` at pixel centre `k` (wrapping). The fast
/// engine keeps one for each active line in
/// [`FastWorkspace::phases`](super::FastWorkspace::phases).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DashPhase {
    at0: u32,
    step: u32,
}

impl DashPhase {
    /// No dashes along the line (`step == 0`); also the value to fill a lent
    /// buffer with.
    pub const SCREEN: Self = Self { at0: 0, step: 0 };

    /// The phase of a line whose centre `k` lies at major coordinate `k + 1/2`
    /// px, with `ratio` px along the line a pixel of the major axis, anchored at
    /// major coordinate `anchor` px: the distance from the anchor grows with `k`
    /// when `grows`. `k1` is a centre near the line (its first), where the phase
    /// is set up in `f32` (the distance there is small when the anchor is on
    /// screen).
    pub(super) fn new(dashing: Dashing, anchor: f32, grows: bool, ratio: f32, k1: i32) -> Self {
        if dashing.on == SOLID {
            return Self::SCREEN;
        }
        let per = ratio / dashing.period as f32;
        let per = if grows { per } else { -per };
        let at1 = turns((k1 as f32 + 0.5 - anchor) * per);
        // A step of a whole number of periods (a zero gap) is not "no dashes".
        let step = turns(per).max(1);
        Self {
            at0: at1.wrapping_sub((k1 as u32).wrapping_mul(step)),
            step,
        }
    }

    /// Is the hidden pixel at centre `k` in a gap of the dashes (never with the
    /// screen pattern)?
    #[inline(always)]
    pub(super) fn in_gap(self, k: i32, on: u32) -> bool {
        self.step != 0 && self.at0.wrapping_add((k as u32).wrapping_mul(self.step)) >= on
    }
}

/// Where hidden pixels in the gaps of dashes along the edges are marked: a
/// type, so that the screen pattern's copy of the line loop has no dash work
/// (and the lines' records no phase).
pub(super) trait Gaps {
    /// The line at `i` of the active lines is drawn next.
    fn line(&mut self, i: usize);
    /// The line at `i` ended: the last, at `last`, takes its place.
    fn remove(&mut self, i: usize, last: usize);
    /// Marks the current line's hidden pixel at centre `k` (column `x`) when it
    /// is in a gap.
    fn mark(&mut self, k: i32, x: usize);
}

/// The screen pattern: no gaps.
pub(super) struct NoGaps;

impl Gaps for NoGaps {
    #[inline(always)]
    fn line(&mut self, _: usize) {}
    #[inline(always)]
    fn remove(&mut self, _: usize, _: usize) {}
    #[inline(always)]
    fn mark(&mut self, _: i32, _: usize) {}
}

/// Dashes along the edges: the row's gap mask, the frame's [`Dashing::on`], the
/// active lines' phases (in the lines' order) and the current line's index
/// (its phase is read only for its hidden pixels).
pub(super) struct GapMask<'a> {
    pub words: &'a mut [u32],
    pub on: u32,
    pub phases: &'a mut [DashPhase],
    pub line: usize,
}

impl Gaps for GapMask<'_> {
    #[inline(always)]
    fn line(&mut self, i: usize) {
        self.line = i;
    }
    #[inline(always)]
    fn remove(&mut self, i: usize, last: usize) {
        if let Some(&p) = self.phases.get(last) {
            if let Some(slot) = self.phases.get_mut(i) {
                *slot = p;
            }
        }
    }
    #[inline(always)]
    fn mark(&mut self, k: i32, x: usize) {
        let phase = self.phases.get(self.line).copied();
        if phase.is_some_and(|p| p.in_gap(k, self.on)) {
            if let Some(w) = self.words.get_mut(x / 32) {
                *w |= 1 << (x % 32);
            }
        }
    }
}

/// The fractional part of `x` (`x - floor(x)`) in `2^-32` units; 0 when `x` has
/// no fractional bits in `f32` (or is not finite).
fn turns(x: f32) -> u32 {
    if !x.is_finite() || x.abs() >= 8_388_608.0 {
        return 0;
    }
    let i = to_i32(x);
    let mut f = x - i as f32;
    if f < 0.0 {
        f += 1.0;
    }
    // f32 to u32 is one instruction on an FPU; the lowest bit is not kept.
    to_u32(f * 2_147_483_648.0) << 1
}

/// The anchor of `edge`'s dashes, `2^-S` px: its end `a` as the vertex cache has
/// it (`cached`), or, when that end is clipped, its projection (on the line beyond
/// the clipped end), or, when it lies behind the near plane (no projection), the
/// clipped end on its side (`clipped`: there the dashes move with the near plane).
pub(super) fn anchor(
    map: &ScreenMap,
    baked: &BakedMesh<'_>,
    edge: &CompactEdge,
    cached: FastVertex,
    clipped: FastVertex,
) -> (f32, f32) {
    if cached.inside() {
        return (f32::from(cached.x), f32::from(cached.y));
    }
    let positions = baked.mesh().vertices();
    if let Some(&p) = positions.get(usize::from(edge.a)) {
        let e = map.eye_space(p);
        if e[2] >= map.near {
            let sp = map.screen(e);
            if sp.x.is_finite() && sp.y.is_finite() {
                return (sp.x, sp.y);
            }
        }
    }
    (f32::from(clipped.x), f32::from(clipped.y))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec::Vec;

    use super::*;
    use crate::render::{Cull, DrawMode};
    use crate::Pattern;

    fn iso() -> Dashing {
        Dashing::of(&Settings {
            mode: DrawMode::Dashed,
            cull: Cull::Auto,
            pattern: Pattern::PAPER,
            dashes: Dashes::ISO,
            lines: crate::render::LineVisibility::ByPixel,
        })
        .unwrap()
    }

    /// The on/off sequence of centres `ks` of a line.
    fn dashes(phase: DashPhase, ks: impl Iterator<Item = i32>) -> Vec<bool> {
        let on = iso().on;
        ks.map(|k| !phase.in_gap(k, on)).collect()
    }

    #[test]
    fn a_horizontal_line_from_its_anchor_is_twelve_on_three_off() {
        // Anchor at x = 10.25 px, growing to the right: centre 10 is a quarter
        // pixel from it, centre 22 the first in a gap (12.25 px).
        let phase = DashPhase::new(iso(), 10.25, true, 1.0, 10);
        let got = dashes(phase, 10..55);
        let want: Vec<bool> = (0..45).map(|i| i % 15 < 12).collect();
        assert_eq!(got, want);
    }

    #[test]
    fn the_phase_is_anchored_whichever_way_the_line_is_walked() {
        // The anchor at the high end (x = 60.75): centre 60 is a quarter pixel
        // from it, 48 the first in a gap (12.25 px).
        let phase = DashPhase::new(iso(), 60.75, false, 1.0, 20);
        let got = dashes(phase, (16..=60).rev());
        let want: Vec<bool> = (0..45).map(|i| i % 15 < 12).collect();
        assert_eq!(got, want);
    }

    #[test]
    fn a_diagonal_line_measures_along_itself() {
        // 45 degrees: a centre is sqrt 2 px along the line, so a period of 15 px
        // takes 15 / sqrt 2 = 10.6 centres; dashes of 12 px take 8.5.
        let ratio = core::f32::consts::SQRT_2;
        let phase = DashPhase::new(iso(), 0.25, true, ratio, 0);
        let got = dashes(phase, 0..64);
        for (k, on) in got.iter().enumerate() {
            let d = (k as f32 + 0.25) * ratio % 15.0;
            assert_eq!(*on, d < 12.0, "centre {k}, {d} px into the period");
        }
    }

    #[test]
    fn set_up_far_from_the_anchor_keeps_the_phase() {
        // The same line set up at centre 300 (as a line clipped at the screen's
        // edge is) has the same phase at every centre as one set up at 0.
        let near = DashPhase::new(iso(), -200.25, true, 1.25, -200);
        let far = DashPhase::new(iso(), -200.25, true, 1.25, 300);
        let on = iso().on;
        for k in 300..400 {
            let a = near.at0.wrapping_add((k as u32).wrapping_mul(near.step));
            let b = far.at0.wrapping_add((k as u32).wrapping_mul(far.step));
            // Within 2^-16 of a period (1/4000 px).
            assert!(
                a.wrapping_sub(b).wrapping_add(1 << 16) < 1 << 17,
                "centre {k}"
            );
            assert_eq!(near.in_gap(k, on), far.in_gap(k, on), "centre {k}");
        }
    }

    #[test]
    fn the_screen_pattern_and_dashes_without_a_gap_have_no_gaps() {
        for k in -5..5 {
            assert!(!DashPhase::SCREEN.in_gap(k, 0));
        }
        let solid = Settings {
            dashes: Dashes::Along { dash: 5, gap: 0 },
            ..Settings::default()
        };
        let solid = Dashing::of(&solid).unwrap();
        let phase = DashPhase::new(solid, 0.0, true, 1.0, 0);
        assert!((0..40).all(|k| !phase.in_gap(k, solid.on)));
        assert_eq!(Dashing::of(&Settings::default()), None);
        // No dash at all: every hidden pixel is in a gap.
        let none = Dashing::of(&Settings {
            dashes: Dashes::Along { dash: 0, gap: 3 },
            ..Settings::default()
        })
        .unwrap();
        let phase = DashPhase::new(none, 0.0, true, 1.0, 0);
        assert!((0..20).all(|k| phase.in_gap(k, none.on)));
    }
}
