//! The fast engine's y-buckets: before the row loop, each face's facing bit, and
//! the drawn faces and feature lines linked into per-row lists by the first row
//! each can reach, where the row loop makes them active.

use fixed::types::extra::LeEqU32;

use super::*;

/// What the set-up found, for the row loop and `Stats`.
pub(super) struct Lists {
    /// Faces drawn: neither culled nor skipped, and reaching the frame.
    pub(super) faces_drawn: u32,
    /// Edges that are feature lines in this view.
    pub(super) feature_edges: u32,
    /// Columns that the drawn faces' spans may reach: rows are cleared there only.
    pub(super) columns: (usize, usize),
}

impl<Frac: LeEqU32, const FACETS: usize, const LINES: usize> FastRenderer<Frac, FACETS, LINES> {
    /// Facing bits, and the per-row lists of drawn faces (when `faces`) and feature
    /// lines.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn lists<V: FaceViews>(
        &self,
        views: V,
        baked: &BakedMesh<'_>,
        map: &ScreenMap,
        settings: &Settings,
        ws: &mut FastWorkspace<'_>,
        viewport: Viewport,
        faces: bool,
    ) -> Lists {
        let mesh = baked.mesh();
        let s = map.s;
        let (width, height) = (i32::from(viewport.width), i32::from(viewport.height));
        let cull = culls(settings, baked);
        let h = usize::from(viewport.height);
        let (face_heads, line_heads) = ws.heads.split_at_mut(h);
        face_heads.fill(NONE);
        line_heads.get_mut(..h).unwrap_or_default().fill(NONE);
        let mut lists = Lists {
            faces_drawn: 0,
            feature_edges: 0,
            columns: (usize::MAX, 0),
        };
        let depth = settings.mode.needs_depth() && faces;
        // Back faces that no ray reaches are skipped (see `holes`).
        let holes = if cull {
            None
        } else {
            HoleBoxes::new(baked.edges(), ws.vertices, s)
        };
        for (f, plane) in baked.planes().iter().enumerate() {
            let facing = views.facing(f, plane, &map.viewpoint, ws.facing);
            set_bit(ws.facing, f, facing);
            if cull && !facing {
                continue;
            }
            // Rows and columns the face can reach; a face to be clipped starts at row 0.
            let (mut lo, mut hi, mut left, mut right, mut clipped) =
                (i32::MAX, i32::MIN, i32::MAX, i32::MIN, false);
            for &v in mesh.face(f) {
                let p = ws.vertices.get(v as usize).copied().unwrap_or_default();
                clipped |= !p.inside();
                let (x, y) = p.half();
                (lo, hi) = (lo.min(y), hi.max(y));
                (left, right) = (left.min(x), right.max(x));
            }
            if let Some(holes) = &holes {
                // Every vertex is inside when there are boxes: none clipped.
                if !facing
                    && turns_away(mesh.face(f), ws.vertices)
                    && !holes.meets(left, right, lo, hi)
                {
                    continue;
                }
            }
            let first = if clipped {
                lists.columns = (0, usize::MAX);
                0
            } else {
                let (first, end) = (step::row_at(lo, s), step::row_at(hi, s));
                let (c0, c1) = (step::row_at(left, s), step::row_at(right, s));
                if first >= height || end <= 0 || first >= end || c0 >= width || c1 <= 0 {
                    continue;
                }
                // A crossing stepped in 16.16 may land a pixel past the face's
                // corners: two columns of margin.
                let (c0, c1) = ((c0 - 2).max(0) as usize, (c1 + 2).max(0) as usize);
                lists.columns = (lists.columns.0.min(c0), lists.columns.1.max(c1));
                first.max(0)
            };
            lists.faces_drawn += 1;
            if !depth {
                continue;
            }
            if let (Some(head), Some(link)) =
                (face_heads.get_mut(first as usize), ws.face_links.get_mut(f))
            {
                *link = *head;
                *head = f as u16;
            }
        }
        if !settings.mode.draws_lines() {
            return lists;
        }
        for (e, edge) in baked.edges().iter().enumerate() {
            let feature = match edge.kind {
                EdgeKind::Boundary | EdgeKind::NonManifold | EdgeKind::Crease => true,
                EdgeKind::Inert => false,
                EdgeKind::Smooth => {
                    let [f, g] = edge.faces;
                    bit(ws.facing, usize::from(f)) != bit(ws.facing, usize::from(g))
                }
            };
            if !feature {
                continue;
            }
            lists.feature_edges += 1;
            let a = ws
                .vertices
                .get(usize::from(edge.a))
                .copied()
                .unwrap_or_default();
            let b = ws
                .vertices
                .get(usize::from(edge.b))
                .copied()
                .unwrap_or_default();
            let first = if a.inside() && b.inside() {
                // Pixels lie in the rows and columns of the ends' pixels.
                let (lo, hi) = (a.y.min(b.y) >> s, a.y.max(b.y) >> s);
                let (l, r) = (a.x.min(b.x) >> s, a.x.max(b.x) >> s);
                if i32::from(lo) >= height || hi < 0 || i32::from(l) >= width || r < 0 {
                    continue;
                }
                i32::from(lo.max(0))
            } else {
                0
            };
            if let (Some(head), Some(link)) =
                (line_heads.get_mut(first as usize), ws.line_links.get_mut(e))
            {
                *link = *head;
                *head = e as u16;
            }
        }
        lists
    }
}
