//! Every capacity that is short at once ([`Error::CapacitiesExceeded`]), in a
//! fixed-size list: no allocation.

use core::fmt;

use super::{Capacity, Error};

/// The most shortfalls one [`Shortfalls`] holds: the mesh's `V`, `F`, `E` of a
/// bake, a frame's `FACETS`, `LINES` and clipped corners, a scene's `V`, `F`, `E`
/// and `C`. Four keep [`Error`] as small as it was (48 bytes on a 64-bit host).
pub const MAX_SHORTFALLS: usize = 4;

/// One capacity that is too small: which, what the input needs and what is
/// compiled in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Shortfall {
    /// The buffer ([`Capacity`]'s doc says which stage uses it and what to grow).
    pub what: Capacity,
    /// The size the input needs (a lower bound when [`at_least`](Self::at_least)).
    pub needed: usize,
    /// The compiled size.
    pub capacity: usize,
    /// `needed` is a lower bound: the exact count needs a buffer that is short
    /// too (a drawing's unique edges are counted once its `V` fits; until then
    /// `E` needs at least half the face corners).
    pub at_least: bool,
}

impl fmt::Display for Shortfall {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let at_least = if self.at_least { "at least " } else { "" };
        write!(
            f,
            "{}: {at_least}{} needed, capacity {}",
            self.what, self.needed, self.capacity
        )
    }
}

/// The capacities of one input that are all too small, so that one run names every
/// size to grow: what [`Error::CapacitiesExceeded`] carries. Fixed-size (at most
/// [`MAX_SHORTFALLS`], needs kept in 32 bits), no allocation.
///
/// ```
/// use pbuffer::{Capacity, Error};
/// use pbuffer::Shortfalls;
/// let mut short = Shortfalls::new();
/// short.check(Capacity::Vertices, 2903, 8);
/// short.check(Capacity::Faces, 5804, 6);
/// short.check(Capacity::Edges, 4, 12); // fits: not listed
/// let e = short.into_result().unwrap_err();
/// assert_eq!(e.to_string(), "capacities too small: mesh vertices (V): 2903 needed, \
///     capacity 8; mesh faces (F): 5804 needed, capacity 6");
/// assert_eq!(e.shortfalls().len(), 2);
/// ```
#[derive(Clone, Copy, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Shortfalls {
    // Apart and in 32 bits (a need past `u32::MAX` saturates), so that an
    // `Error` carrying them is no larger than before.
    what: [Capacity; MAX_SHORTFALLS],
    needed: [u32; MAX_SHORTFALLS],
    capacity: [u32; MAX_SHORTFALLS],
    /// Bit `k`: entry `k`'s need is a lower bound.
    at_least: u8,
    len: u8,
}

/// The listed shortfalls only.
impl fmt::Debug for Shortfalls {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// The same shortfalls in the same order.
impl PartialEq for Shortfalls {
    fn eq(&self, other: &Self) -> bool {
        self.iter().eq(other.iter())
    }
}

impl core::hash::Hash for Shortfalls {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        for item in self.iter() {
            item.hash(state);
        }
    }
}

impl Default for Shortfalls {
    fn default() -> Self {
        Self::new()
    }
}

impl Shortfalls {
    /// None yet.
    pub const fn new() -> Self {
        Self {
            what: [Capacity::Vertices; MAX_SHORTFALLS],
            needed: [0; MAX_SHORTFALLS],
            capacity: [0; MAX_SHORTFALLS],
            at_least: 0,
            len: 0,
        }
    }

    /// Lists `what` when `needed` is more than `capacity` (past
    /// [`MAX_SHORTFALLS`], the rest are dropped).
    pub fn check(&mut self, what: Capacity, needed: usize, capacity: usize) {
        self.check_at_least(what, needed, capacity, false);
    }

    /// [`check`](Self::check) with `needed` a lower bound when `at_least`.
    pub fn check_at_least(
        &mut self,
        what: Capacity,
        needed: usize,
        capacity: usize,
        at_least: bool,
    ) {
        if needed <= capacity {
            return;
        }
        let k = usize::from(self.len);
        let narrow = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        if let (Some(w), Some(n), Some(c)) = (
            self.what.get_mut(k),
            self.needed.get_mut(k),
            self.capacity.get_mut(k),
        ) {
            (*w, *n, *c) = (what, narrow(needed), narrow(capacity));
            self.at_least |= u8::from(at_least) << k;
            self.len += 1;
        }
    }

    /// The shortfalls, in the order they were found.
    pub fn iter(&self) -> impl Iterator<Item = Shortfall> + '_ {
        (0..self.len()).filter_map(move |k| {
            Some(Shortfall {
                what: *self.what.get(k)?,
                needed: *self.needed.get(k)? as usize,
                capacity: *self.capacity.get(k)? as usize,
                at_least: self.at_least & (1 << k) != 0,
            })
        })
    }

    /// How many.
    pub fn len(&self) -> usize {
        usize::from(self.len).min(MAX_SHORTFALLS)
    }

    /// None listed?
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The one for `what`, if it is short.
    pub fn get(&self, what: Capacity) -> Option<Shortfall> {
        self.iter().find(|s| s.what == what)
    }

    /// `Ok` when nothing is short; one shortfall is the familiar
    /// [`Error::CapacityExceeded`]; two or more are [`Error::CapacitiesExceeded`].
    pub fn into_result(self) -> Result<(), Error> {
        let mut all = self.iter();
        match (all.next(), all.next()) {
            (None, _) => Ok(()),
            (Some(one), None) => Err(Error::CapacityExceeded {
                what: one.what,
                needed: one.needed,
                capacity: one.capacity,
            }),
            _ => Err(Error::CapacitiesExceeded(self)),
        }
    }

    /// The shortfalls `error` names: its one capacity, or all of them; none for
    /// any other error.
    pub fn of<T>(error: &Error<T>) -> Self {
        let mut all = Self::new();
        match *error {
            Error::CapacityExceeded {
                what,
                needed,
                capacity,
            } => all.check(what, needed, capacity),
            Error::CapacitiesExceeded(list) => all = list,
            _ => {}
        }
        all
    }
}

impl fmt::Display for Shortfalls {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("capacities too small: ")?;
        for (k, item) in self.iter().enumerate() {
            if k > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{item}")?;
        }
        Ok(())
    }
}

impl<T> Error<T> {
    /// Every capacity this error names as too small, with its need: the one of
    /// [`CapacityExceeded`](Error::CapacityExceeded), the list of
    /// [`CapacitiesExceeded`](Error::CapacitiesExceeded), none for any other error.
    pub fn shortfalls(&self) -> Shortfalls {
        Shortfalls::of(self)
    }
}
