//! Coverage for grey displays: an A-buffer of sub-sample masks at the edges of faces.
//!
//! A pixel whose 3 x 3 neighbourhood of face ids holds one face is inside that face
//! (full coverage). Any other pixel (an edge pixel) is sampled on a 4 x 4 grid at
//! (i + (a + 1/2) / 4, j + (b + 1/2) / 4): each face seen in the neighbourhood (at
//! most 9) gets a 16-bit mask of the sub-samples it covers (the coverage point test
//! of [conventions](crate::conventions), exact on the fixed-point grid), and each
//! sub-sample goes to
//! the nearest face covering it, with the Z-buffer's tie rule (the lower face index
//! wins within [`DepthPlane::tie`]), or to the background. The pixel's grey is the
//! mean of the 16 sub-samples' greys. Feature-edge lines stay solid in the line
//! colour: they are one pixel wide by convention, and anti-aliasing them would blur
//! a dashed hidden line into the faces.
//!
//! A face that covers sub-samples of a pixel but no pixel centre of its 3 x 3
//! neighbourhood is not in the face ids there. Faces less than three pixels wide or
//! high (most such faces: small faces of a detailed mesh) are found by their
//! bounding boxes, up to 512 per band and 128 per row; a longer diagonal sliver or a
//! sharp tip is still missed where no centre near it is covered.

use embedded_graphics_core::pixelcolor::{Gray8, GrayColor, PixelColor};
use heapless::Vec;

use crate::render::compose::{self, shade, Compose, FrameProbe, SolidPalette};
use crate::render::depth::coverage::covers;
use crate::render::depth::plane::DepthPlane;
use crate::render::lines::Band;
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, face_polygon, DrawMode, FrameCtx};
use crate::Capacity;
use crate::{Error, Span, SpanSink};

/// The fewest sub-pixel bits for which the sub-samples, at odd eighths of a pixel,
/// lie on the half sub-pixel grid (`2^-(S+1)` px) of the coverage test.
pub(crate) const GREY_MIN_BITS: u32 = 2;

/// Faces whose clipped polygon and depth plane are kept set up.
const SLOTS: usize = 12;

/// The most faces considered at one pixel: the 3 x 3 neighbourhood's nine and the
/// small faces over it. More is [`Error::CapacityExceeded`] (`needed` then says one
/// more, a lower bound): dense meshes on small frames reach it (fandisk and the
/// teapot at 128 x 64), where thousands of faces are below a pixel.
const CANDIDATES: usize = 64;

/// Faces whose bounding box is narrower or lower than this many pixels are "small":
/// they may cover sub-samples of a pixel without covering any pixel centre near it,
/// so the face ids do not show them; they are looked up by bounding box.
const THIN_PX: i32 = 3;

/// A face small enough to be missed by the face ids (see the module comment), kept
/// for one band of [`ZBufferRenderer::render_grey`](super::ZBufferRenderer::render_grey):
/// the caller lends a slice of these, one per face that can be small in a band (the
/// mesh's face count always suffices).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SmallFace {
    /// 1 + face index.
    id: u16,
    /// Bounding box x0, y0, x1, y1 in sub-pixel units.
    bbox: [i32; 4],
}

/// The grey levels of a frame with anti-aliased face edges, for
/// [`ZBufferRenderer::render_grey`](super::ZBufferRenderer::render_grey). Levels are
/// 0 (black) ..= 255 (white) whatever the target's depth; coverage is mixed in
/// levels and the result converted by [`grey`](Self::grey).
pub trait GreyPalette {
    /// The target's colour type.
    type Color: PixelColor;
    /// Level of the background, mixed into edge pixels where no face covers a
    /// sub-sample (pixels no face reaches are left untouched).
    fn background(&self) -> u8;
    /// Colour of drawn line pixels (solid, not anti-aliased).
    fn line(&self) -> Self::Color;
    /// Level of face `face`, whose normal makes `shade` (0 edge-on .. 255 facing the
    /// eye) with the view.
    fn face(&self, face: u16, shade: u8) -> u8;
    /// The target colour of a level.
    fn grey(&self, level: u8) -> Self::Color;
}

/// A [`GreyPalette`] for any grey colour type of embedded-graphics (`Gray2`,
/// `Gray4`, `Gray8`): faces shaded linearly from `dark` (edge-on) to `light`
/// (facing the eye). Mixing is done in 8-bit levels, then rounded to the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GreyShades<C> {
    /// The background (what the target is cleared to).
    pub background: C,
    /// Feature-edge lines.
    pub line: C,
    /// A face seen edge-on.
    pub dark: C,
    /// A face facing the eye.
    pub light: C,
}

