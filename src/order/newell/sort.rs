//! The sort: the list of fragments, Newell's tests, shuffles and splits, then the
//! compaction, the ranks and the seams.

use core::cmp::Reverse;
use core::ops::Range;

use super::{NewellOptions, NewellOrder, NewellStorage};
use crate::camera::Camera;
use crate::mesh::{Mesh, Viewpoint, MAX_FACES};
use crate::order::bsp::PLANE_TOLERANCE;
use crate::order::build::need;
use crate::order::plane::{dot, exact_side, split_point, vertex, Plane, Side};
use crate::order::seams::{insert_seam_vertices, Seams};
use crate::sort::sort_by_key;
use crate::Error;

/// The mark of a slot whose fragment was split (its pieces replace it).
const DEAD: u32 = u32::MAX;
/// The place of a live fragment that is not in the list (culled, or zero area).
const NOT_DRAWN: u32 = u32::MAX - 1;

/// A slot's `[x_min, x_max, y_min, y_max, depth_min, depth_max]`.
type Extent = [f32; 6];

/// The view, in f64.
struct View {
    /// Rows of the affine map to clip coordinates, applied to `p - eye`.
    rows: [[f64; 3]; 3],
    eye: [f64; 3],
    perspective: bool,
    viewpoint: Viewpoint,
}

impl View {
    fn new(camera: &Camera) -> Self {
        Self {
            rows: camera.clip_rows(1.0).map(|r| r.map(f64::from)),
            eye: camera.eye().map(f64::from),
            perspective: camera.is_perspective(),
            viewpoint: camera.viewpoint(),
        }
    }

    /// `(x, y, depth)`: clip x and y, and the distance in front of the eye.
    fn clip(&self, p: [f32; 3]) -> [f64; 3] {
        let p = p.map(f64::from);
        let d = [p[0] - self.eye[0], p[1] - self.eye[1], p[2] - self.eye[2]];
        self.rows.map(|r| dot(r, d))
    }

    /// Screen position (normalised device units, y up), `None` at or behind the
    /// eye under perspective.
    fn screen(&self, p: [f32; 3]) -> Option<[f64; 2]> {
        let [x, y, w] = self.clip(p);
        if !self.perspective {
            Some([x, y])
        } else if w > 0.0 {
            Some([x / w, y / w])
        } else {
            None
        }
    }

    /// The eye's side of `plane`: `On` when it is on the plane (within the
    /// tolerance), so that the plane's polygons are seen edge-on.
    fn eye_side(&self, plane: &Plane) -> Side {
        match self.viewpoint {
            Viewpoint::Perspective { eye } => plane.side_of(plane.distance(eye), eye),
            Viewpoint::Orthographic { direction_to_eye } => {
                exact_side(dot(plane.n, direction_to_eye.map(f64::from)))
            }
        }
    }
}

/// An f32 as a u32 of the same order (finite values).
fn ordered(x: f32) -> u32 {
    let b = x.to_bits();
    if b >> 31 == 1 {
        !b
    } else {
        b | (1 << 31)
    }
}

/// The sort's state: the lent slices and how much of each is used.
struct Sorter<'a, 'b, 'm> {
    mesh: &'b Mesh<'m>,
    view: View,
    tolerance_sq: f64,
    vertices: &'a mut [[f32; 3]],
    vertex_count: usize,
    base: usize,
    seams: &'a mut [[u32; 2]],
    indices: &'a mut [u32],
    index_count: usize,
    offsets: &'a mut [u32],
    source: &'a mut [u16],
    boxes: &'a mut [Extent],
    /// `list[..len]`: the drawn fragments, paint order (far first) up to `head`,
    /// then the head, then the rest sorted by farthest depth.
    list: &'a mut [u32],
    len: usize,
    /// Per slot: [`DEAD`], or the generation in which it was moved ahead (marked).
    marks: &'a mut [u32],
    /// Slots made so far.
    slots: usize,
    /// Twice the words of `list` (for errors about `work`).
    work_words: usize,
    generation: u32,
    /// Marked fragments moved ahead again in this generation (at most the fragments
    /// left to paint).
    forced: usize,
    splits: usize,
    shuffles: usize,
    unresolved: usize,
    steps: usize,
    max_steps: usize,
}

