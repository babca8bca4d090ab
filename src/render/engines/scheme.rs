//! Paper 003's schemes 1 and 2 as an engine: each drawn face's surface code is
//! added (modulo 2) into a row at its edge crossings, a running XOR left to right
//! leaves at every pixel the XOR of the codes of the faces covering it, and the
//! colour table of the scheme names the visible face. No depth is computed per
//! frame: the depth order is in the codes, made once for a fixed scene whose
//! occlusion graph is known (the paper's instrument panel).
//!
//! The crossings are the scan converter's span ends, the same spans the Z-buffer
//! engine depth-tests, so a face covers exactly the pixels it covers there.
//!
//! Scheme 2 adds a path code per pixel: the paper changes it "each time a new
//! screen-segment is entered", so the caller lends [`ScreenSegments`] naming the path
//! of each pixel. A code the table does not list is an error naming the pixel, never
//! a guessed face. The codes carry no more than the graph: a combination the graph
//! omits whose XOR equals a listed code cannot be told from it (scheme 1 codes that
//! are independent over all surfaces, unit vectors, leave no such combination).
//!
//! Scheme 3 needs no table for a single path: that is the code-fill engine
//! ([`CodeFillRenderer`](super::CodeFillRenderer)) with a depth order. On several
//! paths its codes depend on the path (a surface's depth rank there), so one code per
//! face cannot be added across segments; it is not drawn here.

use core::marker::PhantomData;

use embedded_graphics_core::pixelcolor::{BinaryColor, PixelColor};
use fixed::types::extra::LeEqU32;
use heapless::Vec;

use super::painter::reaches;
use crate::camera::Camera;
use crate::codes::{ColourTable, CombinationScheme, PathScheme, SchemeViolation, Visible};
use crate::geometry::Subpixel;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::band::IdBand;
use crate::render::compose::{Flat, FrameProbe, Palette};
use crate::render::idpass::{render_ids, FrameInput, IdPass, IdWorkspace};
use crate::render::transform::{ProjectedVertex, ScreenVertex};
use crate::render::{bit, face_polygon, need, FrameCtx, Settings, Stats};
use crate::Capacity;
use crate::{Error, FillRule, ScanConverter, ScreenPoint, Span, SpanSink, Viewport};

/// Which path of the occlusion graph each pixel lies on: the paper's screen
/// segments, for scheme 2. Every face covering a pixel must be on its path.
pub trait ScreenSegments {
    /// The path (index into the graph's paths) of pixel (`x`, `y`).
    fn path(&self, x: u16, y: u16) -> usize;
}

/// The whole screen is one segment: every pixel on the same path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct OneSegment(pub usize);

impl ScreenSegments for OneSegment {
    fn path(&self, _: u16, _: u16) -> usize {
        self.0
    }
}

/// The codes a [`SchemeRenderer`] fills with and the colour table that decodes them,
/// made from a scheme whose conditions have been checked (the scheme types exist
/// only if their propositions hold), so the table always matches the codes. `W` is
/// the scheme's code width capacity, `E` the table's rows.
#[derive(Clone)]
pub struct SchemeCoding<'a, const W: usize, const E: usize> {
    codes: Codes<'a, W>,
    table: ColourTable<E>,
}

#[derive(Clone, Copy)]
enum Codes<'a, const W: usize> {
    Combination(CombinationScheme<'a, W>),
    Path(PathScheme<'a, W>, &'a dyn ScreenSegments),
}

impl<'a, const W: usize, const E: usize> SchemeCoding<'a, W, E> {
    /// Scheme 1: one code per surface (surface `s` = mesh face `s`), the XOR looked up
    /// in the scheme's colour table.
    ///
    /// Errors: [`Error::CapacityExceeded`] if the table needs more than `E` rows.
    pub fn combination(scheme: CombinationScheme<'a, W>) -> Result<Self, Error> {
        Ok(Self {
            table: scheme.colour_table()?,
            codes: Codes::Combination(scheme),
        })
    }

