//! Newell's loop over the list: the head is painted when no later fragment must go
//! before it, else a fragment is moved ahead (a shuffle, marked) or a cycle is cut
//! by a split; the list's order (farthest depth first) and its insertions.

use core::cmp::Reverse;

use super::sort::{Sorter, DEAD};
use crate::order::plane::Plane;
use crate::Capacity;
use crate::Error;

/// An f32 as a u32 of the same order (finite values).
fn ordered(x: f32) -> u32 {
    let b = x.to_bits();
    if b >> 31 == 1 {
        !b
    } else {
        b | (1 << 31)
    }
}

impl Sorter<'_, '_, '_> {
    /// The list's sort key: farthest depth first, then slot.
    pub(super) fn key(&self, f: u32) -> (Reverse<u32>, u32) {
        let e = self.extent(f as usize);
        (Reverse(ordered(e[5])), f)
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
    pub(super) fn settle(&mut self) -> Result<(), Error> {
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
                Capacity::OrderWork,
                len.saturating_add(1).saturating_mul(3),
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
}
