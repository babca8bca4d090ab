//! Screen-space vertices in fixed point, and the ranges the scan converter works in.

use fixed::types::extra::LeEqU32;
use fixed::FixedI32;

use crate::Error;

/// Half-width of the guard band, in pixels.
///
/// When every vertex of a polygon satisfies `|x|, |y| <= GUARD_BAND_PX`, all edge
/// set-up runs in 64-bit and all per-row stepping in 32-bit integers, with headroom
/// (see the module docs of [`scan`](crate::scan) for the bounds). A polygon with a
/// vertex beyond the band takes the exact wide path instead: its edges are clipped
/// to the viewport and evaluated per row in 128-bit arithmetic, so the pixels are
/// the same as an unbounded rasterizer's, only slower.
pub const GUARD_BAND_PX: i32 = 1 << 14;

pub use crate::error::MAX_VIEWPORT;

/// The largest supported number of sub-pixel bits.
pub const MAX_SUBPIXEL_BITS: u32 = 12;

/// A vertex in screen space: x to the right, y down, in pixels, with `Frac::U32`
/// (= S) fractional bits.
///
/// S is the sub-pixel precision: vertices live on the 1/2^S grid. Pixel (i, j) is
/// sampled at its centre (i + 0.5, j + 0.5). S may be 0 to
/// [`MAX_SUBPIXEL_BITS`]; a larger S fails to compile where the point is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ScreenPoint<Frac: LeEqU32> {
    /// Horizontal position in pixels.
    pub x: FixedI32<Frac>,
    /// Vertical position in pixels, growing downward.
    pub y: FixedI32<Frac>,
}

impl<Frac: LeEqU32> ScreenPoint<Frac> {
    /// A point from two fixed-point coordinates.
    pub const fn new(x: FixedI32<Frac>, y: FixedI32<Frac>) -> Self {
        Self { x, y }
    }

    /// A point from raw fixed-point bits: the value is `raw / 2^S` pixels.
    pub const fn from_bits(x: i32, y: i32) -> Self {
        Self {
            x: FixedI32::from_bits(x),
            y: FixedI32::from_bits(y),
        }
    }

    /// Snaps an `f32` position to the 1/2^S grid (round to nearest, ties to even).
    pub fn from_f32(x: f32, y: f32) -> Result<Self, Error> {
        if !x.is_finite() || !y.is_finite() {
            return Err(Error::NonFinite);
        }
        match (FixedI32::checked_from_num(x), FixedI32::checked_from_num(y)) {
            (Some(x), Some(y)) => Ok(Self { x, y }),
            _ => Err(Error::OutOfRange),
        }
    }

    /// Snaps an `f64` position to the 1/2^S grid (round to nearest, ties to even).
    pub fn from_f64(x: f64, y: f64) -> Result<Self, Error> {
        if !x.is_finite() || !y.is_finite() {
            return Err(Error::NonFinite);
        }
        match (FixedI32::checked_from_num(x), FixedI32::checked_from_num(y)) {
            (Some(x), Some(y)) => Ok(Self { x, y }),
            _ => Err(Error::OutOfRange),
        }
    }

    /// True when both coordinates lie inside the guard band.
    pub fn in_guard_band(&self) -> bool {
        let limit = i64::from(GUARD_BAND_PX) << Frac::U32;
        i64::from(self.x.to_bits()).abs() <= limit && i64::from(self.y.to_bits()).abs() <= limit
    }
}

/// The pixel rectangle `[0, width) x [0, height)` that spans are clipped to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Viewport {
    /// Width in pixels, at most [`MAX_VIEWPORT`].
    pub width: u16,
    /// Height in pixels, at most [`MAX_VIEWPORT`].
    pub height: u16,
}

impl Viewport {
    /// A viewport of the given size, or `Err(ViewportTooLarge)` beyond [`MAX_VIEWPORT`].
    pub fn new(width: u32, height: u32) -> Result<Self, Error> {
        match (u16::try_from(width), u16::try_from(height)) {
            (Ok(w), Ok(h)) if width <= MAX_VIEWPORT && height <= MAX_VIEWPORT => Ok(Self {
                width: w,
                height: h,
            }),
            _ => Err(Error::ViewportTooLarge { width, height }),
        }
    }
}

/// Sub-pixel bits of a fixed-point fraction type, checked at compile time.
pub(crate) struct Subpixel<Frac>(core::marker::PhantomData<Frac>);

impl<Frac: LeEqU32> Subpixel<Frac> {
    /// S, the number of fractional bits; a compile error when above the maximum.
    pub(crate) const BITS: u32 = {
        assert!(
            Frac::U32 <= MAX_SUBPIXEL_BITS,
            "pbuffer supports at most 12 sub-pixel bits"
        );
        Frac::U32
    };
}