pub(super) fn run<'s>(
    mesh: &Mesh<'_>,
    camera: &Camera,
    cull: bool,
    storage: NewellStorage<'s>,
    options: NewellOptions,
) -> Result<NewellOrder<'s>, Error> {
    let NewellStorage {
        vertices,
        indices,
        offsets,
        source,
        rank,
        seams,
        boxes,
        work,
    } = storage;
    let work_words = work.len();
    let half = work_words / 2;
    let (list, marks) = work.split_at_mut(half);
    let mut s = Sorter {
        mesh,
        view: View::new(camera),
        tolerance_sq: PLANE_TOLERANCE * PLANE_TOLERANCE,
        vertices,
        vertex_count: 0,
        base: mesh.vertices().len(),
        seams,
        indices,
        index_count: 0,
        offsets,
        source,
        boxes,
        list,
        len: 0,
        marks,
        slots: 0,
        work_words,
        generation: 1,
        forced: 0,
        splits: 0,
        shuffles: 0,
        unresolved: 0,
        steps: 0,
        max_steps: options.max_steps,
    };
    s.start(cull)?;
    s.settle()?;
    let (live, drawn) = s.compact()?;
    s.finish(live, drawn, rank)
}

impl<'a> Sorter<'a, '_, '_> {
    fn err(needed: usize, capacity: usize) -> Error {
        Error::CapacityExceeded { needed, capacity }
    }

    fn at(&self, k: usize) -> u32 {
        self.list.get(k).copied().unwrap_or(0)
    }

    fn range(&self, f: usize) -> (usize, usize) {
        match (self.offsets.get(f), self.offsets.get(f.saturating_add(1))) {
            (Some(&s), Some(&e)) if s <= e => (s as usize, e as usize),
            _ => (0, 0),
        }
    }

    fn idx(&self, f: usize) -> &[u32] {
        let (s, e) = self.range(f);
        self.indices.get(s..e).unwrap_or(&[])
    }

    fn face(&self, f: usize) -> usize {
        self.source.get(f).map_or(0, |&s| usize::from(s))
    }

    fn extent(&self, f: usize) -> Extent {
        self.boxes.get(f).copied().unwrap_or([0.0; 6])
    }

    fn plane(&self, f: usize) -> Plane {
        Plane::of_record(self.mesh, self.face(f) as u32, self.tolerance_sq)
    }

    /// The plane of fragment `f`'s face and the face's own thickness about it: the
    /// largest distance of its vertices (0 for a planar face, in the units of
    /// [`Plane::distance`]).
    fn banded(&self, f: usize) -> (Plane, f64) {
        let plane = self.plane(f);
        let corners = self.mesh.face(self.face(f));
        let band = corners.iter().fold(0.0f64, |b, &i| {
            b.max(plane.distance(vertex(self.mesh.vertices(), i)).abs())
        });
        (plane, band)
    }

    /// How many vertices of fragment `f` lie in front of and behind `plane`, beyond
    /// the tolerance and beyond `band` (a face that is not planar is known no better
    /// than its thickness: a vertex within it counts as on the plane).
    fn sides(&self, f: usize, (plane, band): &(Plane, f64)) -> (usize, usize) {
        let mut sides = (0, 0);
        for &i in self.idx(f) {
            let p = vertex(self.vertices, i);
            let s = plane.distance(p);
            if s.abs() <= *band {
                continue;
            }
            match plane.side_of(s, p) {
                Side::Front => sides.0 += 1,
                Side::Back => sides.1 += 1,
                Side::On => {}
            }
        }
        sides
    }

    /// The list's sort key: farthest depth first, then slot.
    fn key(&self, f: u32) -> (Reverse<u32>, u32) {
        let e = self.extent(f as usize);
        (Reverse(ordered(e[5])), f)
    }

