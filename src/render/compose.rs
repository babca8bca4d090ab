//! Composition: a band's face ids and line masks become spans of one colour.

use embedded_graphics_core::pixelcolor::{BinaryColor, PixelColor};

use super::lines::Band;
use super::transform::ProjectedVertex;
use super::{bit, DrawMode, FrameCtx};
use crate::mesh::Viewpoint;
use crate::{Error, Span, SpanSink};

/// The colours of a frame.
pub trait Palette {
    /// The target's colour type.
    type Color: PixelColor;
    /// Colour of drawn line pixels (visible, and hidden ones the pattern passes).
    fn line(&self) -> Self::Color;
    /// Colour of pixel (x, y) of face `face`, whose normal makes `shade` (0 edge-on ..
    /// 255 facing the eye) with the view; `None` leaves the pixel untouched.
    fn face(&self, face: u16, shade: u8, x: u16, y: u16) -> Option<Self::Color>;
    /// The colours [`face`](Self::face) gives the 32 pixels `x0..x0 + 32` of row `y`
    /// of face `face`, when they are two colours and every pixel is touched: bit `k`
    /// of the word set takes the first colour, clear the second. `None` (the
    /// default): the pixels are asked one by one. Lets an engine write a row's
    /// faces a word at a time.
    fn face_word(
        &self,
        face: u16,
        shade: u8,
        x0: u16,
        y: u16,
    ) -> Option<(u32, Self::Color, Self::Color)> {
        let _ = (face, shade, x0, y);
        None
    }
}

/// The monochrome palette: lines in `line`, faces as ordered dither of their
/// shading in the other colour's complement (lit faces light).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MonoPalette {
    /// The line colour; faces are dithered between it and its opposite.
    pub line: BinaryColor,
}

/// 4x4 Bayer thresholds, 0..16.
const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

impl Palette for MonoPalette {
    type Color = BinaryColor;

    fn line(&self) -> BinaryColor {
        self.line
    }

    // Indexing: y % 4 and x % 4 on a 4 x 4 matrix.
    #[allow(clippy::indexing_slicing)]
    fn face(&self, _face: u16, shade: u8, x: u16, y: u16) -> Option<BinaryColor> {
        // Dark faces get more line-coloured dots; at most half, so lines stay readable.
        let level = (255 - u16::from(shade)) / 32;
        let threshold = BAYER[usize::from(y % 4)][usize::from(x % 4)];
        Some(if u16::from(threshold) < level {
            self.line
        } else {
            self.line.invert()
        })
    }

    // Indexing: y % 4 on a 4 x 4 matrix.
    #[allow(clippy::indexing_slicing)]
    fn face_word(
        &self,
        _face: u16,
        shade: u8,
        x0: u16,
        y: u16,
    ) -> Option<(u32, BinaryColor, BinaryColor)> {
        let level = (255 - u16::from(shade)) / 32;
        let mut nibble = 0u32;
        for (i, &threshold) in BAYER[usize::from(y % 4)].iter().enumerate() {
            nibble |= u32::from(u16::from(threshold) < level) << i;
        }
        // Bit k is column (x0 + k) % 4 of the matrix: the row turned to start at x0.
        let r = u32::from(x0 % 4);
        let nibble = ((nibble >> r) | (nibble << (4 - r))) & 0xF;
        Some((nibble * 0x1111_1111, self.line, self.line.invert()))
    }
}

/// Any colour type: lines in `line`, every face in `face` (or left untouched when
/// `None`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SolidPalette<C> {
    /// Line colour.
    pub line: C,
    /// Face colour, or `None` to leave face pixels as they are.
    pub face: Option<C>,
}

impl<C: PixelColor> Palette for SolidPalette<C> {
    type Color = C;

    fn line(&self) -> C {
        self.line
    }

    fn face(&self, _: u16, _: u8, _: u16, _: u16) -> Option<C> {
        self.face
    }
}

/// Sees each finished row: face ids (0 none, else 1 + face) and the visible and
/// hidden line masks (bit k of word w is pixel 32w + k), before the pattern.
pub trait FrameProbe {
    /// False for a probe that ignores every row, so an engine need not make the ids.
    const ACTIVE: bool = true;
    /// Row `y` is finished.
    fn row(&mut self, y: u16, ids: &[u16], visible: &[u32], hidden: &[u32]);
}

impl FrameProbe for () {
    const ACTIVE: bool = false;
    fn row(&mut self, _: u16, _: &[u16], _: &[u32], _: &[u32]) {}
}

