//! The iterative build of the BSP tree: the work stack of fragment sets, splitting.

use super::bsp::{BspNode, BspOptions, BspStorage, BspTree, NO_NODE, PLANE_TOLERANCE};
use super::plane::{
    exact_side, fans, split_point, vertex, Fate, Plane, Record, Records, Side, Tally,
};
use super::seams::{insert_seam_vertices, Seams};
use crate::mesh::{Mesh, MAX_FACES};
use crate::Error;

/// Words of a set header on the work stack: `[words, count, link, level]`.
const HEADER: usize = 4;

/// [`BspTree::build_with`]: copies the vertices, pushes the root set, splits sets
/// until none is left, then checks the write-only slices and wraps the result.
pub(super) fn run<'s>(
    mesh: &Mesh<'_>,
    storage: BspStorage<'s>,
    options: BspOptions,
) -> Result<BspTree<'s>, Error> {
    let BspStorage {
        vertices,
        indices,
        offsets,
        source,
        nodes,
        seams,
        work,
    } = storage;
    let tolerance = PLANE_TOLERANCE;
    let mut out = Output {
        vertices,
        vertex_count: 0,
        base: mesh.vertices().len(),
        seams,
        indices,
        index_count: 0,
        offsets,
        source,
        fragment_count: 0,
        nodes,
        node_count: 0,
    };
    let mut build = Build {
        mesh,
        options,
        tolerance_sq: tolerance * tolerance,
        work,
        top: 0,
        peak: 0,
        depth: 0,
    };
    out.copy_mesh_vertices(mesh)?;
    let pieces = build.push_faces()?;
    while build.top > 0 {
        build.split_top(&mut out)?;
    }
    let depth = build.depth;
    out.finish(depth, pieces, build.peak, build.work)
}

pub(super) fn need(needed: usize, capacity: usize) -> Result<(), Error> {
    if needed > capacity {
        return Err(Error::CapacityExceeded { needed, capacity });
    }
    Ok(())
}

/// The output slices and how much of each is used (or would be: the write-only
/// ones count on past their capacity so the error can name the exact need).
struct Output<'s> {
    vertices: &'s mut [[f32; 3]],
    vertex_count: usize,
    /// The mesh's vertex count: split points are numbered from here.
    base: usize,
    /// `seams[x - base]`: the root segment of split point `x` (see [`Seams`]).
    seams: &'s mut [[u32; 2]],
    indices: &'s mut [u32],
    index_count: usize,
    offsets: &'s mut [u32],
    source: &'s mut [u16],
    fragment_count: usize,
    nodes: &'s mut [BspNode],
    node_count: usize,
}

impl<'s> Output<'s> {
    fn copy_mesh_vertices(&mut self, mesh: &Mesh<'_>) -> Result<(), Error> {
        let from = mesh.vertices();
        let capacity = self.vertices.len();
        let to = self
            .vertices
            .get_mut(..from.len())
            .ok_or(Error::CapacityExceeded {
                needed: from.len(),
                capacity,
            })?;
        to.copy_from_slice(from);
        self.vertex_count = from.len();
        Ok(())
    }

    /// The split points' root segments, as far as they are made.
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

    /// Appends a split point on root segment `root`; `more` further ones are about to
    /// follow (for the error).
    fn push_vertex(&mut self, p: [f32; 3], root: [u32; 2], more: usize) -> Result<u32, Error> {
        let capacity = self.vertices.len();
        let slot = self
            .vertices
            .get_mut(self.vertex_count)
            .ok_or(Error::CapacityExceeded {
                needed: self.vertex_count.saturating_add(more).saturating_add(1),
                capacity,
            })?;
        *slot = p;
        let split = self.vertex_count.saturating_sub(self.base);
        let capacity = self.seams.len();
        let seam = self.seams.get_mut(split).ok_or(Error::CapacityExceeded {
            needed: split.saturating_add(more).saturating_add(1),
            capacity,
        })?;
        *seam = root;
        let index = u32::try_from(self.vertex_count).map_err(|_| Error::CapacityExceeded {
            needed: self.vertex_count.saturating_add(1),
            capacity: u32::MAX as usize,
        })?;
        self.vertex_count += 1;
        Ok(index)
    }

