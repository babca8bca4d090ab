//! The occlusion graph: which surfaces can cover one pixel together, in depth order.

use super::SchemeViolation;
use crate::Error;

/// Surfaces `0..surfaces` and the *paths* of the paper's priority graph: each path is
/// a chain of surfaces that can overlap at one pixel, nearest first. Borrowed, never
/// copied.
///
/// The paper's fig. 2 (surface 1 occludes 2; 1, 2 and 3 occlude 4), numbered from 0:
///
/// ```
/// use pbuffer::codes::OcclusionGraph;
///
/// let graph = OcclusionGraph::new(4, &[&[0, 1, 3], &[2, 3]])?;
/// assert_eq!(graph.longest_path(), 3);
/// assert_eq!(graph.largest_union(), 4);
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OcclusionGraph<'p> {
    surfaces: usize,
    paths: &'p [&'p [u16]],
}

impl<'p> OcclusionGraph<'p> {
    /// A graph of `surfaces` surfaces and the given paths.
    ///
    /// Errors ([`Error::Scheme`]), the first found: an empty path, a surface index not
    /// below `surfaces`, a surface listed twice in one path, two paths that order their
    /// shared surfaces differently.
    pub fn new(surfaces: usize, paths: &'p [&'p [u16]]) -> Result<Self, Error> {
        let violation = |v| Err(Error::Scheme(v));
        for (index, path) in paths.iter().enumerate() {
            if path.is_empty() {
                return violation(SchemeViolation::EmptyPath { path: index });
            }
            for (k, &surface) in path.iter().enumerate() {
                if usize::from(surface) >= surfaces {
                    return violation(SchemeViolation::UnknownSurface {
                        path: index,
                        surface,
                    });
                }
                if path
                    .get(..k)
                    .is_some_and(|nearer| nearer.contains(&surface))
                {
                    return violation(SchemeViolation::RepeatedSurface {
                        path: index,
                        surface,
                    });
                }
            }
        }
        for (first, a) in paths.iter().enumerate() {
            for (second, b) in paths.iter().enumerate().skip(first + 1) {
                let shared_in_a = a.iter().filter(|s| b.contains(s));
                let shared_in_b = b.iter().filter(|s| a.contains(s));
                if !shared_in_a.eq(shared_in_b) {
                    return violation(SchemeViolation::OrderConflict { first, second });
                }
            }
        }
        Ok(Self { surfaces, paths })
    }

    /// The number of surfaces.
    pub const fn surfaces(&self) -> usize {
        self.surfaces
    }

    /// The paths, each nearest surface first.
    pub const fn paths(&self) -> &'p [&'p [u16]] {
        self.paths
    }

    /// Path `index`, if there is one.
    pub fn path(&self, index: usize) -> Option<&'p [u16]> {
        self.paths.get(index).copied()
    }

    /// The most surfaces on one path: the least code width of every scheme
    /// (Proposition 1), and the width of the priority scheme.
    pub fn longest_path(&self) -> usize {
        self.paths.iter().map(|p| p.len()).max().unwrap_or(0)
    }

    /// The most distinct surfaces on two paths together (or one): the least code width
    /// of the combination scheme (the corollary of Proposition 2).
    pub fn largest_union(&self) -> usize {
        let mut largest = 0;
        for first in 0..self.paths.len() {
            for second in first..self.paths.len() {
                largest = largest.max(self.union(first, second).count());
            }
        }
        largest
    }

    /// The distinct surfaces of paths `first` and `second`: all of `first`, then those
    /// of `second` that `first` lacks.
    pub(crate) fn union(&self, first: usize, second: usize) -> impl Iterator<Item = u16> + 'p {
        let a = self.path(first).unwrap_or(&[]);
        let b = self.path(second).unwrap_or(&[]);
        a.iter()
            .chain(b.iter().filter(move |s| !a.contains(s)))
            .copied()
    }

    /// Writes each surface's depth level into `levels` (0 = nothing behind it on any
    /// chain of paths, otherwise one more than the deepest level behind it) and
    /// returns the number of levels. Levels strictly fall along every path.
    ///
    /// Errors: `levels` is not one per surface; the depth orders form a cycle.
    pub(crate) fn depth_levels(&self, levels: &mut [u128]) -> Result<u32, Error> {
        if levels.len() != self.surfaces {
            return Err(Error::Scheme(SchemeViolation::CodeCount {
                given: levels.len(),
                expected: self.surfaces,
            }));
        }
        levels.fill(0);
        // Relax until stable (longest paths in a DAG, without recursion). A level of
        // `surfaces` or more needs a chain longer than the surfaces: a cycle.
        let ceiling = self.surfaces as u128;
        let mut changed = true;
        while changed {
            changed = false;
            for path in self.paths {
                for pair in path.windows(2).rev() {
                    let &[near, far] = pair else { continue };
                    let behind = levels.get(usize::from(far)).copied().unwrap_or(0);
                    let Some(level) = levels.get_mut(usize::from(near)) else {
                        continue;
                    };
                    if *level <= behind {
                        *level = behind + 1;
                        changed = true;
                        if *level >= ceiling {
                            return Err(Error::Scheme(SchemeViolation::CyclicOrder));
                        }
                    }
                }
            }
        }
        let deepest = levels.iter().copied().max();
        Ok(deepest.map_or(0, |d| u32::try_from(d + 1).unwrap_or(u32::MAX)))
    }
}