/// Black background, white lines, faces from 3/16 to 11/16 grey.
impl<C: GrayColor + From<Gray8>> Default for GreyShades<C> {
    fn default() -> Self {
        GreyShades {
            background: C::BLACK,
            line: C::WHITE,
            dark: Gray8::new(48).into(),
            light: Gray8::new(176).into(),
        }
    }
}

impl<C: GrayColor + From<Gray8>> GreyPalette for GreyShades<C>
where
    Gray8: From<C>,
{
    type Color = C;

    fn background(&self) -> u8 {
        Gray8::from(self.background).luma()
    }

    fn line(&self) -> C {
        self.line
    }

    fn face(&self, _: u16, shade: u8) -> u8 {
        let (dark, light) = (
            i32::from(Gray8::from(self.dark).luma()),
            i32::from(Gray8::from(self.light).luma()),
        );
        let level = dark + ((light - dark) * i32::from(shade) + 127) / 255;
        level.clamp(0, 255) as u8
    }

    fn grey(&self, level: u8) -> C {
        Gray8::new(level).into()
    }
}

/// The 16-bit mask of the sub-samples of pixel (`i`, `j`) that `poly` covers at `s`
/// (>= 2) sub-pixel bits: bit `4b + a` is the sub-sample at (i + (2a + 1) / 8,
/// j + (2b + 1) / 8). `bbox` (x0, y0, x1, y1 in half sub-pixel units) bounds `poly`.
pub(crate) fn pixel_mask(poly: &[ScreenVertex], bbox: &[i64; 4], s: u32, i: i64, j: i64) -> u16 {
    let px = 1i64 << (s + 1);
    let unit = 1i64 << s.saturating_sub(2);
    let (x0, y0) = (i * px, j * px);
    if bbox[2] < x0 || bbox[0] >= x0 + px || bbox[3] < y0 || bbox[1] >= y0 + px {
        return 0;
    }
    let mut mask = 0u16;
    for b in 0..4 {
        let y = y0 + (2 * b + 1) * unit;
        if y < bbox[1] || y >= bbox[3] {
            continue;
        }
        for a in 0..4 {
            if covers(poly, x0 + (2 * a + 1) * unit, y) {
                mask |= 1 << (4 * b + a);
            }
        }
    }
    mask
}

/// The bounding box of `poly` in half sub-pixel units: x0, y0, x1, y1.
fn bounds(poly: &[ScreenVertex]) -> [i64; 4] {
    poly.iter().fold(
        [i64::MAX, i64::MAX, i64::MIN, i64::MIN],
        |[x0, y0, x1, y1], v| {
            let (x, y) = (2 * i64::from(v.x), 2 * i64::from(v.y));
            [x0.min(x), y0.min(y), x1.max(x), y1.max(y)]
        },
    )
}

/// One face seen at an edge pixel: the sub-samples it covers and its depth plane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Candidate {
    /// Covered sub-samples (see [`pixel_mask`]).
    pub mask: u16,
    pub plane: DepthPlane,
    /// Its grey level.
    pub level: u8,
}

/// The sum over the 16 sub-samples of pixel (`i`, `j`) of the level of the nearest
/// covering candidate, or `background`. `cands` are in face index order: at equal
/// depth (within the later face's tie) the earlier one keeps the sub-sample.
pub(crate) fn resolve(cands: &[Candidate], s: u32, i: i64, j: i64, background: u8) -> u32 {
    // Sub-samples covered once need no depth; twice or more are compared.
    let (mut once, mut many) = (0u16, 0u16);
    for c in cands {
        many |= once & c.mask;
        once |= c.mask;
    }
    let mut sum = (16 - once.count_ones()) * u32::from(background);
    for c in cands {
        sum += (c.mask & !many).count_ones() * u32::from(c.level);
    }
    let px = 1i64 << (s + 1);
    let unit = 1i64 << s.saturating_sub(2);
    let mut rest = many;
    while rest != 0 {
        let k = i64::from(rest.trailing_zeros());
        rest &= rest - 1;
        let (x, y) = (
            i * px + (2 * (k % 4) + 1) * unit,
            j * px + (2 * (k / 4) + 1) * unit,
        );
        let mut best: Option<(u32, u8)> = None;
        for c in cands.iter().filter(|c| c.mask & (1 << k) != 0) {
            let q = c.plane.at(x, y);
            match best {
                Some((near, _)) if q <= near.saturating_add(c.plane.tie()) => {}
                _ => best = Some((q, c.level)),
            }
        }
        sum += u32::from(best.map_or(background, |(_, level)| level));
    }
    sum
}

