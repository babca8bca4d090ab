//! Vectors over GF(2) held as `u128` bit sets: rank, span membership, cosets.

use super::bit_length;
use crate::Error;

/// An echelon basis of a subspace of GF(2)^`W` (`W` up to 128): slot `b` holds the
/// basis vector whose highest set bit is `b`, or 0.
///
/// Because every basis vector has its own highest bit (its *pivot*), reducing a vector
/// from the top bit down clears every pivot bit it can; what is left is the same for
/// all vectors of one coset of the span.
///
/// ```
/// use pbuffer::codes::Basis;
///
/// let mut span = Basis::<4>::new();
/// assert_eq!(span.insert(0b0011), Ok(true));
/// assert_eq!(span.insert(0b0110), Ok(true));
/// assert_eq!(span.insert(0b0101), Ok(false)); // 0011 + 0110
/// assert!(span.contains(0b0101));
/// assert_eq!(span.rank(), 2);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Basis<const W: usize> {
    slots: [u128; W],
    rank: u32,
}

impl<const W: usize> Default for Basis<W> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const W: usize> Basis<W> {
    /// The zero subspace.
    pub const fn new() -> Self {
        Self {
            slots: [0; W],
            rank: 0,
        }
    }

    /// The dimension of the span.
    pub const fn rank(&self) -> u32 {
        self.rank
    }

    /// The representative of the coset `v + span` with no pivot bit set: two vectors
    /// give the same result exactly when their sum is in the span.
    pub fn reduce(&self, mut v: u128) -> u128 {
        // From the top down: a basis vector only changes bits at or below its pivot.
        for (bit, &slot) in self.slots.iter().enumerate().take(128).rev() {
            if (v >> bit) & 1 == 1 {
                v ^= slot;
            }
        }
        v
    }

    /// Whether `v` lies in the span.
    pub fn contains(&self, v: u128) -> bool {
        self.reduce(v) == 0
    }

    /// Adds `v` to the span: `Ok(true)` if it was independent of the basis (the rank
    /// grew), `Ok(false)` if it was already in the span (zero included).
    ///
    /// Errors: [`Error::CodeTooWide`] if `v` has a bit at or above `W`.
    pub fn insert(&mut self, v: u128) -> Result<bool, Error> {
        let needed = bit_length(v) as usize;
        if needed > W {
            return Err(Error::CodeTooWide {
                needed,
                capacity: W,
            });
        }
        let reduced = self.reduce(v);
        if reduced == 0 {
            return Ok(false);
        }
        let pivot = bit_length(reduced) as usize - 1;
        match self.slots.get_mut(pivot) {
            Some(slot) => {
                *slot = reduced;
                self.rank += 1;
                Ok(true)
            }
            // Not reached: the pivot is below `needed <= W`.
            None => Err(Error::CodeTooWide {
                needed,
                capacity: W,
            }),
        }
    }

    /// The pivot bits: a vector with none of them set is its own coset representative.
    pub fn pivots(&self) -> u128 {
        self.slots
            .iter()
            .filter(|&&slot| slot != 0)
            .fold(0, |mask, &slot| mask | 1 << (bit_length(slot) - 1))
    }
}

/// Whether `vectors` are linearly independent over GF(2) (a zero vector, or a repeated
/// one, makes them dependent).
///
/// Errors: [`Error::CodeTooWide`] if a vector has a bit at or above `W`.
pub fn independent<const W: usize>(vectors: impl IntoIterator<Item = u128>) -> Result<bool, Error> {
    let mut span = Basis::<W>::new();
    for v in vectors {
        if !span.insert(v)? {
            return Ok(false);
        }
    }
    Ok(true)
}

/// Spreads the bits of `value`, lowest first, over the set bits of `mask`, lowest
/// first (a parallel bit deposit).
pub(crate) fn deposit(mut value: u128, mask: u128) -> u128 {
    let mut out = 0;
    let mut rest = mask;
    while rest != 0 && value != 0 {
        let lowest = rest & rest.wrapping_neg();
        if value & 1 == 1 {
            out |= lowest;
        }
        value >>= 1;
        rest ^= lowest;
    }
    out
}
