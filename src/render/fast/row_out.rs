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
    hidden: &mut [u32],
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
    // Word `k` of the drawn line pixels, from its visible and hidden words.
    let line_word = |k: usize, v: u32, h: u32| -> u32 {
        if !lines {
            return 0;
        }
        if dashed {
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
    let n = width.div_ceil(32);
    if matches!(settings.mode, DrawMode::Surfaces | DrawMode::SurfacesDashed) {
        // A word at a time: the line pixels and the faces' pixels of the line
        // colour gather in `visible`, those of the palette's other colour in
        // `hidden` (each word read before it is written); a face whose palette
        // has no word form goes out pixel by pixel.
        let mut other = None;
        for (k, chunk) in row.chunks(32).enumerate() {
            let word = |m: &[u32]| m.get(k).copied().unwrap_or(0);
            let lines_k = line_word(k, word(visible), word(hidden));
            let (mut first, mut second) = (0u32, 0u32);
            let x0 = (32 * k) as u16;
            let mut i = 0;
            while let Some(&cell) = chunk.get(i) {
                let entry = cell & 0xFFFF;
                let mut j = i + 1;
                while chunk.get(j).is_some_and(|&c| c & 0xFFFF == entry) {
                    j += 1;
                }
                if entry != 0 {
                    let id = 0xFFFF - entry as u16;
                    // Bits i..j, less the line pixels.
                    let run = ((u32::MAX >> (32 - (j - i))) << i) & !lines_k;
                    let shade = shades.of(id);
                    match palette.face_word(id, shade, x0, y) {
                        Some((m, a, b)) if a == line && other.is_none_or(|o| o == b) => {
                            other = Some(b);
                            first |= run & m;
                            second |= run & !m;
                        }
                        _ => {
                            let mut bits = run;
                            while bits != 0 {
                                let x = x0 + bits.trailing_zeros() as u16;
                                bits &= bits - 1;
                                runs.put(x, x + 1, palette.face(id, shade, x, y), sink)?;
                            }
                        }
                    }
                }
                i = j;
            }
            if let Some(v) = visible.get_mut(k) {
                *v = lines_k | first;
            }
            if let Some(h) = hidden.get_mut(k) {
                *h = second;
            }
        }
        // The pixels asked one by one: the last run.
        runs.put(width as u16, width as u16, None, sink)?;
        runs.spans += sink.fill_mask(y, visible.get(..n).unwrap_or(&[]), line)?;
        if let Some(b) = other {
            runs.spans += sink.fill_mask(y, hidden.get(..n).unwrap_or(&[]), b)?;
        }
    } else {
        // Lines only: the row's line words go out whole.
        for (k, w) in visible.iter_mut().enumerate().take(n) {
            *w = line_word(k, *w, hidden.get(k).copied().unwrap_or(0));
        }
        runs.spans += sink.fill_mask(y, visible.get(..n).unwrap_or(&[]), line)?;
    }
    Ok(runs.spans)
}
