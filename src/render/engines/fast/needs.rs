//! What a frame needs of the tables the fast engine fills as it goes (active
//! facets, active lines, the clip pool), counted without drawing: after an
//! overflow, so that the error carries the frame's true need, and on request
//! ([`FastRenderer::needs`]). Off the hot path: the row loop only calls in here
//! once a table is full.
//!
//! Each facet and line is made as the row loop makes it, at the row whose list
//! holds it, and is active from there to its last row. The active count of a row
//! is the ones begun minus the ones ended before it: the ends go into a per-row
//! count in the other half of the list heads (the lists are rebuilt before each
//! pass), summed as the rows go.

use fixed::types::extra::LeEqU32;

use super::*;
use crate::{Capacity, Shortfalls};

/// What one frame of the fast engine needs of the tables that fill as it runs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct FrameNeeds {
    /// The most facets active on one row: the `FACETS` that draws the frame
    /// ([`Capacity::ActiveFacets`]).
    pub facets: usize,
    /// The most feature lines active on one row: the `LINES` that draws it
    /// ([`Capacity::ActiveLines`]).
    pub lines: usize,
    /// Corners of the frame's clipped faces: the
    /// [`FastWorkspace::pool`] length that draws it
    /// ([`Capacity::ClippedCorners`]).
    pub clipped_corners: usize,
}

impl FrameNeeds {
    /// The larger of each need: what draws both frames.
    pub fn max(self, other: Self) -> Self {
        Self {
            facets: self.facets.max(other.facets),
            lines: self.lines.max(other.lines),
            clipped_corners: self.clipped_corners.max(other.clipped_corners),
        }
    }
}

impl<Frac: LeEqU32, const FACETS: usize, const LINES: usize> FastRenderer<Frac, FACETS, LINES> {
    /// What the frame of `baked` seen by `camera` in `viewport` needs of this
    /// engine's `FACETS` and `LINES` and of [`FastWorkspace::pool`], counted
    /// without drawing (whatever `FACETS` and `LINES` are). `ws` is checked as
    /// [`render`](Self::render) checks it (without `ids`) and is left in any
    /// state.
    pub fn needs(
        &self,
        baked: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
    ) -> Result<FrameNeeds, Error> {
        self.needs_in(OneMesh, baked, camera, settings, ws, viewport)
    }

    /// [`needs`](Self::needs) with the faces seen from `views`.
    pub(crate) fn needs_in<V: FaceViews>(
        &self,
        views: V,
        baked: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
    ) -> Result<FrameNeeds, Error> {
        self.check(baked, viewport, ws, false, Dashing::of(settings).is_some())?;
        let mesh = baked.mesh();
        let map =
            ScreenMap::with_vertices(camera, viewport, Frac::U32, mesh.vertices(), ws.vertices);
        Ok(self.count(views, baked, &map, settings, ws, viewport))
    }

    /// `error` from [`render`](Self::render), with the frame's true need when it is
    /// one of the tables [`needs`](Self::needs) counts (active facets, active lines,
    /// clipped corners), and every other of those tables the frame overflows too
    /// (then `CapacitiesExceeded`, naming each): the short API's errors. Kept out
    /// of `render`, whose row loop reports only that a table is full: counting
    /// there cost the Cortex-M4 frame 2.5 % (its inputs stayed alive across the
    /// loop).
    #[cold]
    #[inline(never)]
    pub fn with_true_need<T>(
        &self,
        error: Error<T>,
        baked: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
    ) -> Error<T> {
        self.with_true_need_in(error, OneMesh, baked, camera, settings, ws, viewport)
    }

    /// [`with_true_need`](Self::with_true_need) with the faces seen from `views`.
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn with_true_need_in<T, V: FaceViews>(
        &self,
        error: Error<T>,
        views: V,
        baked: &BakedMesh<'_>,
        camera: &Camera,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
    ) -> Error<T> {
        let Error::CapacityExceeded {
            what,
            needed,
            capacity,
        } = error
        else {
            return error;
        };
        let tables = [
            (Capacity::ActiveFacets, FACETS),
            (Capacity::ActiveLines, LINES),
            (Capacity::ClippedCorners, ws.pool.len()),
        ];
        if !tables.iter().any(|&(table, _)| table == what) {
            return error;
        }
        let Ok(frame) = self.needs_in(views, baked, camera, settings, ws, viewport) else {
            return error;
        };
        // Every table the frame overflows, each with its peak; the one that
        // stopped the frame at least as large as it was found.
        let mut short = Shortfalls::new();
        for ((table, room), peak) in
            tables
                .into_iter()
                .zip([frame.facets, frame.lines, frame.clipped_corners])
        {
            if table == what {
                short.check(table, peak.max(needed), capacity);
            } else {
                short.check(table, peak, room);
            }
        }
        match short.into_result() {
            Err(all) => all.widen(),
            Ok(()) => error,
        }
    }

