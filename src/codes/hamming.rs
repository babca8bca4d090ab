//! Extended Hamming codes, the surface codes of the path scheme (scheme 2).

use super::bit_length;
use crate::Error;

/// The extended Hamming code of length `2^order`: `2^order - order - 1` data bits,
/// minimum distance 4, so every nonzero codeword has weight 4 or more.
///
/// Digits are numbered as the paper writes them, left to right from position 0: the
/// overall parity is at position 0, the Hamming parities at positions 1, 2, 4, 8, ...
/// and the data bits, most significant first, fill the other positions. As a `u128`,
/// position `i` is bit `length - 1 - i`, so the words read like the paper's tables.
///
/// ```
/// use pbuffer::codes::HAMMING_8_4;
///
/// // Table 1 of the paper: surface code 0001 -> 01101001.
/// assert_eq!(HAMMING_8_4.encode(0b0001)?, 0b0110_1001);
/// # Ok::<(), pbuffer::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ExtendedHamming {
    order: u32,
}

/// The (8,4) extended Hamming code of the paper's fig. 5: 16 paths of up to 4 surfaces.
pub const HAMMING_8_4: ExtendedHamming = ExtendedHamming { order: 3 };

/// The (16,11) extended Hamming code: 32 paths of up to 11 surfaces.
pub const HAMMING_16_11: ExtendedHamming = ExtendedHamming { order: 4 };

impl ExtendedHamming {
    /// The code of length `2^order`, for `order` in 2..=7 (lengths 4 to 128), else `None`.
    pub const fn with_order(order: u32) -> Option<Self> {
        if order >= 2 && order <= 7 {
            Some(Self { order })
        } else {
            None
        }
    }

    /// The number of check bits of the Hamming part (the overall parity is one more).
    pub const fn order(self) -> u32 {
        self.order
    }

    /// Codeword length in bits.
    pub const fn length(self) -> u32 {
        1 << self.order
    }

    /// Data bits per codeword.
    pub const fn data_bits(self) -> u32 {
        self.length() - self.order - 1
    }

    /// The codeword of `data`. The code is linear: `encode(a ^ b) = encode(a) ^ encode(b)`.
    ///
    /// Errors: [`Error::CodeTooWide`] if `data` has more than [`data_bits`](Self::data_bits) bits.
    pub fn encode(self, data: u128) -> Result<u128, Error> {
        let (length, data_bits) = (self.length(), self.data_bits());
        if bit_length(data) > data_bits {
            return Err(Error::CodeTooWide {
                needed: bit_length(data) as usize,
                capacity: data_bits as usize,
            });
        }
        let mut word = 0u128;
        let mut next = data_bits;
        let mut positions = 0u32;
        for position in 3..length {
            if position.is_power_of_two() {
                continue;
            }
            next -= 1;
            if (data >> next) & 1 == 1 {
                word |= 1 << (length - 1 - position);
                positions ^= position;
            }
        }
        // Hamming parities: make the XOR of the positions of all set bits zero.
        for check in 0..self.order {
            if (positions >> check) & 1 == 1 {
                word |= 1 << (length - 1 - (1 << check));
            }
        }
        // Overall parity at position 0: even weight.
        if word.count_ones() % 2 == 1 {
            word |= 1 << (length - 1);
        }
        Ok(word)
    }

    /// The syndrome of `word`: the XOR of the positions of its set bits, with the
    /// overall parity as bit `order`. Zero exactly for codewords (bits beyond the
    /// length count as nonzero syndrome).
    pub fn syndrome(self, word: u128) -> u32 {
        let length = self.length();
        if bit_length(word) > length {
            return u32::MAX;
        }
        let mut positions = 0;
        for position in 0..length {
            if (word >> (length - 1 - position)) & 1 == 1 {
                positions ^= position;
            }
        }
        positions | (word.count_ones() % 2) << self.order
    }

    /// Whether `word` is a codeword.
    pub fn is_codeword(self, word: u128) -> bool {
        self.syndrome(word) == 0
    }
}
