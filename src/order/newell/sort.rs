//! The sort's state and its two ends: the lent storage taken apart, the mesh copied
//! in as the first fragments and the drawn ones listed farthest first, the fragment
//! storage (slots, indices, split points), then the compaction, the ranks and the
//! seams. Newell's tests are in `obscure`, the loop that shuffles and splits in
//! `settle`, the cut of a fragment by a plane in `split`, the view in `view`.

use super::view::View;
use super::{NewellOptions, NewellOrder, NewellStorage};
use crate::camera::Camera;
use crate::error::need;
use crate::mesh::{Mesh, MAX_FACES};
use crate::order::bsp::PLANE_TOLERANCE;
use crate::order::plane::{fan_triangles, fans, vertex, Plane, Record};
use crate::order::seams::{insert_seam_vertices, Seams};
use crate::sort::sort_by_key;
use crate::Capacity;
use crate::Error;

/// The mark of a slot whose fragment was split (its pieces replace it).
pub(super) const DEAD: u32 = u32::MAX;
/// The place of a live fragment that is not in the list (culled, or zero area).
const NOT_DRAWN: u32 = u32::MAX - 1;

/// A slot's `[x_min, x_max, y_min, y_max, depth_min, depth_max]`.
type Extent = [f32; 6];

/// The sort's state: the lent slices and how much of each is used.
pub(super) struct Sorter<'a, 'b, 'm> {
    pub(super) mesh: &'b Mesh<'m>,
    pub(super) view: View,
    tolerance_sq: f64,
    pub(super) vertices: &'a mut [[f32; 3]],
    pub(super) vertex_count: usize,
    base: usize,
    seams: &'a mut [[u32; 2]],
    pub(super) indices: &'a mut [u32],
    index_count: usize,
    offsets: &'a mut [u32],
    pub(super) source: &'a mut [u16],
    boxes: &'a mut [Extent],
    /// `list[..len]`: the drawn fragments, paint order (far first) up to `head`,
    /// then the head, then the rest sorted by farthest depth.
    pub(super) list: &'a mut [u32],
    pub(super) len: usize,
    /// Per slot: [`DEAD`], or the generation in which it was moved ahead (marked).
    pub(super) marks: &'a mut [u32],
    /// Per slot: the surface it lies on, a [`Record`] word (its face, and its fan
    /// triangle when the face is not planar).
    surfaces: &'a mut [u32],
    /// Slots made so far.
    pub(super) slots: usize,
    /// The words of `work` (for errors about it).
    pub(super) work_words: usize,
    pub(super) generation: u32,
    /// Marked fragments moved ahead again in this generation (at most the fragments
    /// left to paint).
    pub(super) forced: usize,
    pub(super) splits: usize,
    pub(super) shuffles: usize,
    pub(super) unresolved: usize,
    pub(super) steps: usize,
    pub(super) max_steps: usize,
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
    let third = work_words / 3;
    let (list, rest) = work.split_at_mut(third);
    let (marks, surfaces) = rest.split_at_mut(third);
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
        surfaces,
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
    s.max_steps = s.max_steps.min(scene_steps(s.len.max(mesh.face_count())));
    s.settle()?;
    let (live, drawn) = s.compact()?;
    s.finish(live, drawn, rank)
}

/// The most shuffles and splits a sort of `n` faces or starting fragments (a bent
/// face starts as its fan triangles), whichever is more, may make, whatever the
/// options allow: without cycles it makes fewer than `n^2 / 2` shuffles, and the
/// cycles of real scenes take a few splits each. A sort that needs more is one
/// whose tests cannot decide (planes of coordinates near `f32::MAX` are not
/// finite); it fails in time proportional to its scene, not after a million steps.
fn scene_steps(n: usize) -> usize {
    n.saturating_mul(n).saturating_mul(8).saturating_add(256)
}

impl<'a> Sorter<'a, '_, '_> {
    pub(super) fn err(what: Capacity, needed: usize, capacity: usize) -> Error {
        Error::CapacityExceeded {
            what,
            needed,
            capacity,
        }
    }

    pub(super) fn at(&self, k: usize) -> u32 {
        self.list.get(k).copied().unwrap_or(0)
    }

    pub(super) fn range(&self, f: usize) -> (usize, usize) {
        match (self.offsets.get(f), self.offsets.get(f.saturating_add(1))) {
            (Some(&s), Some(&e)) if s <= e => (s as usize, e as usize),
            _ => (0, 0),
        }
    }

    pub(super) fn idx(&self, f: usize) -> &[u32] {
        let (s, e) = self.range(f);
        self.indices.get(s..e).unwrap_or(&[])
    }

    pub(super) fn face(&self, f: usize) -> usize {
        self.source.get(f).map_or(0, |&s| usize::from(s))
    }

    pub(super) fn extent(&self, f: usize) -> Extent {
        self.boxes.get(f).copied().unwrap_or([0.0; 6])
    }

    /// The [`Record`] word of slot `f`'s surface.
    pub(super) fn surface(&self, f: usize) -> u32 {
        self.surfaces.get(f).copied().unwrap_or(self.face(f) as u32)
    }

    /// The plane of slot `f`'s surface: its face's, or its fan triangle's.
    pub(super) fn plane(&self, f: usize) -> Plane {
        Plane::of_record(self.mesh, self.surface(f), self.tolerance_sq)
    }

