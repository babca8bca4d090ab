//! A finished row of the fast engine to spans: runs of line pixels (visible, and
//! hidden ones the pattern passes) and, in the surface modes, runs of one face
//! colour.

use super::baked::FacePlane;
use super::views::FaceViews;
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

/// Shades kept, by face index modulo this (a power of two): a row's runs
/// change face every few pixels, and the rows after it meet the same faces.
const KEPT_SHADES: usize = 32;

/// The shading of a face (|cos| between its normal and the eye direction, 0..255),
/// with the last shades asked kept (a square root each made, so kept).
pub(super) struct Shades<'a, V: FaceViews> {
    planes: &'a [FacePlane],
    viewpoint: Viewpoint,
    views: V,
    kept: [(u16, u8); KEPT_SHADES],
}

impl<'a, V: FaceViews> Shades<'a, V> {
    /// None kept yet; face `f`'s plane is seen from `views.view_of(f, viewpoint)`.
    pub fn new(planes: &'a [FacePlane], viewpoint: Viewpoint, views: V) -> Self {
        Self {
            planes,
            viewpoint,
            views,
            kept: [(super::NONE, 0); KEPT_SHADES],
        }
    }

    fn of(&mut self, face: u16) -> u8 {
        let slot = usize::from(face) % KEPT_SHADES;
        if let Some(&(f, shade)) = self.kept.get(slot) {
            if f == face {
                return shade;
            }
        }
        let plane = self
            .planes
            .get(usize::from(face))
            .copied()
            .unwrap_or_default();
        let n = plane.normal;
        let len = sqrt(dot(n, n));
        let shade = if len > 0.0 {
            let view = self.views.view_of(face, &self.viewpoint);
            let d = view.direction_from(plane.centroid);
            ((dot(n, d) / len).abs().min(1.0) * 255.0) as u8
        } else {
            0
        };
        if let Some(k) = self.kept.get_mut(slot) {
            *k = (face, shade);
        }
        shade
    }
}

/// A finished row: row `y`'s nearest face entries, none of them a face outside
/// `columns.0 .. columns.1`.
pub(super) struct FaceRow<'a> {
    pub y: u16,
    pub cells: &'a [u32],
    pub columns: (usize, usize),
}

/// Sends `finished` to `sink`: `visible` and `hidden` are its line masks (`visible`
/// becomes the drawn line pixels). Returns the spans sent.
pub(super) fn emit_row<K: SpanSink, P: Palette<Color = K::Color>>(
    finished: FaceRow<'_>,
    settings: &Settings,
    visible: &mut [u32],
    hidden: &mut [u32],
    palette: &P,
    shades: &mut Shades<'_, impl FaceViews>,
    sink: &mut K,
) -> Result<u32, K::Error> {
    let FaceRow {
        y,
        cells: row,
        columns: faces,
    } = finished;
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
    let w1 = if settings.pattern.divides_word() {
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
            // Words without faces' columns hold no face.
            let mut i = if 32 * k + 32 <= faces.0 || 32 * k >= faces.1 {
                chunk.len()
            } else {
                0
            };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::engines::fast::views::OneMesh;

    /// Faces 1 and 33 share a kept slot: each is asked in turn, and each still
    /// gets its own shade (the one a fresh `Shades` makes).
    #[test]
    fn faces_sharing_a_kept_shade_slot_keep_their_own_shades() {
        let plane = |z: f32| FacePlane {
            normal: [0.0, 1.0 - z, z],
            centroid: [0.0; 3],
        };
        let mut planes = [plane(0.0); 40];
        planes[1] = plane(1.0);
        planes[33] = plane(0.5);
        let view = Viewpoint::Orthographic {
            direction_to_eye: [0.0, 0.0, 1.0],
        };
        let fresh = |face: u16| Shades::new(&planes, view, OneMesh).of(face);
        let (one, other) = (fresh(1), fresh(33));
        assert_ne!(one, other, "the two faces face the eye differently");
        let mut shades = Shades::new(&planes, view, OneMesh);
        for face in [1, 33, 33, 1, 1, 33] {
            let expected = if face == 1 { one } else { other };
            assert_eq!(shades.of(face), expected, "face {face}");
        }
    }
}