    /// Appends a fragment (counting on past the capacity of the write-only slices).
    fn emit(&mut self, word: u32, idx: &[u32]) -> Result<(), Error> {
        let start = self.index_count;
        let end = start.saturating_add(idx.len());
        if let Some(to) = self.indices.get_mut(start..end) {
            to.copy_from_slice(idx);
        }
        let f = self.fragment_count;
        if let Some(s) = self.source.get_mut(f) {
            // The face id is below MAX_FACES: it fits 16 bits.
            *s = (word & 0xFFFF) as u16;
        }
        let end_u32 = u32::try_from(end).map_err(|_| Error::CapacityExceeded {
            needed: end,
            capacity: u32::MAX as usize,
        })?;
        if f == 0 {
            if let Some(o) = self.offsets.first_mut() {
                *o = 0;
            }
        }
        if let Some(o) = self.offsets.get_mut(f.saturating_add(1)) {
            *o = end_u32;
        }
        self.index_count = end;
        self.fragment_count = f.saturating_add(1);
        Ok(())
    }

    /// A new node for `plane`, linked from its parent (`link` = parent * 2 + side).
    fn new_node(&mut self, plane: &Plane, link: u32) -> Result<u32, Error> {
        let id = self.node_count;
        let id_u32 = u32::try_from(id).ok().filter(|&n| n < u32::MAX / 2).ok_or(
            Error::CapacityExceeded {
                needed: id.saturating_add(1),
                capacity: (u32::MAX / 2) as usize,
            },
        )?;
        let first = u32::try_from(self.fragment_count).unwrap_or(u32::MAX);
        if let Some(node) = self.nodes.get_mut(id) {
            *node = BspNode {
                plane: plane.coefficients(),
                first,
                ..BspNode::EMPTY
            };
        }
        if link != NO_NODE {
            if let Some(parent) = self.nodes.get_mut((link / 2) as usize) {
                if link % 2 == 0 {
                    parent.front = id_u32;
                } else {
                    parent.back = id_u32;
                }
            }
        }
        self.node_count = id.saturating_add(1);
        Ok(id_u32)
    }

    /// Closes node `id`: its fragments are those emitted since it was made.
    fn close_node(&mut self, id: u32) {
        let fragments = self.fragment_count;
        if let Some(node) = self.nodes.get_mut(id as usize) {
            let count = fragments.saturating_sub(node.first as usize);
            node.count = u32::try_from(count).unwrap_or(u32::MAX);
        }
    }

    /// Makes the fragments watertight: [`insert_seam_vertices`]. Returns the
    /// `work` words used.
    fn insert_seam_vertices(&mut self, work: &mut [u32]) -> Result<usize, Error> {
        let vertices: &[[f32; 3]] = self.vertices;
        let roots: &[[u32; 2]] = self.seams;
        let splits = self.vertex_count.saturating_sub(self.base);
        let (index_count, words) = insert_seam_vertices(
            vertices.get(..self.vertex_count).unwrap_or(vertices),
            self.base,
            roots.get(..splits).unwrap_or(roots),
            self.indices,
            self.index_count,
            self.offsets,
            self.fragment_count,
            work,
        )?;
        self.index_count = index_count;
        Ok(words)
    }

    fn finish(
        mut self,
        depth: usize,
        pieces: usize,
        work_peak: usize,
        work: &mut [u32],
    ) -> Result<BspTree<'s>, Error> {
        let fragments = self.fragment_count;
        need(self.node_count, self.nodes.len())?;
        need(fragments.saturating_add(1), self.offsets.len())?;
        need(fragments, self.source.len())?;
        // Before the seams' split points are inserted: a lower bound.
        need(self.index_count, self.indices.len())?;
        if fragments > MAX_FACES {
            return Err(Error::TooManyFaces {
                faces: fragments,
                max: MAX_FACES,
            });
        }
        let sorted_words = self.insert_seam_vertices(work)?;
        let work_peak = work_peak.max(sorted_words);
        let vertices: &'s [[f32; 3]] = self.vertices;
        let indices: &'s [u32] = self.indices;
        let offsets: &'s [u32] = self.offsets;
        let source: &'s [u16] = self.source;
        let nodes: &'s [BspNode] = self.nodes;
        let fragment_mesh = Mesh::new(
            vertices.get(..self.vertex_count).unwrap_or(vertices),
            indices.get(..self.index_count).unwrap_or(indices),
            offsets.get(..=fragments).unwrap_or(offsets),
        )?;
        Ok(BspTree {
            fragments: fragment_mesh,
            source: source.get(..fragments).unwrap_or(source),
            nodes: nodes.get(..self.node_count).unwrap_or(nodes),
            depth,
            pieces,
            work_peak,
        })
    }
}