    /// Copies the mesh (its vertices and faces become slots `0..faces`) and lists
    /// the faces drawn in the view, farthest first.
    fn start(&mut self, cull: bool) -> Result<(), Error> {
        let mesh = self.mesh;
        let from = mesh.vertices();
        let capacity = self.vertices.len();
        self.vertices
            .get_mut(..from.len())
            .ok_or(Self::err(from.len(), capacity))?
            .copy_from_slice(from);
        self.vertex_count = from.len();
        let faces = mesh.face_count();
        let capacity = self.offsets.len();
        *self
            .offsets
            .first_mut()
            .ok_or(Self::err(faces.saturating_add(1), capacity))? = 0;
        for f in 0..faces {
            for &i in mesh.face(f) {
                self.put(i)?;
            }
            // Face ids are below MAX_FACES < 2^16.
            self.new_slot(f as u16)?;
        }
        let viewpoint = self.view.viewpoint;
        for f in 0..faces {
            let drawn = !cull || mesh.faces_viewpoint(f, &viewpoint);
            if drawn && !self.plane(f).is_degenerate() {
                let slot = self.list.get_mut(self.len).ok_or(Self::err(
                    self.len.saturating_add(1).saturating_mul(2),
                    self.work_words,
                ))?;
                *slot = f as u32;
                self.len += 1;
            }
        }
        let (list, len) = (core::mem::take(&mut self.list), self.len);
        if let Some(drawn) = list.get_mut(..len) {
            sort_by_key(drawn, |&f| self.key(f));
        }
        self.list = list;
        Ok(())
    }

    /// Takes the next slot for the fragment just written (`offsets[slots]` to the
    /// index count), with source face `face`: its box, no mark.
    fn new_slot(&mut self, face: u16) -> Result<usize, Error> {
        let f = self.slots;
        let end = u32::try_from(self.index_count).map_err(|_| Self::err(self.index_count, 0))?;
        let capacity = self.offsets.len();
        *self
            .offsets
            .get_mut(f.saturating_add(1))
            .ok_or(Self::err(f.saturating_add(2), capacity))? = end;
        let capacity = self.source.len();
        *self
            .source
            .get_mut(f)
            .ok_or(Self::err(f.saturating_add(1), capacity))? = face;
        let words = self.work_words;
        *self
            .marks
            .get_mut(f)
            .ok_or(Self::err(f.saturating_add(1).saturating_mul(2), words))? = 0;
        let capacity = self.boxes.len();
        if f >= capacity {
            return Err(Self::err(f.saturating_add(1), capacity));
        }
        self.slots = f + 1;
        let extent = self.measure(f);
        if let Some(b) = self.boxes.get_mut(f) {
            *b = extent;
        }
        Ok(f)
    }

