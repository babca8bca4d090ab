//! The work stack of fragment sets: the root set pushed, one node split at a time.

use super::choose::choose_splitter;
use super::output::Output;
use super::split::{split, Writer};
use super::HEADER;
use crate::mesh::Mesh;
use crate::order::bsp::{BspOptions, NO_NODE};
use crate::order::plane::{fan_triangles, fans, Fate, Record, Records, Tally};
use crate::Capacity;
use crate::Error;

/// The build's state: the work stack of fragment sets still to be split.
///
/// `work[..top]` holds sets, each its records (see [`Record`]) followed by a header
/// `[words, count, link, level]`: `link` = parent node * 2 + (0 front, 1 back), or
/// [`NO_NODE`] for the root; `level` = the node's depth (root 1). The top set is split
/// next; its children are written above it, then moved down in its place.
pub(super) struct Build<'w, 'm, 'a> {
    pub(super) mesh: &'w Mesh<'m>,
    pub(super) options: BspOptions,
    pub(super) tolerance_sq: f64,
    pub(super) work: &'a mut [u32],
    pub(super) top: usize,
    pub(super) peak: usize,
    pub(super) depth: usize,
}

impl Build<'_, '_, '_> {
    /// Pushes the root set: every face in order, whole, or as its fan triangles when
    /// it is not planar (see [`fans`] and
    /// [`BspTree::build_with`](crate::order::BspTree::build_with)). Returns the number
    /// of faces.
    pub(super) fn push_faces(&mut self) -> Result<usize, Error> {
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
        let area = self.work.get_mut(..needed).ok_or(Error::CapacityExceeded {
            what: Capacity::OrderWork,
            needed,
            capacity,
        })?;
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
                for (word, triangle) in fan_triangles(face, corners) {
                    put(word);
                    put(3);
                    triangle.iter().for_each(|&i| put(i));
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
                what: Capacity::OrderWork,
                needed: at.saturating_add(1),
                capacity: self.work.len(),
            })
    }

    /// Splits the top set: one node, its fragments out, its two child sets pushed.
    pub(super) fn split_top(&mut self, out: &mut Output<'_>) -> Result<(), Error> {
        let header = self
            .top
            .checked_sub(HEADER)
            .ok_or(Error::CapacityExceeded {
                what: Capacity::OrderWork,
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
            .ok_or(Error::CapacityExceeded {
                what: Capacity::OrderWork,
                needed,
                capacity,
            })?;
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
                what: Capacity::OrderWork,
                needed: end,
                capacity: self.work.len(),
            });
        }
        self.work.copy_within(self.top..end, base);
        self.top = base + moved;
        Ok(())
    }
}
