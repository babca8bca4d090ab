//! Bitsets of `u32` words: a flag for each face or edge (facing, drawn, planar);
//! and the bytes of fixed buffers, for the RAM the short API reports.

use core::mem::{align_of, size_of};

/// `bytes` rounded up to a multiple of `align` (a power of two): the size of a
/// struct whose fields sum to `bytes` (fields sorted by alignment leave no gap
/// but the tail).
pub(crate) const fn padded(bytes: usize, align: usize) -> usize {
    bytes.div_ceil(align) * align
}

/// Bytes of a `heapless::Vec<T, n>`: its length word and `n` slots, padded.
pub(crate) const fn vec_bytes<T>(n: usize) -> usize {
    padded(
        size_of::<heapless::Vec<T, 0>>() + n * size_of::<T>(),
        align_of::<heapless::Vec<T, 0>>(),
    )
}

/// Bit `i` of a bitset of words (bit `i % 32` of word `i / 32`): a face's or an
/// edge's flag; false beyond the words.
pub(crate) fn bit(bits: &[u32], i: usize) -> bool {
    bits.get(i / 32).is_some_and(|w| w & (1 << (i % 32)) != 0)
}

/// Sets bit `i` of a bitset to `on` (nothing beyond the words).
pub(crate) fn set_bit(bits: &mut [u32], i: usize, on: bool) {
    if let Some(w) = bits.get_mut(i / 32) {
        if on {
            *w |= 1 << (i % 32);
        } else {
            *w &= !(1 << (i % 32));
        }
    }
}