    /// Copies the mesh (its vertices, and its faces as slots: a face that is not
    /// planar as its fan triangles, as the BSP build takes it) and lists the slots
    /// drawn in the view, farthest first.
    fn start(&mut self, cull: bool) -> Result<(), Error> {
        let mesh = self.mesh;
        let from = mesh.vertices();
        let capacity = self.vertices.len();
        self.vertices
            .get_mut(..from.len())
            .ok_or(Self::err(Capacity::SplitVertices, from.len(), capacity))?
            .copy_from_slice(from);
        self.vertex_count = from.len();
        let faces = mesh.face_count();
        let capacity = self.offsets.len();
        *self.offsets.first_mut().ok_or(Self::err(
            Capacity::FragmentOffsets,
            faces.saturating_add(1),
            capacity,
        ))? = 0;
        for f in 0..faces {
            let corners = mesh.face(f);
            if fans(mesh, f, self.tolerance_sq) {
                for (word, triangle) in fan_triangles(f, corners) {
                    for i in triangle {
                        self.put(i)?;
                    }
                    self.new_slot(word)?;
                }
            } else {
                for &i in corners {
                    self.put(i)?;
                }
                // Face ids are below MAX_FACES < 2^16.
                self.new_slot(f as u32)?;
            }
        }
        let viewpoint = self.view.viewpoint;
        for f in 0..self.slots {
            let drawn = !cull || mesh.faces_viewpoint(self.face(f), &viewpoint);
            if drawn && !self.plane(f).is_degenerate() {
                let slot = self.list.get_mut(self.len).ok_or(Self::err(
                    Capacity::OrderWork,
                    self.len.saturating_add(1).saturating_mul(3),
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
    /// index count), on surface `surface` (a [`Record`] word, which names its source
    /// face): its box, no mark.
    pub(super) fn new_slot(&mut self, surface: u32) -> Result<usize, Error> {
        // Face ids are below MAX_FACES < 2^16.
        let face = Record::face(surface) as u16;
        let f = self.slots;
        let end = u32::try_from(self.index_count)
            .map_err(|_| Self::err(Capacity::Index32, self.index_count, 0))?;
        let capacity = self.offsets.len();
        *self.offsets.get_mut(f.saturating_add(1)).ok_or(Self::err(
            Capacity::FragmentOffsets,
            f.saturating_add(2),
            capacity,
        ))? = end;
        let capacity = self.source.len();
        *self.source.get_mut(f).ok_or(Self::err(
            Capacity::FragmentSources,
            f.saturating_add(1),
            capacity,
        ))? = face;
        let words = self.work_words;
        *self.marks.get_mut(f).ok_or(Self::err(
            Capacity::OrderWork,
            f.saturating_add(1).saturating_mul(3),
            words,
        ))? = 0;
        *self.surfaces.get_mut(f).ok_or(Self::err(
            Capacity::OrderWork,
            f.saturating_add(1).saturating_mul(3),
            words,
        ))? = surface;
        let capacity = self.boxes.len();
        if f >= capacity {
            return Err(Self::err(
                Capacity::SortBoxes,
                f.saturating_add(1),
                capacity,
            ));
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
    pub(super) fn put(&mut self, v: u32) -> Result<(), Error> {
        let capacity = self.indices.len();
        let at = self.index_count;
        *self.indices.get_mut(at).ok_or(Self::err(
            Capacity::FragmentIndices,
            at.saturating_add(1),
            capacity,
        ))? = v;
        self.index_count = at + 1;
        Ok(())
    }

    /// Appends a split point on root segment `root`.
    pub(super) fn push_vertex(&mut self, p: [f32; 3], root: [u32; 2]) -> Result<u32, Error> {
        let n = self.vertex_count;
        let capacity = self.vertices.len();
        *self.vertices.get_mut(n).ok_or(Self::err(
            Capacity::SplitVertices,
            n.saturating_add(1),
            capacity,
        ))? = p;
        let k = n.saturating_sub(self.base);
        let capacity = self.seams.len();
        *self.seams.get_mut(k).ok_or(Self::err(
            Capacity::SplitSeams,
            k.saturating_add(1),
            capacity,
        ))? = root;
        let index =
            u32::try_from(n).map_err(|_| Self::err(Capacity::Index32, n, u32::MAX as usize))?;
        self.vertex_count = n + 1;
        Ok(index)
    }

    pub(super) fn seams(&self) -> Seams<'_> {
        let vertices: &[[f32; 3]] = self.vertices;
        let roots: &[[u32; 2]] = self.seams;
        let splits = self.vertex_count.saturating_sub(self.base);
        Seams {
            vertices: vertices.get(..self.vertex_count).unwrap_or(vertices),
            base: self.base,
            roots: roots.get(..splits).unwrap_or(roots),
        }
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
        need(Capacity::FragmentRanks, live, rank.len())?;
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
        // The list is done with: its third of `work` sorts the split points.
        if points > list.len() {
            return Err(Self::err(
                Capacity::OrderWork,
                points.saturating_mul(3),
                work_words,
            ));
        }
        let seams = Seams {
            vertices,
            base,
            roots,
        };
        let (index_count, _) =
            insert_seam_vertices(seams, indices, index_count, offsets, live, list)?;
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
