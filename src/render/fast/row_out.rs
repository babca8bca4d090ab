//! A finished row of the fast engine to spans: runs of line pixels (visible, and
//! hidden ones the pattern passes) and, in the surface modes, runs of one face
//! colour.

use super::baked::FacePlane;
use crate::camera::{dot, sqrt};
use crate::mesh::Viewpoint;
use crate::render::{DrawMode, Palette, Settings};
use crate::{Span, SpanSink};

/// Merges touching pixels of one colour into spans.
struct Runs<C> {
    y: u16,
    run: Option<(u16, u16, C)>,
    spans: u32,
}

impl<C: PartialEq + Copy> Runs<C> {
    fn put<K: SpanSink<Color = C>>(
        &mut self,
        x0: u16,
        x1: u16,
        color: Option<C>,
        sink: &mut K,
    ) -> Result<(), K::Error> {
        match (self.run, color) {
            (Some((a, b, c)), Some(nc)) if b == x0 && c == nc => self.run = Some((a, x1, c)),
            (prev, next) => {
                if let Some((a, b, c)) = prev {
                    sink.fill_span(Span::new(self.y, a, b), c)?;
                    self.spans += 1;
                }
                self.run = next.map(|c| (x0, x1, c));
            }
        }
        Ok(())
    }
}

/// The shading of a face (|cos| between its normal and the eye direction, 0..255),
/// with the last face asked kept.
pub(super) struct Shades<'a> {
    pub planes: &'a [FacePlane],
    pub viewpoint: Viewpoint,
    pub last: (u16, u8),
}

impl Shades<'_> {
    fn of(&mut self, face: u16) -> u8 {
        if self.last.0 == face {
            return self.last.1;
        }
        let plane = self
            .planes
            .get(usize::from(face))
            .copied()
            .unwrap_or_default();
        let n = plane.normal;
        let len = sqrt(dot(n, n));
        let shade = if len > 0.0 {
            let d = self.viewpoint.direction_from(plane.centroid);
            ((dot(n, d) / len).abs().min(1.0) * 255.0) as u8
        } else {
            0
        };
        self.last = (face, shade);
        shade
    }
}

/// Sends row `y` to `sink`: `row` holds the nearest face entries, `visible` and
/// `hidden` the line masks (`visible` becomes the drawn line pixels). Returns the
/// spans sent.
#[allow(clippy::too_many_arguments)]
pub(super) fn emit_row<K: SpanSink, P: Palette<Color = K::Color>>(
    y: u16,
    settings: &Settings,
    row: &[u32],
    visible: &mut [u32],
    hidden: &[u32],
    palette: &P,
    shades: &mut Shades<'_>,
    sink: &mut K,
) -> Result<u32, K::Error> {
    let width = row.len();
    let mut runs = Runs {
        y,
        run: None,
        spans: 0,
    };
    let dashed = matches!(settings.mode, DrawMode::Dashed | DrawMode::SurfacesDashed);
    let lines = settings.mode != DrawMode::Surfaces;
    // A pattern whose width divides 32 has one word for the whole row.
    let w0 = settings.pattern.word(0, u32::from(y));
    let w1 = if 32 % u32::from(settings.pattern.width().max(1)) == 0 {
        w0
    } else {
        settings.pattern.word(32, u32::from(y))
    };
    let line_word = |k: usize, v: u32| -> u32 {
        if !lines {
            return 0;
        }
        if dashed {
            let h = hidden.get(k).copied().unwrap_or(0);
            let pattern = if w0 == w1 {
                w0
            } else {
                settings.pattern.word(32 * k as u32, u32::from(y))
            };
            v | (h & pattern)
        } else {
            v
        }
    };
    let line = palette.line();
    if matches!(settings.mode, DrawMode::Surfaces | DrawMode::SurfacesDashed) {
        for (k, chunk) in row.chunks(32).enumerate() {
            let word = line_word(k, visible.get(k).copied().unwrap_or(0));
            for (i, &cell) in chunk.iter().enumerate() {
                let x = (32 * k + i) as u16;
                let id = 0xFFFF - (cell & 0xFFFF) as u16;
                let color = if word & (1 << i) != 0 {
                    Some(line)
                } else if id != 0xFFFF {
                    palette.face(id, shades.of(id), x, y)
                } else {
                    None
                };
                runs.put(x, x + 1, color, sink)?;
            }
        }
    } else {
        // Lines only: the row's line words go out whole.
        let n = width.div_ceil(32);
        for (k, w) in visible.iter_mut().enumerate().take(n) {
            *w = line_word(k, *w);
        }
        runs.spans += sink.fill_mask(y, visible.get(..n).unwrap_or(&[]), line)?;
    }
    runs.put(width as u16, width as u16, None, sink)?;
    Ok(runs.spans)
}