/// A face kept set up: its clipped polygon, bounding box, plane and level.
struct Slot<const POLY: usize> {
    /// 1 + face index; 0 for an empty slot.
    id: u16,
    poly: Vec<ScreenVertex, POLY>,
    bbox: [i64; 4],
    plane: Option<DepthPlane>,
    level: u8,
}

/// The grey composition stage: a [`GreyPalette`] and the faces last set up.
pub(crate) struct GreyCompose<'p, G, const POLY: usize> {
    palette: &'p G,
    slots: [Slot<POLY>; SLOTS],
    next: usize,
    /// The band's small faces (see [`THIN_PX`]), the first `small_len` of the lent list.
    small: &'p mut [SmallFace],
    small_len: usize,
}

impl<'p, G: GreyPalette, const POLY: usize> GreyCompose<'p, G, POLY> {
    /// No face set up yet; `small` is the lent list of a band's small faces.
    pub fn new(palette: &'p G, small: &'p mut [SmallFace]) -> Self {
        Self {
            palette,
            slots: [const {
                Slot {
                    id: 0,
                    poly: Vec::new(),
                    bbox: [0; 4],
                    plane: None,
                    level: 0,
                }
            }; SLOTS],
            next: 0,
            small,
            small_len: 0,
        }
    }

    /// Finds the drawn faces wholly in view, less than [`THIN_PX`] wide or high, that
    /// reach rows `top .. end` (the band).
    fn find_small(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        top: u16,
        end: u16,
    ) -> Result<(), Error> {
        let mut found = 0usize;
        let thin = THIN_PX << ctx.s;
        let (band_lo, band_hi) = (i32::from(top) << ctx.s, i32::from(end) << ctx.s);
        for f in 0..ctx.mesh.face_count() {
            if !bit(drawn, f) {
                continue;
            }
            let mut b = [i32::MAX, i32::MAX, i32::MIN, i32::MIN];
            let mut outside = 0u8;
            for &v in ctx.mesh.face(f) {
                let p = vertices
                    .get(v as usize)
                    .map_or(ProjectedVertex::default(), |p| *p);
                outside |= p.outside();
                let s = p.screen();
                b = [b[0].min(s.x), b[1].min(s.y), b[2].max(s.x), b[3].max(s.y)];
            }
            let small = b[2].saturating_sub(b[0]) < thin || b[3].saturating_sub(b[1]) < thin;
            if outside == 0 && small && b[3] > band_lo && b[1] < band_hi {
                if let Some(slot) = self.small.get_mut(found) {
                    *slot = SmallFace {
                        id: (f + 1) as u16,
                        bbox: b,
                    };
                }
                found += 1;
            }
        }
        crate::render::need(Capacity::SmallFaces, found, self.small.len())?;
        self.small_len = found;
        Ok(())
    }

    /// Face `id` (1 + index) at pixel (`i`, `j`): `None` when it covers no sub-sample
    /// there (or nothing at all).
    fn candidate(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        id: u16,
        i: i64,
        j: i64,
    ) -> Result<Option<Candidate>, Error> {
        let k = match self.slots.iter().position(|slot| slot.id == id) {
            Some(k) => k,
            None => {
                let k = self.next;
                self.next = (self.next + 1) % SLOTS;
                let Some(slot) = self.slots.get_mut(k) else {
                    return Ok(None);
                };
                let f = usize::from(id.saturating_sub(1));
                slot.id = id;
                slot.plane = None;
                if face_polygon(ctx, vertices, f, &mut slot.poly)? {
                    slot.plane = DepthPlane::new(&slot.poly, ctx.s);
                    slot.bbox = bounds(&slot.poly);
                }
                slot.level = self
                    .palette
                    .face(id.saturating_sub(1), shade(ctx, &ctx.viewpoint, f));
                k
            }
        };
        let Some(slot) = self.slots.get(k) else {
            return Ok(None);
        };
        let Some(plane) = slot.plane else {
            return Ok(None);
        };
        let mask = pixel_mask(&slot.poly, &slot.bbox, ctx.s, i, j);
        Ok((mask != 0).then_some(Candidate {
            mask,
            plane,
            level: slot.level,
        }))
    }
}