    /// Scheme 2: node codewords per surface, plus the code of the path `segments`
    /// names at each pixel.
    ///
    /// Errors: [`Error::CapacityExceeded`] if the table needs more than `E` rows.
    pub fn path(
        scheme: PathScheme<'a, W>,
        segments: &'a dyn ScreenSegments,
    ) -> Result<Self, Error> {
        Ok(Self {
            table: scheme.colour_table()?,
            codes: Codes::Path(scheme, segments),
        })
    }

    /// The colour table.
    pub const fn table(&self) -> &ColourTable<E> {
        &self.table
    }

    /// The number of surfaces the codes are for.
    pub fn surfaces(&self) -> usize {
        match self.codes {
            Codes::Combination(s) => s.graph().surfaces(),
            Codes::Path(s, _) => s.graph().surfaces(),
        }
    }

    /// The code width in bits: scheme 1's widest code, scheme 2's codeword length.
    pub fn width(&self) -> u32 {
        match self.codes {
            Codes::Combination(s) => s.width(),
            Codes::Path(s, _) => s.hamming().length(),
        }
    }

    /// The code surface `surface` XORs in at its edge crossings.
    ///
    /// Errors: [`SchemeViolation::CodeCount`] for a surface without a code.
    pub fn surface_code(&self, surface: usize) -> Result<u128, Error> {
        let code = match self.codes {
            Codes::Combination(s) => s.codes().get(surface).copied(),
            Codes::Path(s, _) => u16::try_from(surface).ok().and_then(|f| s.node_codeword(f)),
        };
        code.ok_or(Error::Scheme(SchemeViolation::CodeCount {
            given: self.surfaces(),
            expected: surface + 1,
        }))
    }

    /// The code added at pixel (`x`, `y`) after the filler: scheme 2's path code, 0
    /// for scheme 1.
    ///
    /// Errors: [`SchemeViolation::UnknownPath`] if the segment names no path.
    pub fn pixel_code(&self, x: u16, y: u16) -> Result<u128, Error> {
        match self.codes {
            Codes::Combination(_) => Ok(0),
            Codes::Path(s, segments) => {
                let path = segments.path(x, y);
                s.path_code(path)
                    .ok_or(Error::Scheme(SchemeViolation::UnknownPath { path, x, y }))
            }
        }
    }

    /// The face id (0 none, else 1 + face) of a pixel with `code`.
    ///
    /// Errors: [`SchemeViolation::UnlistedCode`] for a code the table lacks.
    pub fn decode(&self, code: u128, x: u16, y: u16) -> Result<u16, Error> {
        match self.table.lookup(code) {
            Some(Visible::Blank) => Ok(0),
            Some(Visible::Surface(s)) => s.checked_add(1).ok_or(Error::CapacityExceeded {
                what: Capacity::SurfaceIds,
                needed: usize::from(s) + 1,
                capacity: usize::from(u16::MAX),
            }),
            None => Err(Error::Scheme(SchemeViolation::UnlistedCode { code, x, y })),
        }
    }
}

impl<const W: usize, const E: usize> core::fmt::Debug for SchemeCoding<'_, W, E> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let scheme = match self.codes {
            Codes::Combination(_) => "combination",
            Codes::Path(..) => "path",
        };
        f.debug_struct("SchemeCoding")
            .field("scheme", &scheme)
            .field("width", &self.width())
            .field("table_rows", &self.table.len())
            .finish()
    }
}

/// Draws a mesh with scheme 1 or 2 codes: S = `Frac` sub-pixel bits, room for
/// `EDGES` polygon edges in the scan converter and `POLY` vertices per clipped
/// polygon. The caller lends `codes` (one `u128` per pixel of at least one row) to
/// [`render`](Self::render): more rows there means fewer passes over the faces.
#[derive(Debug)]
pub struct SchemeRenderer<Frac: LeEqU32, const EDGES: usize, const POLY: usize> {
    scan: ScanConverter<EDGES>,
    _frac: PhantomData<Frac>,
}

