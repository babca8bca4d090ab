//! The fast engine's frame: set-up (vertex cache; facing and per-row lists, in
//! `buckets`), then one row at a time: facets made active as the row reaches them
//! fill the row, lines are tested against it, spans go out.

use fixed::types::extra::LeEqU32;

use crate::render::{DrawMode, LineVisibility};
use crate::Capacity;
use crate::Pattern;
use segments::{classify, Crossing, Run, Scene, SegmentStats};

use super::*;

impl<Frac: LeEqU32, const FACETS: usize, const LINES: usize> FastRenderer<Frac, FACETS, LINES> {
    /// Renders `baked` seen by `camera` into `sink`, whose viewport is the frame.
    /// Colours come from `palette`; `probe` sees each finished row (for the `--ids`
    /// and `--lines` outputs; `&mut ()` ignores them).
    #[allow(clippy::too_many_arguments)]
    pub fn render<K: SpanSink, P: Palette<Color = K::Color>, R: FrameProbe>(
        &mut self,
        baked: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>> {
        self.render_in(OneMesh, baked, camera, settings, ws, palette, sink, probe)
    }

    /// [`render`](Self::render) with the faces seen from `views`: one mesh from
    /// the camera, or a scene's instances each from its own space (whose facing
    /// bits `ws.facing` holds already).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn render_in<
        V: FaceViews,
        K: SpanSink,
        P: Palette<Color = K::Color>,
        R: FrameProbe,
    >(
        &mut self,
        views: V,
        baked: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>> {
        // Its own copy of the frame loop for dashes along the edges, so that
        // the screen pattern's has no dash work (measured: one loop for both
        // cost the screen pattern's frames 3 to 6 %).
        let frame = (baked, camera, settings);
        match Dashing::of(settings) {
            Some(d) => self.frame::<true, V, K, P, R>(d, views, frame, ws, palette, sink, probe),
            None => {
                let none = Dashing::NONE;
                self.frame::<false, V, K, P, R>(none, views, frame, ws, palette, sink, probe)
            }
        }
    }

    /// [`render`](Self::render), with dashes along the edges `dashing` when
    /// `ALONG` (else it is not read).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn frame<
        const ALONG: bool,
        V: FaceViews,
        K: SpanSink,
        P: Palette<Color = K::Color>,
        R: FrameProbe,
    >(
        &mut self,
        dashing: Dashing,
        views: V,
        (baked, camera, settings): (&BakedMesh<'_>, &Camera, &Settings),
        ws: &mut FastWorkspace<'_>,
        palette: &P,
        sink: &mut K,
        probe: &mut R,
    ) -> Result<Stats, Error<K::Error>> {
        let viewport = sink.viewport();
        let s = Frac::U32;
        self.check(baked, viewport, ws, R::ACTIVE, ALONG)
            .map_err(Error::widen)?;
        let mesh = baked.mesh();
        let (width, height) = (usize::from(viewport.width), usize::from(viewport.height));
        let map = ScreenMap::with_vertices(camera, viewport, s, mesh.vertices(), ws.vertices);
        let by_segment = settings.lines == LineVisibility::BySegment
            && matches!(settings.mode, DrawMode::HiddenRemoved | DrawMode::Dashed)
            && ws.segments.is_some()
            && !baked.vertex_faces().starts.is_empty();
        let mut lists = self.lists(views, baked, &map, settings, ws, viewport, !by_segment);
        let mut segment_stats = SegmentStats::default();
        let pieces = by_segment
            && self
                .by_segment(baked, settings, ws, viewport, &mut segment_stats)
                .map_err(Error::widen)?;
        if by_segment && !pieces {
            // Left to the per-pixel test: the faces' lists too.
            lists = self.lists(views, baked, &map, settings, ws, viewport, true);
        }
        let (depth_step_near, depth_step_far) = map.depth_steps();
        let mut stats = Stats {
            faces: mesh.face_count() as u32,
            faces_drawn: lists.faces_drawn,
            feature_edges: lists.feature_edges,
            bands: u32::from(viewport.height),
            band_rows: 1,
            depth_buffer_bytes: (width * 4) as u32,
            depth_step_near,
            depth_step_far,
            segments: segment_stats,
            ..Stats::default()
        };
        self.facets.clear();
        self.lines.clear();
        let FastWorkspace {
            vertices,
            face_links,
            line_links,
            heads,
            row,
            masks,
            pool,
            ids,
            slopes,
            phases,
            segments,
            ..
        } = ws;
        let (runs, boundaries): (&[Run], &[Crossing]) = match segments {
            Some(seg) if pieces => (seg.work.runs, seg.lists.crossings()),
            _ => (&[], &[]),
        };
        let (face_heads, line_heads) = heads.split_at(height);
        let row = row.get_mut(..width).unwrap_or_default();
        clear_row(row);
        let words = width.div_ceil(32);
        let masks = masks
            .get_mut(..line_masks(ALONG) * words)
            .unwrap_or_default();
        let solid = Settings {
            pattern: Pattern::SOLID,
            ..*settings
        };
        let mut pool_used = 0usize;
        let mut shades = Shades::new(baked.planes(), map.viewpoint, views);
        let depth = settings.mode.needs_depth() && !pieces;
        let test = if pieces {
            LineTest::Pieces
        } else if depth {
            LineTest::Row
        } else {
            LineTest::None
        };
        for y in 0..height {
            let yi = y as i32;
            if depth {
                let mut f = face_heads.get(y).copied().unwrap_or(NONE);
                while f != NONE {
                    pool_used = self
                        .activate(baked, &map, vertices, pool, pool_used, slopes, f, yi)
                        .map_err(Error::widen)?;
                    f = face_links.get(usize::from(f)).copied().unwrap_or(NONE);
                }
                stats.peak_faces = stats.peak_faces.max(self.facets.len() as u32);
                // Cells outside the faces' columns stay as the first clear left them.
                let (c0, c1) = lists.columns;
                clear_row(row.get_mut(c0..c1.min(width)).unwrap_or_default());
                let src = Source {
                    mesh,
                    cache: vertices,
                    pool,
                };
                stats.spans += self
                    .facets
                    .fill_row(&src, yi, s, row)
                    .map_err(Error::widen)?;
            }
            clear_row(masks);
            if settings.mode.draws_lines() {
                let mut e = line_heads.get(y).copied().unwrap_or(NONE);
                while e != NONE {
                    let seen = OnScreen {
                        baked,
                        map: &map,
                        cache: vertices,
                    };
                    self.activate_line::<ALONG>(dashing, seen, phases, runs, e, &mut stats)
                        .map_err(Error::widen)?;
                    e = line_links.get(usize::from(e)).copied().unwrap_or(NONE);
                }
                let (visible, hidden) = masks.split_at_mut(words);
                let (hidden, gaps) = hidden.split_at_mut(words.min(hidden.len()));
                let cache: &[FastVertex] = vertices;
                let beside = |face: u16, [a, b]: [u32; 2], e: (i32, i32), touches: bool| {
                    let corners = mesh.face(usize::from(face));
                    let corner = |v: &u32| cache.get(*v as usize).copied().unwrap_or_default();
                    if !touches {
                        // Positions compared as one word each; an end outside
                        // touches nothing.
                        let touches = corners.iter().any(|v| {
                            let p = corner(v);
                            let k = p.key();
                            (k == a || k == b) && p.inside()
                        });
                        if !touches {
                            return Beside::Apart;
                        }
                        if !corners.iter().all(|v| corner(v).inside()) {
                            return Beside::Clipped;
                        }
                    }
                    if contains(corners.iter().map(|v| corner(v).half()), e) {
                        Beside::Covers
                    } else {
                        Beside::Misses
                    }
                };
                let faces = Slopes {
                    entries: slopes,
                    facets: &self.facets,
                };
                let lines = &mut self.lines;
                if ALONG {
                    let gaps = GapMask {
                        words: gaps,
                        on: dashing.on,
                        phases,
                        line: 0,
                    };
                    line_row(
                        lines, yi, s, test, row, &faces, &beside, boundaries, visible, hidden, gaps,
                    );
                } else {
                    let gaps = NoGaps;
                    line_row(
                        lines, yi, s, test, row, &faces, &beside, boundaries, visible, hidden, gaps,
                    );
                }
            }
            let (visible, hidden) = masks.split_at_mut(words);
            if R::ACTIVE {
                probe_ids(depth, row, ids);
                probe.row(y as u16, ids.get(..width).unwrap_or(&[]), visible, hidden);
            }
            if ALONG {
                // The gaps leave the hidden mask; the hidden pixels left are
                // drawn solid.
                let (hidden, gaps) = hidden.split_at_mut(words.min(hidden.len()));
                for (h, g) in hidden.iter_mut().zip(gaps.iter()) {
                    *h &= !g;
                }
            }
            let finished = FaceRow {
                y: y as u16,
                cells: row,
                columns: lists.columns,
            };
            let row_settings = if ALONG { &solid } else { settings };
            stats.spans += emit_row(
                finished,
                row_settings,
                visible,
                hidden,
                palette,
                &mut shades,
                sink,
            )
            .map_err(Error::Target)?;
        }
        sink.flush().map_err(Error::Target)?;
        Ok(stats)
    }

    /// Hidden lines by the segment: classifies the frame's drawn edges into the
    /// lent runs and boundaries. False: left to the per-pixel test.
    fn by_segment(
        &self,
        baked: &BakedMesh<'_>,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
        stats: &mut SegmentStats,
    ) -> Result<bool, Error> {
        let Some(seg) = ws.segments.as_mut() else {
            return Ok(false);
        };
        let cull = culls(settings, baked);
        let scene = Scene {
            mesh: baked.mesh(),
            edges: baked.edges(),
            around: baked.vertex_faces(),
            piercings: baked.piercings(),
            cache: ws.vertices,
            facing: ws.facing,
            cull,
            s: Frac::U32,
            width: viewport.width,
            height: viewport.height,
        };
        classify(&scene, &mut seg.lists, &mut seg.work, stats)
    }

    /// The lent storage and the frame's limits.
    pub(super) fn check(
        &self,
        baked: &BakedMesh<'_>,
        viewport: Viewport,
        ws: &FastWorkspace<'_>,
        probe: bool,
        along: bool,
    ) -> Result<(), Error> {
        let s = Frac::U32;
        if s > FAST_MAX_SUBPIXEL_BITS {
            return Err(Error::SubpixelTooFine {
                bits: s,
                max: FAST_MAX_SUBPIXEL_BITS,
            });
        }
        let (w, h) = (viewport.width, viewport.height);
        if i32::from(w.max(h)) > guard_px(s) {
            return Err(Error::ViewportTooLarge {
                width: u32::from(w),
                height: u32::from(h),
            });
        }
        let mesh = baked.mesh();
        let faces = mesh.face_count();
        let (w, h) = (usize::from(w), usize::from(h));
        need(Capacity::Vertices, mesh.vertices().len(), ws.vertices.len())?;
        need(Capacity::FaceBits, faces.div_ceil(32), ws.facing.len())?;
        need(Capacity::Faces, faces, ws.face_links.len())?;
        need(Capacity::Faces, faces, ws.slopes.len())?;
        need(Capacity::Edges, baked.edges().len(), ws.line_links.len())?;
        need(Capacity::Rows, 2 * h, ws.heads.len())?;
        need(Capacity::RowWidth, w, ws.row.len())?;
        need(
            Capacity::LineMasks,
            line_masks(along) * w.div_ceil(32),
            ws.masks.len(),
        )?;
        if probe {
            need(Capacity::RowWidth, w, ws.ids.len())?;
        }
        if along {
            need(Capacity::DashPhases, LINES, ws.phases.len())?;
        }
        Ok(())
    }

    /// Makes the facets of face `f` at row `y`: clipped into the pool when a corner
    /// is outside, else the face (or its fan triangles when bent). Returns the pool
    /// entries used.
    // This and the two below keep their parameters apart: with the mesh, the map and
    // the vertex cache passed to them as one `OnScreen`, suzanne's M4 frame took
    // 0.9 % more instructions (the row loop they are called from compiles otherwise).
    #[allow(clippy::too_many_arguments)]
    fn activate(
        &mut self,
        baked: &BakedMesh<'_>,
        map: &ScreenMap,
        vertices: &[FastVertex],
        pool: &mut [FastVertex],
        pool_used: usize,
        slopes: &mut [u16],
        f: u16,
        y: i32,
    ) -> Result<usize, Error> {
        let mesh = baked.mesh();
        let corners = mesh.face(usize::from(f));
        let n = corners.len();
        // Triangles and quads, the common case, are gathered on the stack.
        let mut pts = [FastVertex::ZERO; 4];
        let mut clipped = n > pts.len();
        for (p, &v) in pts.iter_mut().zip(corners) {
            *p = vertices.get(v as usize).copied().unwrap_or_default();
            clipped |= !p.inside();
        }
        if n <= pts.len() && !clipped {
            let bent = n == 4 && mesh.kept_planarity(usize::from(f)) == Some(false);
            self.push_facets(pts.get(..n).unwrap_or(&[]), bent, f, y, map.s, slopes)?;
            return Ok(pool_used);
        }
        self.activate_other(baked, map, vertices, pool, pool_used, slopes, f, y)
    }

    /// [`activate`](Self::activate) for faces of more than four corners or with a
    /// corner outside: clipped into the pool, or gathered into a polygon.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn activate_other(
        &mut self,
        baked: &BakedMesh<'_>,
        map: &ScreenMap,
        vertices: &[FastVertex],
        pool: &mut [FastVertex],
        pool_used: usize,
        slopes: &mut [u16],
        f: u16,
        y: i32,
    ) -> Result<usize, Error> {
        let mesh = baked.mesh();
        let corners = mesh.face(usize::from(f));
        let n = corners.len();
        let clipped = corners
            .iter()
            .any(|&v| vertices.get(v as usize).is_none_or(|p| !p.inside()));
        if clipped {
            return self.activate_clipped(baked, map, pool, pool_used, slopes, f, y);
        }
        let mut poly: Vec<FastVertex, MAX_CORNERS> = Vec::new();
        for &v in corners {
            let p = vertices.get(v as usize).copied().unwrap_or_default();
            poly.push(p).map_err(|_| Error::CapacityExceeded {
                what: Capacity::FaceCorners,
                needed: n,
                capacity: MAX_CORNERS,
            })?;
        }
        let bent = mesh.kept_planarity(usize::from(f)) == Some(false);
        self.push_facets(&poly, bent, f, y, map.s, slopes)?;
        Ok(pool_used)
    }

    /// [`activate_other`](Self::activate_other) for a face with a corner outside:
    /// clipped into the pool. Apart, so that its clip buffers are not on the stack
    /// of every face of more than four corners.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn activate_clipped(
        &mut self,
        baked: &BakedMesh<'_>,
        map: &ScreenMap,
        pool: &mut [FastVertex],
        pool_used: usize,
        slopes: &mut [u16],
        f: u16,
        y: i32,
    ) -> Result<usize, Error> {
        let mesh = baked.mesh();
        let mut poly = ClipPolygon::new();
        let positions = mesh.vertices();
        let points = mesh
            .face(usize::from(f))
            .iter()
            .map(|&v| positions.get(v as usize).copied().unwrap_or_default());
        if !clip_polygon(map, points, &mut poly)? {
            return Ok(pool_used);
        }
        let end = pool_used + poly.len();
        // Pool positions are 16-bit in a facet: a larger pool is used up to there.
        let room = pool.len().min(usize::from(u16::MAX));
        let Some(slots) = pool.get_mut(pool_used..end).filter(|_| end <= room) else {
            return Err(Error::CapacityExceeded {
                what: Capacity::ClippedCorners,
                needed: end,
                capacity: room,
            });
        };
        slots.copy_from_slice(&poly);
        let corners = Corners::Pool {
            start: pool_used as u16,
        };
        let made = self
            .facets
            .push_with(|out| facet(out, &poly, f, corners, y, map.s, false))?;
        set_slope(slopes, f, made);
        Ok(end)
    }

    /// The facets of face `f` with (unclipped) corners `pts` at row `y`: its fan
    /// triangles when it is `bent` and its fan does not fold on screen, else the
    /// polygon; records the face's steepest slope.
    fn push_facets(
        &mut self,
        pts: &[FastVertex],
        bent: bool,
        f: u16,
        y: i32,
        s: u32,
        slopes: &mut [u16],
    ) -> Result<(), Error> {
        let made = if bent && pts.len() == 4 && convex(pts) {
            // One facet, split at its diagonal: the same pixels as its fan.
            self.facets
                .push_with(|out| facet(out, pts, f, Corners::Face, y, s, true))?
        } else if bent && !folds(pts) {
            let mut slope = 0;
            for k in 1..pts.len().saturating_sub(1) {
                let tri = [0, k, k + 1].map(|i| pts.get(i).copied().unwrap_or_default());
                let fan = Corners::Fan(k as u8);
                let (one, _) = self
                    .facets
                    .push_with(|out| facet(out, &tri, f, fan, y, s, false))?;
                slope = slope.max(one);
            }
            // Several planes: the line test takes the steepest slope.
            (slope, None)
        } else {
            self.facets
                .push_with(|out| facet(out, pts, f, Corners::Face, y, s, false))?
        };
        set_slope(slopes, f, made);
        Ok(())
    }

    /// Makes the active line of edge `e` (clipped when an end is outside), its
    /// dash phase in `phases` when `ALONG`.
    fn activate_line<const ALONG: bool>(
        &mut self,
        dashing: Dashing,
        seen: OnScreen<'_, '_>,
        phases: &mut [DashPhase],
        runs: &[Run],
        e: u16,
        stats: &mut Stats,
    ) -> Result<(), Error> {
        let OnScreen {
            baked,
            map,
            cache: vertices,
        } = seen;
        let Some(edge) = baked.edges().get(usize::from(e)) else {
            return Ok(());
        };
        let a = vertices
            .get(usize::from(edge.a))
            .copied()
            .unwrap_or_default();
        let b = vertices
            .get(usize::from(edge.b))
            .copied()
            .unwrap_or_default();
        let ea = a;
        let keys = [a.key(), b.key()];
        let ends = if a.inside() && b.inside() {
            Some((a, b))
        } else {
            let positions = baked.mesh().vertices();
            let p = |v: u16| positions.get(usize::from(v)).copied().unwrap_or_default();
            clip_segment(map, p(edge.a), p(edge.b))
        };
        if let Some((a, b)) = ends {
            let along = ALONG.then(|| (dashing, dash::anchor(map, baked, edge, ea, a)));
            if let Some((mut line, phase)) = ActiveLine::new(a, b, edge.faces, keys, map.s, along) {
                if let Some(run) = runs.get(usize::from(e)) {
                    line.with_pieces(run.first, run.len, run.hidden);
                }
                let full = Error::CapacityExceeded {
                    what: Capacity::ActiveLines,
                    needed: LINES + 1,
                    capacity: LINES,
                };
                self.lines.push(line).map_err(|_| full)?;
                if ALONG {
                    // Room: checked at the frame's start (`LINES` phases).
                    if let Some(slot) = phases.get_mut(self.lines.len() - 1) {
                        *slot = phase;
                    }
                }
                stats.peak_edges = stats.peak_edges.max(self.lines.len() as u32);
            }
        }
        Ok(())
    }
}

/// A `slopes` entry with this bit holds the slot of the face's one facet (whose
/// record the line test reads in the same row), else the steepest slope of its
/// facets (saturated below the bit).
const SLOT: u16 = 0x8000;

/// Records for the line test the face's facet slot (a facet of one plane) or its
/// steepest slope.
fn set_slope(slopes: &mut [u16], f: u16, (slope, slot): (u16, Option<u16>)) {
    if let Some(s) = slopes.get_mut(usize::from(f)) {
        *s = match slot {
            Some(slot) if slot < SLOT => SLOT | slot,
            _ => slope.min(SLOT - 1),
        };
    }
}

/// The line test's view of the faces: `slopes` entries and the active facets.
struct Slopes<'a, const N: usize> {
    entries: &'a [u16],
    facets: &'a ActiveFacets<N>,
}

impl<const N: usize> FaceSlopes for Slopes<'_, N> {
    #[inline(always)]
    fn gradient(&self, face: u16) -> Option<(i32, i32)> {
        let entry = self.entries.get(usize::from(face)).copied().unwrap_or(0);
        if entry & SLOT == 0 {
            return None;
        }
        self.facets.gradient(entry & !SLOT, face)
    }

    #[inline(always)]
    fn slope(&self, face: u16) -> u16 {
        let entry = self.entries.get(usize::from(face)).copied().unwrap_or(0);
        if entry & SLOT == 0 {
            entry
        } else {
            // The face's one facet (split in two planes at its diagonal).
            self.facets.slope(entry & !SLOT)
        }
    }
}

/// The face ids of a row for a probe (1 + face, 0 none). Out of line: the host's
/// instruction counts leave it out, as firmware has no probe.
#[inline(never)]
fn probe_ids(depth: bool, row: &[u32], ids: &mut [u16]) {
    for (id, &cell) in ids.iter_mut().zip(row.iter()) {
        *id = if depth {
            (0xFFFF - (cell & 0xFFFF) as u16).wrapping_add(1)
        } else {
            0
        };
    }
}
