//! `f32` to integer exactly as Rust's `as` converts (toward zero, saturating,
//! NaN to 0), in integer operations on Arm cores without an FPU: there `as` is
//! a soft-float call and three compare calls (about 80 instructions on the
//! Cortex-M3), these about 12. Elsewhere `as` itself, one instruction with an
//! FPU.

/// `x as i32`.
#[inline(always)]
pub(super) fn to_i32(x: f32) -> i32 {
    #[cfg(all(target_arch = "arm", not(target_abi = "eabihf")))]
    {
        to_i32_bits(x)
    }
    #[cfg(not(all(target_arch = "arm", not(target_abi = "eabihf"))))]
    {
        x as i32
    }
}

/// `x as u32`.
#[inline(always)]
pub(super) fn to_u32(x: f32) -> u32 {
    #[cfg(all(target_arch = "arm", not(target_abi = "eabihf")))]
    {
        to_u32_bits(x)
    }
    #[cfg(not(all(target_arch = "arm", not(target_abi = "eabihf"))))]
    {
        x as u32
    }
}

/// `x as i32` from the bits of `x`.
#[inline(always)]
#[cfg_attr(
    not(all(target_arch = "arm", not(target_abi = "eabihf"))),
    allow(dead_code)
)]
pub(super) fn to_i32_bits(x: f32) -> i32 {
    let b = x.to_bits();
    let e = (b >> 23 & 0xFF) as i32;
    if e < 127 {
        // |x| < 1, zero and subnormals included.
        return 0;
    }
    if e >= 127 + 31 {
        // |x| >= 2^31, infinities and NaN.
        return if e == 255 && b & 0x7F_FFFF != 0 {
            0
        } else if b >> 31 != 0 {
            i32::MIN
        } else {
            i32::MAX
        };
    }
    // |x| = m 2^(e - 150), below 2^31: m << 7 at most.
    let m = b & 0x7F_FFFF | 0x80_0000;
    let v = if e >= 150 {
        m << (e - 150)
    } else {
        m >> (150 - e)
    } as i32;
    if b >> 31 != 0 {
        -v
    } else {
        v
    }
}

/// `x as u32` from the bits of `x`.
#[inline(always)]
#[cfg_attr(
    not(all(target_arch = "arm", not(target_abi = "eabihf"))),
    allow(dead_code)
)]
pub(super) fn to_u32_bits(x: f32) -> u32 {
    let b = x.to_bits();
    let e = (b >> 23 & 0xFF) as i32;
    if b >> 31 != 0 || e < 127 {
        // Negative (or NaN with its sign bit), or below 1.
        return 0;
    }
    if e >= 127 + 32 {
        return if e == 255 && b & 0x7F_FFFF != 0 {
            0
        } else {
            u32::MAX
        };
    }
    let m = b & 0x7F_FFFF | 0x80_0000;
    if e >= 150 {
        m << (e - 150)
    } else {
        m >> (150 - e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values at every exponent and around each limit, both signs, the
    /// specials, and random bit patterns.
    fn samples() -> impl Iterator<Item = f32> {
        let mut rng = 0x2545_F491u32;
        let random = core::iter::repeat_with(move || {
            rng ^= rng << 13;
            rng ^= rng >> 17;
            rng ^= rng << 5;
            f32::from_bits(rng)
        })
        .take(200_000);
        let exponents = (0..=255u32)
            .flat_map(|e| [0, 1, 0x40_0000, 0x7F_FFFF].map(move |m| f32::from_bits(e << 23 | m)));
        let limits = [
            2147483648.0f32,
            2147483520.0,
            4294967296.0,
            4294967040.0,
            1.0,
            0.5,
        ];
        let limits = limits.into_iter().flat_map(|v| {
            [
                v,
                f32::from_bits(v.to_bits() - 1),
                f32::from_bits(v.to_bits() + 1),
            ]
        });
        let specials = [
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            0.0,
            -0.0,
        ];
        random
            .chain(exponents)
            .chain(limits)
            .chain(specials)
            .flat_map(|v| [v, -v])
    }

    #[test]
    fn integer_conversions_equal_the_as_casts() {
        for x in samples() {
            assert_eq!(to_i32_bits(x), x as i32, "{x:e} {:08x}", x.to_bits());
            assert_eq!(to_u32_bits(x), x as u32, "{x:e} {:08x}", x.to_bits());
        }
    }
}