default_is_new!(SchemeRenderer<EDGES, POLY>);

impl<Frac: LeEqU32, const EDGES: usize, const POLY: usize> SchemeRenderer<Frac, EDGES, POLY> {
    /// Empty working memory.
    pub const fn new() -> Self {
        Self {
            scan: ScanConverter::new(),
            _frac: PhantomData,
        }
    }

    /// Renders `mesh` seen by `camera` into `sink`, each face filled with its code in
    /// `coding` (surface `s` = face `s`). `Stats::code_bits` is the code width.
    ///
    /// Errors: [`SchemeViolation::CodeCount`] unless `coding` has one surface per
    /// face; [`Error::CapacityExceeded`] if `codes` is shorter than the frame width;
    /// [`SchemeViolation::UnlistedCode`] at the first pixel whose code the table
    /// lacks (the scene has an overlap the scheme's graph does not);
    /// [`SchemeViolation::UnknownPath`] for a segment naming no path. On an error the
    /// sink may hold part of the frame.
    #[allow(clippy::too_many_arguments)]
    pub fn render<
        K: SpanSink,
        P: Palette<Color = K::Color>,
        R: FrameProbe,
        const W: usize,
        const E: usize,
    >(
        &mut self,
        mesh: &Mesh<'_>,
        edges: &EdgeAdjacency<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut IdWorkspace<'_>,
        coding: &SchemeCoding<'_, W, E>,
        codes: &mut [u128],
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>>
    where
        K::Color: PixelColor,
    {
        if coding.surfaces() != mesh.face_count() {
            return Err(Error::Scheme(SchemeViolation::CodeCount {
                given: coding.surfaces(),
                expected: mesh.face_count(),
            }));
        }
        need(
            Capacity::RowCodes,
            usize::from(sink.viewport().width),
            codes.len(),
        )
        .map_err(Error::widen)?;
        let input = FrameInput::of_mesh(mesh, edges, camera, settings, Subpixel::<Frac>::BITS);
        let mut pass = Fill::<Frac, EDGES, POLY, W, E> {
            scan: &mut self.scan,
            _frac: PhantomData,
            coding,
            codes,
        };
        let mut stats =
            render_ids::<POLY, _, _, _, _>(&mut pass, &input, ws, &mut Flat(palette), sink, probe)?;
        stats.code_bits = coding.width();
        Ok(stats)
    }
}

/// One frame's filling.
struct Fill<'a, 'c, Frac, const EDGES: usize, const POLY: usize, const W: usize, const E: usize> {
    scan: &'a mut ScanConverter<EDGES>,
    _frac: PhantomData<Frac>,
    coding: &'a SchemeCoding<'c, W, E>,
    /// The crossings, then the running XOR, of a run of rows.
    codes: &'a mut [u128],
}

impl<Frac: LeEqU32, const EDGES: usize, const POLY: usize, const W: usize, const E: usize> IdPass
    for Fill<'_, '_, Frac, EDGES, POLY, W, E>
{
    fn begin(
        &mut self,
        _: &FrameCtx<'_, '_>,
        _: &[ProjectedVertex],
        _: &[u32],
    ) -> Result<(), Error> {
        Ok(())
    }

    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &mut IdBand<'_>,
        _fresh: u16,
    ) -> Result<u32, Error> {
        let width = usize::from(band.width);
        if width == 0 {
            return Ok(0);
        }
        // As many rows at a time as the lent codes hold (`render` checked one).
        let run = u16::try_from(self.codes.len() / width)
            .unwrap_or(u16::MAX)
            .max(1);
        let end = band.first + band.held;
        let mut top = band.first;
        let mut spans = 0;
        while top < end {
            let rows = top..end.min(top.saturating_add(run));
            let held = width * usize::from(rows.end - rows.start);
            let codes = self.codes.get_mut(..held).unwrap_or(&mut []);
            codes.fill(0);
            spans += xor_crossings::<Frac, EDGES, POLY, W, E>(
                self.scan,
                self.coding,
                ctx,
                vertices,
                drawn,
                rows.clone(),
                codes,
            )?;
            for (k, y) in rows.clone().enumerate() {
                let row = codes.get(k * width..(k + 1) * width).unwrap_or(&[]);
                let ids = band.row_mut(y).unwrap_or(&mut []);
                decode_row(self.coding, row, ids, y)?;
            }
            top = rows.end;
        }
        Ok(spans)
    }
}

