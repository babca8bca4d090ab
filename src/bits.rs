//! Bitsets of `u32` words: a flag for each face or edge (facing, drawn, planar).

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