/// The distinct drawn face ids of the 3 x 3 neighbourhood of pixel `x` (rows that are
/// empty are outside the frame), ascending; `None` when all nine are one id.
/// A small face reaching the row: `(x0, x1)` its extent in sub-pixel units.
fn neighbourhood(
    rows: [&[u16]; 3],
    x: usize,
    drawn: &[u32],
    small: &[SmallFace],
    y: u16,
    s: u32,
) -> Result<Option<Vec<u16, CANDIDATES>>, Error> {
    let centre = rows[1].get(x).copied().unwrap_or(0);
    let mut ids: Vec<u16, CANDIDATES> = Vec::new();
    let mut mixed = false;
    let add = |id: u16, ids: &mut Vec<u16, CANDIDATES>| -> Result<(), Error> {
        if !ids.contains(&id) {
            // Insertion in order: a few ids.
            let at = ids.iter().position(|&k| k > id).unwrap_or(ids.len());
            ids.insert(at, id).map_err(|_| Error::CapacityExceeded {
                what: Capacity::PixelCandidates,
                needed: CANDIDATES + 1,
                capacity: CANDIDATES,
            })?;
        }
        Ok(())
    };
    for row in rows {
        for n in x.saturating_sub(1)..=x + 1 {
            let Some(&id) = row.get(n) else { continue };
            mixed |= id != centre;
            if id != 0 && bit(drawn, usize::from(id - 1)) {
                add(id, &mut ids)?;
            }
        }
    }
    let (lo, hi) = ((x as i32) << s, (x as i32 + 1) << s);
    let (top, bottom) = (i32::from(y) << s, (i32::from(y) + 1) << s);
    for f in small {
        let [x0, y0, x1, y1] = f.bbox;
        if x1 > lo && x0 < hi && y1 > top && y0 < bottom {
            mixed |= f.id != centre;
            add(f.id, &mut ids)?;
        }
    }
    Ok(mixed.then_some(ids))
}

impl<K: SpanSink, G: GreyPalette<Color = K::Color>, const POLY: usize> Compose<K>
    for GreyCompose<'_, G, POLY>
{
    fn band<R: FrameProbe>(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &Band<'_>,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<u32, Error<K::Error>> {
        let settings = ctx.settings;
        if !settings.mode.draws_faces() {
            let lines = SolidPalette {
                line: self.palette.line(),
                face: None,
            };
            return compose::emit_band(ctx, band, drawn, &lines, sink, probe)
                .map_err(Error::Target);
        }
        let Band {
            ids: band,
            lines: masks,
        } = band;
        let background = self.palette.background();
        self.find_small(ctx, vertices, drawn, band.top, band.top + band.rows)
            .map_err(Error::widen)?;
        let mut spans = 0u32;
        let mut level_of: (u16, u8) = (0, 0);
        for r in 0..band.rows {
            let y = band.top + r;
            let rows = [
                y.checked_sub(1).map_or(&[][..], |u| band.row(u)),
                band.row(y),
                band.row(y.saturating_add(1)),
            ];
            let (visible, hidden) = masks.row(r);
            probe.row(y, rows[1], visible, hidden);
            let line_word = |k: usize| -> u32 {
                let v = visible.get(k).copied().unwrap_or(0);
                let h = hidden.get(k).copied().unwrap_or(0);
                match settings.mode {
                    DrawMode::SurfacesDashed => {
                        v | (h & settings.pattern.word(32 * k as u32, u32::from(y)))
                    }
                    _ => 0,
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
            for (k, chunk) in rows[1].chunks(32).enumerate() {
                let word = line_word(k);
                for (n, &id) in chunk.iter().enumerate() {
                    let x = 32 * k + n;
                    let x16 = x as u16;
                    let color = if word & (1 << n) != 0 {
                        Some(self.palette.line())
                    } else if let Some(ids) = neighbourhood(
                        rows,
                        x,
                        drawn,
                        self.small.get(..self.small_len).unwrap_or(&[]),
                        y,
                        ctx.s,
                    )
                    .map_err(Error::widen)?
                    {
                        let (i, j) = (i64::from(x16), i64::from(y));
                        let mut cands: Vec<Candidate, CANDIDATES> = Vec::new();
                        for &c in &ids {
                            if let Some(cand) = self
                                .candidate(ctx, vertices, c, i, j)
                                .map_err(Error::widen)?
                            {
                                // At most one candidate per id: within capacity.
                                let _ = cands.push(cand);
                            }
                        }
                        let sum = resolve(&cands, ctx.s, i, j, background);
                        Some(self.palette.grey(((sum + 8) / 16).min(255) as u8))
                    } else if id != 0 && bit(drawn, usize::from(id - 1)) {
                        if level_of.0 != id {
                            let f = usize::from(id - 1);
                            let s = shade(ctx, &ctx.viewpoint, f);
                            level_of = (id, self.palette.face(id - 1, s));
                        }
                        Some(self.palette.grey(level_of.1))
                    } else {
                        None
                    };
                    put(x16, color, sink).map_err(Error::Target)?;
                }
            }
            put(band.width, None, sink).map_err(Error::Target)?;
        }
        Ok(spans)
    }
}

#[cfg(test)]
#[path = "abuffer_tests.rs"]
mod tests;