/// The build's state: the work stack of fragment sets still to be split.
///
/// `work[..top]` holds sets, each its records (see [`Record`]) followed by a header
/// `[words, count, link, level]`: `link` = parent node * 2 + (0 front, 1 back), or
/// [`NO_NODE`] for the root; `level` = the node's depth (root 1). The top set is split
/// next; its children are written above it, then moved down in its place.
struct Build<'w, 'm, 'a> {
    mesh: &'w Mesh<'m>,
    options: BspOptions,
    tolerance_sq: f64,
    work: &'a mut [u32],
    top: usize,
    peak: usize,
    depth: usize,
}

impl Build<'_, '_, '_> {
    /// Pushes the root set: every face in order, whole, or as its fan triangles when
    /// it is not planar (see [`fans`] and [`BspTree::build_with`]). Returns the number
    /// of faces.
    fn push_faces(&mut self) -> Result<usize, Error> {
        let mesh = self.mesh;
        let count = mesh.face_count();
        let tolerance_sq = self.tolerance_sq;
        let fanned = |face: usize| fans(mesh, face, tolerance_sq);
        let (words, records) = (0..count).fold((0usize, 0usize), |(words, records), face| {
            let n = mesh.face(face).len();
            let (more_words, more_records) = if fanned(face) {
                ((n - 2).saturating_mul(3 + Record::HEAD), n - 2)
            } else {
                (n + Record::HEAD, 1)
            };
            (
                words.saturating_add(more_words),
                records.saturating_add(more_records),
            )
        });
        let needed = words.saturating_add(HEADER);
        let capacity = self.work.len();
        let area = self
            .work
            .get_mut(..needed)
            .ok_or(Error::CapacityExceeded { needed, capacity })?;
        let mut at = 0usize;
        let mut put = |value: u32| {
            if let Some(w) = area.get_mut(at) {
                *w = value;
            }
            at += 1;
        };
        for face in 0..count {
            let corners = mesh.face(face);
            if fanned(face) {
                let v0 = corners.first().copied().unwrap_or(0);
                for (k, pair) in corners.get(1..).unwrap_or(&[]).windows(2).enumerate() {
                    put(Record::of_fan(face, k + 1));
                    put(3);
                    [v0].iter().chain(pair).for_each(|&i| put(i));
                }
            } else {
                // Face ids are below MAX_FACES < 2^16.
                put(face as u32);
                put(corners.len() as u32);
                corners.iter().for_each(|&i| put(i));
            }
        }
        for value in [words, records, NO_NODE as usize, 1] {
            put(u32::try_from(value).unwrap_or(u32::MAX));
        }
        self.top = needed;
        self.peak = needed;
        Ok(count)
    }

    fn word(&self, at: usize) -> Result<usize, Error> {
        self.work
            .get(at)
            .map(|&w| w as usize)
            .ok_or(Error::CapacityExceeded {
                needed: at.saturating_add(1),
                capacity: self.work.len(),
            })
    }

    /// Splits the top set: one node, its fragments out, its two child sets pushed.
    fn split_top(&mut self, out: &mut Output<'_>) -> Result<(), Error> {
        let header = self
            .top
            .checked_sub(HEADER)
            .ok_or(Error::CapacityExceeded {
                needed: HEADER,
                capacity: self.top,
            })?;
        let words = self.word(header)?;
        let count = self.word(header + 1)?;
        let link = self.word(header + 2)? as u32;
        let level = self.word(header + 3)?;
        self.depth = self.depth.max(level);
        let base = header.saturating_sub(words);
        let (below, above) = self.work.split_at_mut(self.top);
        let set = below.get(base..header).unwrap_or(&[]);

        let (splitter, plane) = choose_splitter(
            self.mesh,
            set,
            count,
            &self.options,
            self.tolerance_sq,
            out.vertices,
        );
        let node = out.new_node(&plane, link)?;

        // Pass 1: the sizes of the two child sets.
        let (mut front, mut back) = ((0usize, 0usize), (0usize, 0usize));
        for (word, idx) in Records::new(set) {
            match Tally::of(&plane, idx, out.vertices).fate(word == splitter) {
                Fate::Node => {}
                Fate::Front => front = (front.0 + idx.len() + Record::HEAD, front.1 + 1),
                Fate::Back => back = (back.0 + idx.len() + Record::HEAD, back.1 + 1),
                Fate::Split {
                    front: f,
                    back: b,
                    pieces,
                    ..
                } => {
                    front = (front.0 + f + Record::HEAD, front.1 + 1);
                    back = (back.0 + b + Record::HEAD * pieces, back.1 + pieces);
                }
            }
        }
        let front_len = if front.1 > 0 { front.0 + HEADER } else { 0 };
        let back_len = if back.1 > 0 { back.0 + HEADER } else { 0 };
        let needed = self.top.saturating_add(front_len).saturating_add(back_len);
        let capacity = self.top.saturating_add(above.len());
        let children = above
            .get_mut(..front_len + back_len)
            .ok_or(Error::CapacityExceeded { needed, capacity })?;
        self.peak = self.peak.max(needed);
        let (front_area, back_area) = children.split_at_mut(front_len);

        // Pass 2: the node's fragments out (in set order, which is source order),
        // the others into the child sets.
        let mut front_writer = Writer::new(front_area);
        let mut back_writer = Writer::new(back_area);
        for (word, idx) in Records::new(set) {
            match Tally::of(&plane, idx, out.vertices).fate(word == splitter) {
                Fate::Node => out.emit(word, idx)?,
                Fate::Front => front_writer.record(word, idx),
                Fate::Back => back_writer.record(word, idx),
                Fate::Split { new, .. } => {
                    split(
                        out,
                        &plane,
                        word,
                        idx,
                        new,
                        &mut front_writer,
                        &mut back_writer,
                    )?;
                }
            }
        }
        out.close_node(node);
        let child_level = level.saturating_add(1);
        for (writer, (w, c), side) in [(&mut front_writer, front, 0), (&mut back_writer, back, 1)] {
            if c > 0 {
                for value in [w, c, (node as usize) * 2 + side, child_level] {
                    writer.put(u32::try_from(value).unwrap_or(u32::MAX));
                }
            }
        }
        // Move the children down over the set just split.
        let moved = front_len + back_len;
        let end = self.top.saturating_add(moved);
        if end > self.work.len() || base > self.top {
            // Unreachable: the children's area was taken from `work` above.
            return Err(Error::CapacityExceeded {
                needed: end,
                capacity: self.work.len(),
            });
        }
        self.work.copy_within(self.top..end, base);
        self.top = base + moved;
        Ok(())
    }
}

