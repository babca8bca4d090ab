//! The frame loop of the banded engines: the Z-buffer (its depth band lent to its
//! pass), the code-fill engine (rows scanned in order, the shared apron kept), the
//! painter's and list-priority orders, the coding schemes, area subdivision and ray
//! casting. Only the fast engine, one row high, has its own. Each engine is an [`IdPass`] that fills a band's face
//! ids; the loop around it (front end, bands, line pass, composition) is this one.

use embedded_graphics_core::pixelcolor::PixelColor;

use super::compose::{Compose, FrameProbe};
use super::lines::{line_pass, Band, FaceChunks, LineMasks};
use super::transform::ProjectedVertex;
use super::{band_rows, begin_frame, FrameCtx, Settings, Stats};
use crate::camera::Camera;
use crate::mesh::{EdgeAdjacency, Mesh};
use crate::render::band::IdBand;
use crate::{Error, SpanSink};

/// Storage the caller lends for one frame of an id-filling engine. Sizes:
/// `vertices` >= the vertex count of what is drawn (the mesh's, or a depth order's
/// surfaces'); `drawn` >= faces / 32 words; `features` >= edges / 32 words; `ids` >=
/// width x [`storage_rows`](super::storage_rows); `lines` >= 2 x ceil(width / 32) x
/// band rows. The band height follows from `ids.len() / width`, as for
/// [`Workspace`](super::Workspace).
#[derive(Debug)]
pub struct IdWorkspace<'s> {
    /// The per-frame vertex cache.
    pub vertices: &'s mut [ProjectedVertex],
    /// One bit per mesh face: drawn in this view (not culled).
    pub drawn: &'s mut [u32],
    /// One bit per mesh edge: a feature edge in this view not yet drawn (scratch:
    /// the line pass clears an edge's bit after the last band it reaches).
    pub features: &'s mut [u32],
    /// Face ids of the band (0 none, else 1 + face).
    pub ids: &'s mut [u16],
    /// Line masks of the band.
    pub lines: &'s mut [u32],
}

impl IdWorkspace<'_> {
    /// Bytes of all the lent buffers.
    pub fn bytes(&self) -> usize {
        use core::mem::size_of_val;
        size_of_val(self.vertices)
            + size_of_val(self.drawn)
            + size_of_val(self.features)
            + size_of_val(self.ids)
            + size_of_val(self.lines)
    }
}

/// One visibility engine that fills face ids.
pub(crate) trait IdPass {
    /// Once per frame, after the vertices are transformed and the drawn faces marked.
    fn begin(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
    ) -> Result<(), Error>;

    /// Samples a band may hold, besides the ids (a depth band's length): the band
    /// height follows from the smaller of this and the ids.
    fn samples(&self) -> usize {
        usize::MAX
    }

    /// Adds the pass's own figures to the frame's, once the frame is set up with
    /// bands of `band_rows` rows.
    fn frame_stats(&self, _ctx: &FrameCtx<'_, '_>, _band_rows: u16, _stats: &mut Stats) {}

    /// Does the pass keep the rows of the apron a band shares with the next (a
    /// pass that scans rows in order, once each)? Else every band starts empty.
    fn keeps_rows(&self) -> bool {
        false
    }

    /// Fills the held rows of `band` from row `fresh` on (every held row, its own
    /// rows and the apron, unless the pass [keeps rows](Self::keeps_rows)) with the
    /// id of the visible face at each pixel (0 none); returns a count for
    /// `Stats::spans`.
    fn fill(
        &mut self,
        ctx: &FrameCtx<'_, '_>,
        vertices: &[ProjectedVertex],
        drawn: &[u32],
        band: &mut IdBand<'_>,
        fresh: u16,
    ) -> Result<u32, Error>;

    /// After the last band, before the sink is flushed: the pass's closing figures,
    /// or the error the whole frame shows.
    fn finish(&self, _stats: &mut Stats) -> Result<(), Error> {
        Ok(())
    }
}