    /// A fragment's screen box (unbounded when a vertex is at or behind the eye)
    /// and depth range.
    fn measure(&self, f: usize) -> Extent {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let mut behind = false;
        for &i in self.idx(f) {
            let p = vertex(self.vertices, i);
            let [x, y, w] = self.view.clip(p);
            let (sx, sy) = match self.view.screen(p) {
                Some([sx, sy]) => (sx, sy),
                None => {
                    behind = true;
                    (x, y)
                }
            };
            for (k, v) in [sx, sy, w].into_iter().enumerate() {
                if let (Some(l), Some(h)) = (lo.get_mut(k), hi.get_mut(k)) {
                    *l = l.min(v);
                    *h = h.max(v);
                }
            }
        }
        if behind {
            lo[0] = f64::NEG_INFINITY;
            lo[1] = f64::NEG_INFINITY;
            hi[0] = f64::INFINITY;
            hi[1] = f64::INFINITY;
        }
        [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]].map(|v| v as f32)
    }

    /// Appends one index to the fragment being written.
    fn put(&mut self, v: u32) -> Result<(), Error> {
        let capacity = self.indices.len();
        let at = self.index_count;
        *self
            .indices
            .get_mut(at)
            .ok_or(Self::err(at.saturating_add(1), capacity))? = v;
        self.index_count = at + 1;
        Ok(())
    }

    /// Appends a split point on root segment `root`.
    fn push_vertex(&mut self, p: [f32; 3], root: [u32; 2]) -> Result<u32, Error> {
        let n = self.vertex_count;
        let capacity = self.vertices.len();
        *self
            .vertices
            .get_mut(n)
            .ok_or(Self::err(n.saturating_add(1), capacity))? = p;
        let k = n.saturating_sub(self.base);
        let capacity = self.seams.len();
        *self
            .seams
            .get_mut(k)
            .ok_or(Self::err(k.saturating_add(1), capacity))? = root;
        let index = u32::try_from(n).map_err(|_| Self::err(n, u32::MAX as usize))?;
        self.vertex_count = n + 1;
        Ok(index)
    }

    fn seams(&self) -> Seams<'_> {
        let vertices: &[[f32; 3]] = self.vertices;
        let roots: &[[u32; 2]] = self.seams;
        let splits = self.vertex_count.saturating_sub(self.base);
        Seams {
            vertices: vertices.get(..self.vertex_count).unwrap_or(vertices),
            base: self.base,
            roots: roots.get(..splits).unwrap_or(roots),
        }
    }

    fn step(&mut self) -> Result<(), Error> {
        self.steps = self.steps.saturating_add(1);
        if self.steps > self.max_steps {
            return Err(Error::DepthSortUnsettled { steps: self.steps });
        }
        Ok(())
    }

    /// Newell's loop: paints (fixes) the head when no later fragment needs to be
    /// painted before it, else shuffles or splits and looks again.
    fn settle(&mut self) -> Result<(), Error> {
        let mut head = 0usize;
        'head: while head < self.len {
            let p = self.at(head) as usize;
            let near_end = self.extent(p)[4];
            let mut j = head + 1;
            while j < self.len {
                let q = self.at(j) as usize;
                if self.extent(q)[5] < near_end {
                    // The rest is sorted by farthest depth: all nearer than P.
                    break;
                }
                if !self.may_obscure(p, q) {
                    j += 1;
                    continue;
                }
                let marked = self.marks.get(q).copied() == Some(self.generation);
                if !marked && !self.may_obscure(q, p) {
                    self.step()?;
                    self.shuffles += 1;
                    self.move_ahead(head, j)?;
                    continue 'head;
                }
                // A cycle, or P and Q each over the other: split.
                if self.split_cycle(head, j)? {
                    continue 'head;
                }
                if self.forced < self.len - head && !self.may_obscure(q, p) {
                    // Q may go first, but it was moved ahead before in this round
                    // and no plane cuts the cycle: the tests are conservative, so
                    // this may be no cycle at all. Move it again, a bounded number
                    // of times per round.
                    self.step()?;
                    self.shuffles += 1;
                    self.forced += 1;
                    self.move_ahead(head, j)?;
                    continue 'head;
                }
                self.unresolved += 1;
                j += 1;
            }
            head += 1;
            self.generation = self.generation.saturating_add(1);
            self.forced = 0;
        }
        Ok(())
    }

    /// May P, painted before Q, cover a part of Q that is nearer? (True unless one
    /// of Newell's tests proves otherwise; coplanar overlapping polygons: when P's
    /// face index is the lower one.)
    fn may_obscure(&self, p: usize, q: usize) -> bool {
        let (bp, bq) = (self.extent(p), self.extent(q));
        // 1: P wholly beyond Q.
        if bp[4] > bq[5] {
            return false;
        }
        // 2 and 3: disjoint (or touching) screen extents.
        if bp[1] <= bq[0] || bq[1] <= bp[0] || bp[3] <= bq[2] || bq[3] <= bp[2] {
            return false;
        }
        let (fp, fq) = (self.face(p), self.face(q));
        if fp == fq {
            // Pieces of one face do not overlap.
            return false;
        }
        let (plane_p, plane_q) = (self.banded(p), self.banded(q));
        let (p_by_q, q_by_p) = (self.sides(p, &plane_q), self.sides(q, &plane_p));
        if p_by_q == (0, 0) && q_by_p == (0, 0) {
            // Coplanar: the lower face index is nearer where they overlap.
            return fp < fq && self.projections_overlap(p, q);
        }
        // 4: P wholly on the far side of Q's plane (Q edge-on covers nothing).
        let far = match self.view.eye_side(&plane_q.0) {
            Side::Front => p_by_q.0 == 0,
            Side::Back => p_by_q.1 == 0,
            Side::On => true,
        };
        // 5: Q wholly on the near side of P's plane.
        let near = match self.view.eye_side(&plane_p.0) {
            Side::Front => q_by_p.1 == 0,
            Side::Back => q_by_p.0 == 0,
            Side::On => true,
        };
        // 6: the projections overlap.
        !far && !near && self.projections_overlap(p, q)
    }

    /// Do the projections of fragments `p` and `q` overlap? False when an edge
    /// direction of either separates them (touching counts as apart: no pixel
    /// centre is covered by both); true when a vertex is at or behind the eye.
    fn projections_overlap(&self, p: usize, q: usize) -> bool {
        self.separated(p, q) != Some(true)
    }

    fn separated(&self, p: usize, q: usize) -> Option<bool> {
        let (a, b) = (self.idx(p), self.idx(q));
        let screen = |i: u32| self.view.screen(vertex(self.vertices, i));
        let interval = |poly: &[u32], axis: [f64; 2]| -> Option<(f64, f64)> {
            let mut range = (f64::INFINITY, f64::NEG_INFINITY);
            for &i in poly {
                let [x, y] = screen(i)?;
                let t = axis[0] * x + axis[1] * y;
                range = (range.0.min(t), range.1.max(t));
            }
            Some(range)
        };
        for poly in [a, b] {
            for (k, &u) in poly.iter().enumerate() {
                let v = poly.get(k + 1).or(poly.first()).copied().unwrap_or(u);
                let (pu, pv) = (screen(u)?, screen(v)?);
                let axis = [pu[1] - pv[1], pv[0] - pu[0]];
                if axis == [0.0, 0.0] {
                    continue;
                }
                let (ia, ib) = (interval(a, axis)?, interval(b, axis)?);
                if ia.1 <= ib.0 || ib.1 <= ia.0 {
                    return Some(true);
                }
            }
        }
        Some(false)
    }

    /// Does fragment `f` have vertices on both sides of `plane` (beyond the
    /// tolerance)?
    fn straddles(&self, f: usize, plane: &(Plane, f64)) -> bool {
        let (front, back) = self.sides(f, plane);
        front > 0 && back > 0
    }

    /// Breaks the cycle found at head P (`list[head]`) and Q (`list[j]`) by a split:
    /// Q by P's plane, or P by Q's, or else any fragment of the cycle (P, Q and the
    /// fragments moved ahead in this round) by the plane of another. False when no
    /// such plane cuts any of them.
    fn split_cycle(&mut self, head: usize, j: usize) -> Result<bool, Error> {
        let (p, q) = (self.at(head) as usize, self.at(j) as usize);
        let (plane_p, plane_q) = (self.banded(p), self.banded(q));
        if self.straddles(q, &plane_p) {
            self.split_at(head, j, &plane_p.0)?;
            return Ok(true);
        }
        if self.straddles(p, &plane_q) {
            self.split_at(head, head, &plane_q.0)?;
            return Ok(true);
        }
        // The cycle runs through fragments moved ahead in this round: cut one of
        // them (or P, or Q) by the plane of another.
        let in_cycle = |this: &Self, k: usize| {
            k == head || k == j || this.marks.get(this.at(k) as usize) == Some(&this.generation)
        };
        for kr in head..self.len {
            if !in_cycle(self, kr) {
                continue;
            }
            let r = self.at(kr) as usize;
            for ks in head..self.len {
                let s = self.at(ks) as usize;
                if ks == kr || !in_cycle(self, ks) || self.face(s) == self.face(r) {
                    continue;
                }
                let plane_s = self.banded(s);
                if self.straddles(r, &plane_s) {
                    self.split_at(head, kr, &plane_s.0)?;
                    return Ok(true);
                }
            }
        }
        // Last, P and Q by each other's plane without the thickness band (faces
        // that are not planar: their vertices within the band decided nothing).
        let (plane_p, plane_q) = ((plane_p.0, 0.0), (plane_q.0, 0.0));
        if self.straddles(q, &plane_p) {
            self.split_at(head, j, &plane_p.0)?;
            return Ok(true);
        }
        if self.straddles(p, &plane_q) {
            self.split_at(head, head, &plane_q.0)?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Removes `list[k]`.
    fn remove(&mut self, k: usize) {
        let len = self.len;
        if k < len {
            self.list.copy_within(k + 1..len, k);
            self.len = len - 1;
        }
    }

    /// Inserts slot `f` into the sorted `list[from..]`.
    fn insert_sorted(&mut self, f: u32, from: usize) -> Result<(), Error> {
        let len = self.len;
        if len >= self.list.len() {
            return Err(Self::err(
                len.saturating_add(1).saturating_mul(2),
                self.work_words,
            ));
        }
        let key = self.key(f);
        let rest = self.list.get(from..len).unwrap_or(&[]);
        let at = from + rest.partition_point(|&g| self.key(g) < key);
        self.list.copy_within(at..len, at + 1);
        if let Some(slot) = self.list.get_mut(at) {
            *slot = f;
        }
        self.len = len + 1;
        Ok(())
    }

    /// Shuffle: Q (`list[j]`) becomes the head, marked; P goes back into the rest
    /// by its farthest depth.
    fn move_ahead(&mut self, head: usize, j: usize) -> Result<(), Error> {
        let (p, q) = (self.at(head), self.at(j));
        self.remove(j);
        if let Some(slot) = self.list.get_mut(head) {
            *slot = q;
        }
        if let Some(m) = self.marks.get_mut(q as usize) {
            *m = self.generation;
        }
        self.insert_sorted(p, head + 1)
    }

    /// Splits `list[k]` by `plane`; its pieces go into the rest by farthest depth
    /// (when it was the head, the farthest of all becomes the head).
    fn split_at(&mut self, head: usize, k: usize, plane: &Plane) -> Result<(), Error> {
        self.step()?;
        self.splits += 1;
        let x = self.at(k) as usize;
        let pieces = self.split(x, plane)?;
        if let Some(m) = self.marks.get_mut(x) {
            *m = DEAD;
        }
        self.remove(k);
        let from = if k == head { head } else { head + 1 };
        for f in pieces {
            // Slots fit u32: they are below the offsets' length, checked against u32.
            self.insert_sorted(f as u32, from)?;
        }
        Ok(())
    }

    /// Cuts fragment `x` by the exact signs of the distances to `plane`, as the BSP
    /// build does: the front is one polygon (Sutherland-Hodgman), the back one piece
    /// per stretch of vertices behind, closed by the chord the front bridges the
    /// other way; all keep `x`'s winding. Returns the new slots.
    fn split(&mut self, x: usize, plane: &Plane) -> Result<Range<usize>, Error> {
        let (s, e) = self.range(x);
        let len = e - s;
        let face = self.source.get(x).copied().unwrap_or(0);
        let at = |this: &Self, k: usize| this.indices.get(s + k % len.max(1)).copied().unwrap_or(0);
        let side =
            |this: &Self, k: usize| exact_side(plane.distance(vertex(this.vertices, at(this, k))));
        let crosses = |this: &Self, k: usize| {
            matches!(
                (side(this, k), side(this, k + 1)),
                (Side::Front, Side::Back) | (Side::Back, Side::Front)
            )
        };
        let first_slot = self.slots;
        // The front, making the split points: the j-th crossing edge (from edge 0)
        // makes vertex `first + j`.
        let first = self.vertex_count;
        let mut made = 0usize;
        for k in 0..len {
            let (a, b) = (at(self, k), at(self, k + 1));
            if side(self, k) != Side::Back {
                self.put(a)?;
            }
            if crosses(self, k) {
                let (sa, sb) = (
                    plane.distance(vertex(self.vertices, a)),
                    plane.distance(vertex(self.vertices, b)),
                );
                let p = split_point(self.vertices, a, sa, b, sb);
                let root = self.seams().root(a, b);
                let v = self.push_vertex(p, root)?;
                made += 1;
                self.put(v)?;
            }
        }
        self.new_slot(face)?;
        // The back pieces, walking from the start of a back stretch.
        let made = made.max(1);
        // Vertex indices fit u32 (push_vertex checked).
        let split_vertex = |ordinal: usize| first.saturating_add(ordinal % made) as u32;
        let start = (0..len)
            .find(|&k| side(self, k) == Side::Back && side(self, k + len - 1) != Side::Back)
            .unwrap_or(0);
        let mut ordinal = (0..start).filter(|&k| crosses(self, k)).count();
        let mut open = false;
        for k in start..start + len {
            if side(self, k) == Side::Back {
                let before = k + len - 1;
                if side(self, before) != Side::Back {
                    open = true;
                    if side(self, before) == Side::On {
                        self.put(at(self, before))?;
                    } else {
                        self.put(split_vertex(ordinal + made - 1))?;
                    }
                }
                self.put(at(self, k))?;
                if side(self, k + 1) != Side::Back {
                    if side(self, k + 1) == Side::On {
                        self.put(at(self, k + 1))?;
                    } else {
                        self.put(split_vertex(ordinal))?;
                    }
                    if open {
                        self.new_slot(face)?;
                        open = false;
                    }
                }
            }
            if crosses(self, k) {
                ordinal += 1;
            }
        }
        Ok(first_slot..self.slots)
    }

    /// Drops the split fragments (the live ones move down, in slot order) and
    /// writes each live fragment's paint place into `marks` ([`NOT_DRAWN`] when it
    /// was not sorted). Returns the live and the sorted fragment counts.
    fn compact(&mut self) -> Result<(usize, usize), Error> {
        let slots = self.slots;
        for m in self.marks.iter_mut().take(slots) {
            if *m != DEAD {
                *m = NOT_DRAWN;
            }
        }
        let drawn = self.len;
        for i in 0..drawn {
            let f = self.at(i) as usize;
            if let Some(m) = self.marks.get_mut(f) {
                // The list is shorter than u32::MAX / 2.
                *m = i as u32;
            }
        }
        let mut live = 0usize;
        let mut end = 0usize;
        for f in 0..slots {
            let mark = self.marks.get(f).copied().unwrap_or(DEAD);
            if mark == DEAD {
                continue;
            }
            let (s, e) = self.range(f);
            // Forward: the live fragments' new places never pass their old ones.
            self.indices.copy_within(s..e, end);
            end += e - s;
            let face = self.source.get(f).copied().unwrap_or(0);
            if let Some(src) = self.source.get_mut(live) {
                *src = face;
            }
            if let Some(m) = self.marks.get_mut(live) {
                *m = mark;
            }
            // Live <= f < slots: the offsets hold it.
            if let Some(o) = self.offsets.get_mut(live + 1) {
                *o = end as u32;
            }
            live += 1;
        }
        self.index_count = end;
        if live > MAX_FACES {
            return Err(Error::TooManyFaces {
                faces: live,
                max: MAX_FACES,
            });
        }
        Ok((live, drawn))
    }

    /// Ranks, seams and the result.
    fn finish<'s>(
        self,
        live: usize,
        drawn: usize,
        rank: &'s mut [u32],
    ) -> Result<NewellOrder<'s>, Error>
    where
        'a: 's,
    {
        need(live, rank.len())?;
        let mut others = drawn;
        for (f, r) in rank.iter_mut().enumerate().take(live) {
            let place = self.marks.get(f).copied().unwrap_or(NOT_DRAWN) as usize;
            *r = if place < drawn {
                // Paint order is far first; rank 0 is the nearest.
                (drawn - 1 - place) as u32
            } else {
                let r = others as u32;
                others += 1;
                r
            };
        }
        let Self {
            vertices,
            vertex_count,
            base,
            seams,
            indices,
            index_count,
            offsets,
            source,
            list,
            marks: _,
            splits,
            shuffles,
            unresolved,
            work_words,
            ..
        } = self;
        let vertices: &'a [[f32; 3]] = vertices;
        let vertices = vertices.get(..vertex_count).unwrap_or(vertices);
        let points = vertex_count.saturating_sub(base);
        let roots: &[[u32; 2]] = seams;
        let roots = roots.get(..points).unwrap_or(roots);
        // The list is done with: its half of `work` sorts the split points.
        if points > list.len() {
            return Err(Self::err(points.saturating_mul(2), work_words));
        }
        let (index_count, _) = insert_seam_vertices(
            vertices,
            base,
            roots,
            indices,
            index_count,
            offsets,
            live,
            list,
        )?;
        let indices: &'a [u32] = indices;
        let offsets: &'a [u32] = offsets;
        let source: &'a [u16] = source;
        let rank: &'s [u32] = rank;
        let fragments = Mesh::new(
            vertices,
            indices.get(..index_count).unwrap_or(indices),
            offsets.get(..=live).unwrap_or(offsets),
        )?;
        Ok(NewellOrder {
            fragments,
            source: source.get(..live).unwrap_or(source),
            rank: rank.get(..live).unwrap_or(rank),
            drawn,
            splits,
            shuffles,
            unresolved,
        })
    }
}