/// Appends words to a child set's area (its size was counted in pass 1).
struct Writer<'a> {
    area: &'a mut [u32],
    at: usize,
}

impl<'a> Writer<'a> {
    fn new(area: &'a mut [u32]) -> Self {
        Self { area, at: 0 }
    }

    fn put(&mut self, value: u32) {
        if let Some(w) = self.area.get_mut(self.at) {
            *w = value;
        }
        self.at += 1;
    }

    fn record(&mut self, word: u32, idx: &[u32]) {
        self.put(word);
        self.put(idx.len() as u32);
        idx.iter().for_each(|&i| self.put(i));
    }

    /// Starts a record whose length is filled in by [`Writer::end`].
    fn begin(&mut self, word: u32) -> usize {
        self.put(word);
        let at = self.at;
        self.put(0);
        at
    }

    fn end(&mut self, len_at: usize) {
        let len = self.at.saturating_sub(len_at + 1);
        if let Some(w) = self.area.get_mut(len_at) {
            *w = len as u32;
        }
    }
}

/// Cuts polygon `idx` by the exact signs of the distances (see [`Tally`]): each edge
/// crossing the plane makes one split point. The front is one polygon
/// (Sutherland-Hodgman: the vertices in front or exactly on the plane and the split
/// points, in order); the back is one piece per stretch of vertices behind the plane,
/// from the point where the boundary enters the back (a split point, or a vertex
/// exactly on the plane) to where it leaves, closed by the chord that the front
/// polygon bridges the other way. So the pieces' boundaries add up to the polygon's
/// (the chords cancel) even when it crosses the plane more than twice and is not
/// planar, where Sutherland-Hodgman's two sets of bridges would not be the same
/// segments. All pieces keep the polygon's winding; `new` split points are made.
fn split(
    out: &mut Output<'_>,
    plane: &Plane,
    word: u32,
    idx: &[u32],
    new: usize,
    front: &mut Writer<'_>,
    back: &mut Writer<'_>,
) -> Result<(), Error> {
    let len = idx.len();
    let at = |k: usize| idx.get(k % len.max(1)).copied().unwrap_or(0);
    let side = |out: &Output<'_>, k: usize| exact_side(plane.distance(vertex(out.vertices, at(k))));
    let crosses = |out: &Output<'_>, k: usize| {
        matches!(
            (side(out, k), side(out, k + 1)),
            (Side::Front, Side::Back) | (Side::Back, Side::Front)
        )
    };
    // The front, making the split points: the j-th crossing edge (from edge 0) makes
    // vertex `first + j`.
    let first = out.vertex_count;
    let f_len = front.begin(word);
    let mut made = 0usize;
    for k in 0..len {
        let (a, b) = (at(k), at(k + 1));
        if side(out, k) != Side::Back {
            front.put(a);
        }
        if crosses(out, k) {
            let (sa, sb) = (
                plane.distance(vertex(out.vertices, a)),
                plane.distance(vertex(out.vertices, b)),
            );
            let p = split_point(out.vertices, a, sa, b, sb);
            let root = out.seams().root(a, b);
            let x = out.push_vertex(p, root, new.saturating_sub(made + 1))?;
            made += 1;
            front.put(x);
        }
    }
    front.end(f_len);
    // The back pieces, walking from the start of a back stretch.
    let made = made.max(1);
    let split_vertex = |ordinal: usize| {
        // Vertex indices fit u32 (push_vertex checked).
        first.saturating_add(ordinal % made) as u32
    };
    let start = (0..len)
        .find(|&k| side(out, k) == Side::Back && side(out, k + len - 1) != Side::Back)
        .unwrap_or(0);
    let mut ordinal = (0..start).filter(|&k| crosses(out, k)).count();
    let mut piece = None;
    for k in start..start + len {
        if side(out, k) == Side::Back {
            let before = k + len - 1;
            if side(out, before) != Side::Back {
                piece = Some(back.begin(word));
                if side(out, before) == Side::On {
                    back.put(at(before));
                } else {
                    back.put(split_vertex(ordinal + made - 1));
                }
            }
            back.put(at(k));
            if side(out, k + 1) != Side::Back {
                if side(out, k + 1) == Side::On {
                    back.put(at(k + 1));
                } else {
                    back.put(split_vertex(ordinal));
                }
                if let Some(len_at) = piece.take() {
                    back.end(len_at);
                }
            }
        }
        if crosses(out, k) {
            ordinal += 1;
        }
    }
    Ok(())
}