/// What one id-filling frame draws: the mesh, and the vertex positions the engine's
/// polygons index (the mesh's, or a depth order's surfaces', which begin with them).
pub(crate) struct FrameInput<'a, 'm> {
    pub mesh: &'a Mesh<'m>,
    pub positions: &'a [[f32; 3]],
    pub edges: &'a EdgeAdjacency<'a>,
    pub camera: &'a Camera,
    pub settings: &'a Settings,
    pub s: u32,
}

impl<'a, 'm> FrameInput<'a, 'm> {
    /// A frame of `mesh` at its own vertex positions, with S = `s` sub-pixel bits.
    pub fn of_mesh(
        mesh: &'a Mesh<'m>,
        edges: &'a EdgeAdjacency<'a>,
        camera: &'a Camera,
        settings: &'a Settings,
        s: u32,
    ) -> Self {
        Self {
            mesh,
            positions: mesh.vertices(),
            edges,
            camera,
            settings,
            s,
        }
    }
}

/// Renders one frame with `pass` deciding the visible faces and `composer` turning
/// each finished band into spans (`compose::Flat` for a palette).
pub(crate) fn render_ids<const POLY: usize, E: IdPass, K: SpanSink, C: Compose<K>, R: FrameProbe>(
    pass: &mut E,
    input: &FrameInput<'_, '_>,
    ws: &mut IdWorkspace<'_>,
    composer: &mut C,
    sink: &mut K,
    probe: &mut R,
) -> Result<Stats, Error<K::Error>>
where
    K::Color: PixelColor,
{
    let viewport = sink.viewport();
    let (width, height) = (viewport.width, viewport.height);
    let row_words = usize::from(width).div_ceil(32);
    let samples = ws.ids.len().min(pass.samples());
    let band_rows = band_rows(viewport, samples, ws.lines.len()).map_err(Error::widen)?;
    let mut stats = Stats {
        band_rows: u32::from(band_rows),
        ..Stats::default()
    };
    let ctx = begin_frame(
        input,
        viewport,
        ws.vertices,
        ws.drawn,
        ws.features,
        &mut stats,
    )
    .map_err(Error::widen)?;
    pass.frame_stats(&ctx, band_rows, &mut stats);
    let IdWorkspace {
        vertices,
        drawn,
        features,
        ids,
        lines,
    } = ws;
    let settings = input.settings;
    if settings.mode.needs_depth() {
        pass.begin(&ctx, vertices, drawn).map_err(Error::widen)?;
    }
    let keeps_rows = pass.keeps_rows() && settings.mode.needs_depth();
    let mut band = Band {
        ids: IdBand::new(ids, width),
        lines: LineMasks {
            words: lines,
            row_words,
            rows: 0,
        },
    };
    // The line test's chunk boxes, set up once a frame where it first needs them.
    let mut chunks = FaceChunks::new();
    let mut top = 0u16;
    while top < height && band_rows > 0 {
        let rows = band_rows.min(height - top);
        let ids = &mut band.ids;
        let fresh = if keeps_rows {
            ids.advance(top, rows, height)
        } else {
            ids.held = 0;
            ids.advance(top, rows, height);
            let n = usize::from(width) * usize::from(ids.held);
            if let Some(held) = ids.ids.get_mut(..n) {
                held.fill(0);
            }
            ids.first
        };
        band.lines.reset(rows);
        stats.bands += 1;
        if settings.mode.needs_depth() {
            stats.spans += pass
                .fill(&ctx, vertices, drawn, &mut band.ids, fresh)
                .map_err(Error::widen)?;
        }
        if settings.mode.draws_lines() {
            let (edges, chunks) = (input.edges, &mut chunks);
            line_pass::<POLY>(&ctx, vertices, drawn, features, edges, chunks, &mut band);
        }
        stats.spans += composer.band(&ctx, vertices, drawn, &band, sink, probe)?;
        top += rows;
    }
    pass.finish(&mut stats).map_err(Error::widen)?;
    sink.flush().map_err(Error::Target)?;
    Ok(stats)
}