    /// The counting passes: facets (and the pool) over the face lists, then lines
    /// over the line lists.
    fn count<V: FaceViews>(
        &self,
        views: V,
        baked: &BakedMesh<'_>,
        map: &ScreenMap,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
    ) -> FrameNeeds {
        let h = usize::from(viewport.height);
        let s = map.s;
        let mut needs = FrameNeeds::default();
        // Each pass counts in the other kind's half of the list heads, so the lists
        // are built again for the second.
        if settings.mode.needs_depth() {
            self.lists(views, baked, map, settings, ws, viewport, true);
            let FastWorkspace {
                vertices,
                face_links,
                heads,
                ..
            } = ws;
            let (face_heads, ends) = heads.split_at_mut(h);
            let mut pool = 0usize;
            needs.facets = peak(face_heads, face_links, ends, |f, y, end| {
                pool += count_facets(baked, map, vertices, f, y, end);
            });
            needs.clipped_corners = pool;
        }
        if settings.mode.draws_lines() {
            self.lists(views, baked, map, settings, ws, viewport, true);
            let FastWorkspace {
                vertices,
                line_links,
                heads,
                ..
            } = ws;
            let (ends, line_heads) = heads.split_at_mut(h);
            needs.lines = peak(line_heads, line_links, ends, |e, y, end| {
                let seen = OnScreen {
                    baked,
                    map,
                    cache: vertices,
                };
                if let Some(line) = make_line(seen, e) {
                    end(line.end_row(y, s));
                }
            });
        }
        needs
    }
}

/// The most items active on one row: `make` is called with each item of the
/// per-row lists (`heads`, `links`) and its row, and calls back with the last row
/// of each active item it makes. `ends` (at least a row each; zeroed here) counts
/// the items that end before each row.
fn peak(
    heads: &[u16],
    links: &[u16],
    ends: &mut [u16],
    mut make: impl FnMut(u16, i32, &mut dyn FnMut(i32)),
) -> usize {
    let rows = heads.len();
    let ends = ends.get_mut(..rows).unwrap_or_default();
    ends.fill(0);
    let (mut live, mut most) = (0usize, 0usize);
    for y in 0..rows {
        live = live.saturating_sub(usize::from(ends.get(y).copied().unwrap_or(0)));
        let mut item = heads.get(y).copied().unwrap_or(NONE);
        while item != NONE {
            make(item, y as i32, &mut |last: i32| {
                live += 1;
                // Active through its last row (the row itself when above it).
                let after = last.max(y as i32) as usize + 1;
                if let Some(n) = ends.get_mut(after) {
                    *n = n.wrapping_add(1);
                }
            });
            item = links.get(usize::from(item)).copied().unwrap_or(NONE);
        }
        most = most.max(live);
    }
    most
}

/// The facets face `f` makes at row `y`, as `FastRenderer::activate` makes them:
/// calls `end` with each one's last row; returns the pool corners it takes.
fn count_facets(
    baked: &BakedMesh<'_>,
    map: &ScreenMap,
    vertices: &[FastVertex],
    f: u16,
    y: i32,
    end: &mut dyn FnMut(i32),
) -> usize {
    let mesh = baked.mesh();
    let corners = mesh.face(usize::from(f));
    let s = map.s;
    let mut out = Facet::EMPTY;
    let mut made = |pts: &[FastVertex], corners: Corners, split: bool| {
        if facet(&mut out, pts, f, corners, y, s, split) {
            end(out.last);
        }
    };
    let clipped = corners
        .iter()
        .any(|&v| vertices.get(v as usize).is_none_or(|p| !p.inside()));
    if clipped {
        let mut poly = ClipPolygon::new();
        let positions = mesh.vertices();
        let points = corners
            .iter()
            .map(|&v| positions.get(v as usize).copied().unwrap_or_default());
        // A face that cannot be clipped stops the frame with its own error.
        if !matches!(clip_polygon(map, points, &mut poly), Ok(true)) {
            return 0;
        }
        made(&poly, Corners::Pool { start: 0 }, false);
        return poly.len();
    }
    let mut pts: Vec<FastVertex, MAX_CORNERS> = Vec::new();
    for &v in corners {
        let p = vertices.get(v as usize).copied().unwrap_or_default();
        if pts.push(p).is_err() {
            // More corners than the engine takes: its own error.
            return 0;
        }
    }
    let n = pts.len();
    let bent = n >= 4 && mesh.kept_planarity(usize::from(f)) == Some(false);
    if bent && n == 4 && convex(&pts) {
        made(&pts, Corners::Face, true);
    } else if bent && !folds(&pts) {
        for k in 1..n.saturating_sub(1) {
            let tri = [0, k, k + 1].map(|i| pts.get(i).copied().unwrap_or_default());
            made(&tri, Corners::Fan(k as u8), false);
        }
    } else {
        made(&pts, Corners::Face, false);
    }
    0
}

/// The active line edge `e` makes, as `FastRenderer::activate_line` makes it
/// (its dash phase aside, which does not change its rows).
fn make_line(seen: OnScreen<'_, '_>, e: u16) -> Option<ActiveLine> {
    let edge = seen.baked.edges().get(usize::from(e))?;
    let end = |v: u16| seen.cache.get(usize::from(v)).copied().unwrap_or_default();
    let (a, b) = (end(edge.a), end(edge.b));
    let ends = [a.key(), b.key()];
    let (a, b) = if a.inside() && b.inside() {
        (a, b)
    } else {
        let positions = seen.baked.mesh().vertices();
        let p = |v: u16| positions.get(usize::from(v)).copied().unwrap_or_default();
        clip_segment(seen.map, p(edge.a), p(edge.b))?
    };
    ActiveLine::new(a, b, edge.faces, ends, seen.map.s, None).map(|(line, _)| line)
}