/// Chooses the splitter of a set: among up to `options.candidates` records spread
/// evenly over the set (skipping those of zero normal), the lowest score
/// `split_weight * splits + |front - back|`, the earliest on a tie. If no candidate
/// has a normal, the first record that has one; if none has, record 0 (a node of
/// zero-normal fragments, which cover no pixels). Returns the splitter's surface (its
/// record word: a face, or a fan triangle of one, see [`Record::fan`]) and plane:
/// every fragment of that surface in the set goes to the node (a face that is not
/// planar and kept whole, cut earlier, keeps its pieces together in its plane's node).
fn choose_splitter(
    mesh: &Mesh<'_>,
    set: &[u32],
    count: usize,
    options: &BspOptions,
    tolerance_sq: f64,
    vertices: &[[f32; 3]],
) -> (u32, Plane) {
    let tries = usize::from(options.candidates.max(1));
    let weight = u64::from(options.split_weight);
    let mut best: Option<(u64, u32, Plane)> = None;
    let mut next_try = 0usize; // index j of the next candidate ordinal j * count / tries
    for (ordinal, (word, _)) in Records::new(set).enumerate() {
        if next_try >= tries {
            break;
        }
        if ordinal < next_try.saturating_mul(count) / tries {
            continue;
        }
        while next_try < tries && next_try.saturating_mul(count) / tries <= ordinal {
            next_try += 1;
        }
        let plane = Plane::of_record(mesh, word, tolerance_sq);
        if plane.is_degenerate() {
            continue;
        }
        let bound = best.as_ref().map_or(u64::MAX, |b| b.0);
        let (mut splits, mut front, mut back) = (0u64, 0u64, 0u64);
        for (other, idx) in Records::new(set) {
            match Tally::of(&plane, idx, vertices).fate(other == word) {
                Fate::Node => {}
                Fate::Front => front += 1,
                Fate::Back => back += 1,
                Fate::Split { .. } => {
                    splits += 1;
                    front += 1;
                    back += 1;
                }
            }
            if weight.saturating_mul(splits) >= bound {
                break;
            }
        }
        let score = weight
            .saturating_mul(splits)
            .saturating_add(front.abs_diff(back));
        if score < bound {
            best = Some((score, word, plane));
        }
    }
    if let Some((_, word, plane)) = best {
        return (word, plane);
    }
    let first_with_normal = Records::new(set)
        .map(|(word, _)| (word, Plane::of_record(mesh, word, tolerance_sq)))
        .find(|(_, plane)| !plane.is_degenerate());
    first_with_normal.unwrap_or_else(|| {
        let word = set.first().copied().unwrap_or(0);
        (word, Plane::of_record(mesh, word, tolerance_sq))
    })
}