/// XORs every drawn face's code into `codes` (rows `rows`, `width` codes each) at
/// both ends of each of its spans; returns the spans.
fn xor_crossings<
    Frac: LeEqU32,
    const EDGES: usize,
    const POLY: usize,
    const W: usize,
    const E: usize,
>(
    scan: &mut ScanConverter<EDGES>,
    coding: &SchemeCoding<'_, W, E>,
    ctx: &FrameCtx<'_, '_>,
    vertices: &[ProjectedVertex],
    drawn: &[u32],
    rows: core::ops::Range<u16>,
    codes: &mut [u128],
) -> Result<u32, Error> {
    let mut poly: Vec<ScreenVertex, POLY> = Vec::new();
    let mut points: Vec<ScreenPoint<Frac>, POLY> = Vec::new();
    let mut spans = 0;
    for f in (0..ctx.mesh.face_count()).filter(|&f| bit(drawn, f)) {
        if !face_polygon(ctx, vertices, f, &mut poly)? || !reaches(&poly, ctx.s, &rows) {
            continue;
        }
        points.clear();
        for v in &poly {
            let _ = points.push(ScreenPoint::from_bits(v.x, v.y));
        }
        let mut sink = Crossings {
            codes: &mut *codes,
            first: rows.start,
            code: coding.surface_code(f)?,
            viewport: ctx.viewport,
            spans: 0,
        };
        scan.fill_rows(
            &points,
            FillRule::EvenOdd,
            rows.clone(),
            BinaryColor::On,
            &mut sink,
        )
        .map_err(|e| match e {
            Error::Target(never) => match never {},
            other => other.widen(),
        })?;
        spans += sink.spans;
    }
    Ok(spans)
}

/// Turns a row of crossings into face ids: the running XOR, plus the pixel's path
/// code, looked up in the table. Runs of one code are looked up once.
fn decode_row<const W: usize, const E: usize>(
    coding: &SchemeCoding<'_, W, E>,
    crossings: &[u128],
    ids: &mut [u16],
    y: u16,
) -> Result<(), Error> {
    let mut running = 0u128;
    let mut last: Option<(u128, u16)> = None;
    for (x, (&crossing, id)) in crossings.iter().zip(ids.iter_mut()).enumerate() {
        let x = x as u16;
        running ^= crossing;
        let code = running ^ coding.pixel_code(x, y)?;
        *id = match last {
            Some((c, id)) if c == code => id,
            _ => {
                let id = coding.decode(code, x, y)?;
                last = Some((code, id));
                id
            }
        };
    }
    Ok(())
}

/// A span sink that XORs one code at both ends of each span (the right end only when
/// it is inside the row: nothing follows it there).
struct Crossings<'c> {
    codes: &'c mut [u128],
    first: u16,
    code: u128,
    viewport: Viewport,
    spans: u32,
}

impl SpanSink for Crossings<'_> {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;

    fn viewport(&self) -> Viewport {
        self.viewport
    }

    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Self::Error> {
        self.spans += 1;
        let width = usize::from(self.viewport.width);
        let Some(row) = span.y().checked_sub(self.first) else {
            return Ok(());
        };
        let start = usize::from(row) * width;
        let (x0, x1) = (usize::from(span.x0()), usize::from(span.x1()));
        if let Some(c) = self.codes.get_mut(start + x0) {
            *c ^= self.code;
        }
        if x1 < width {
            if let Some(c) = self.codes.get_mut(start + x1) {
                *c ^= self.code;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "scheme_tests.rs"]
mod tests;