/// Shading of face `f`: |cos| of the angle between its normal and the eye direction.
pub(crate) fn shade(ctx: &FrameCtx<'_, '_>, view: &Viewpoint, f: usize) -> u8 {
    let n = ctx.mesh.face_normal(f);
    let len = crate::camera::sqrt(crate::camera::dot(n, n));
    if len <= 0.0 {
        return 0;
    }
    let d = view.direction_from(ctx.mesh.face_centroid(f));
    let c = (crate::camera::dot(n, d) / len).abs().min(1.0);
    (c * 255.0) as u8
}

/// Sends the band's rows to the sink; returns the number of spans sent.
pub(crate) fn emit_band<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
    ctx: &FrameCtx<'_, '_>,
    band: &Band<'_>,
    drawn: &[u32],
    palette: &P,
    sink: &mut K,
    probe: &mut R,
) -> Result<u32, K::Error> {
    let Band {
        ids: band,
        lines: masks,
    } = band;
    let settings = ctx.settings;
    let width = usize::from(band.width);
    let mut spans = 0u32;
    let mut shade_of: (u16, u8) = (0, 0);
    for r in 0..band.rows {
        let y = band.top + r;
        let ids = band.row(y);
        let (visible, hidden) = masks.row(r);
        probe.row(y, ids, visible, hidden);
        let line_word = |k: usize| -> u32 {
            let v = visible.get(k).copied().unwrap_or(0);
            let h = hidden.get(k).copied().unwrap_or(0);
            match settings.mode {
                DrawMode::Wireframe | DrawMode::HiddenRemoved => v,
                DrawMode::Dashed | DrawMode::SurfacesDashed => {
                    v | (h & settings.pattern.word(32 * k as u32, u32::from(y)))
                }
                DrawMode::Surfaces => 0,
            }
        };
        let mut run: Option<(u16, u16, K::Color)> = None;
        let mut put = |x: u16, color: Option<K::Color>, sink: &mut K| -> Result<(), K::Error> {
            match (run, color) {
                (Some((a, b, c)), Some(nc)) if b == x && c == nc => run = Some((a, x + 1, c)),
                (prev, next) => {
                    if let Some((a, b, c)) = prev {
                        sink.fill_span(Span::new(y, a, b), c)?;
                        spans += 1;
                    }
                    run = next.map(|c| (x, x + 1, c));
                }
            }
            Ok(())
        };
        if settings.mode.draws_faces() {
            // One line word (visible, hidden and pattern) per 32 pixels, not per pixel.
            for (k, chunk) in ids.chunks(32).enumerate() {
                let word = line_word(k);
                for (i, &id) in chunk.iter().enumerate() {
                    let x16 = (32 * k + i) as u16;
                    let color = if word & (1 << i) != 0 {
                        Some(palette.line())
                    } else if id != 0 && bit(drawn, usize::from(id - 1)) {
                        if shade_of.0 != id {
                            shade_of = (id, shade(ctx, &ctx.viewpoint, usize::from(id - 1)));
                        }
                        palette.face(id - 1, shade_of.1, x16, y)
                    } else {
                        None
                    };
                    put(x16, color, sink)?;
                }
            }
        } else {
            let line = palette.line();
            for k in 0..width.div_ceil(32) {
                let mut bits = line_word(k);
                while bits != 0 {
                    let x = 32 * k + bits.trailing_zeros() as usize;
                    if x >= width {
                        break;
                    }
                    put(x as u16, Some(line), sink)?;
                    bits &= bits - 1;
                }
            }
        }
        put(band.width, None, sink)?;
    }
    Ok(spans)
}

/// One composition stage of a frame loop: a finished band (face ids with apron, line
/// masks) to spans. [`Flat`] is [`emit_band`]; the grey coverage mode is another.
pub(crate) trait Compose<K: SpanSink> {
    /// Sends the band's rows to the sink; returns the number of spans sent.
    fn band<R: FrameProbe>(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &Band<'_>,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<u32, Error<K::Error>>;
}

/// One colour per pixel from a [`Palette`]: [`emit_band`].
pub(crate) struct Flat<'p, P>(pub &'p P);

impl<K: SpanSink, P: Palette<Color = K::Color>> Compose<K> for Flat<'_, P> {
    fn band<R: FrameProbe>(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        _: &[ProjectedVertex],
        drawn: &[u32],
        band: &Band<'_>,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<u32, Error<K::Error>> {
        emit_band(ctx, band, drawn, self.0, sink, probe).map_err(Error::Target)
    }
}
