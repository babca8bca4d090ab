//! The crate-wide error type.

use core::convert::Infallible;
use core::fmt;

/// Everything that can go wrong in pbuffer, as a value: no input panics.
///
/// `T` is the error of the span sink or draw target the spans go to; it is
/// [`Infallible`] for pure geometry and for in-memory targets such as
/// [`PackedFramebuffer`](crate::PackedFramebuffer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error<T = Infallible> {
    /// A coordinate was NaN or infinite.
    NonFinite,
    /// A finite coordinate does not fit the fixed-point type (32 bits with S fractional bits).
    OutOfRange,
    /// A polygon needs at least three vertices.
    TooFewVertices {
        /// How many vertices were given.
        found: usize,
    },
    /// A fixed-capacity buffer is too small for this input.
    CapacityExceeded {
        /// The capacity this input needs.
        needed: usize,
        /// The compiled capacity.
        capacity: usize,
    },
    /// The target is larger than [`MAX_VIEWPORT`](crate::MAX_VIEWPORT) in some direction.
    ViewportTooLarge {
        /// Width of the target in pixels.
        width: u32,
        /// Height of the target in pixels.
        height: u32,
    },
    /// The span sink or draw target failed.
    Target(T),
}

impl Error<Infallible> {
    /// Widens a geometry error to the error type of any target.
    pub fn widen<T>(self) -> Error<T> {
        match self {
            Error::NonFinite => Error::NonFinite,
            Error::OutOfRange => Error::OutOfRange,
            Error::TooFewVertices { found } => Error::TooFewVertices { found },
            Error::CapacityExceeded { needed, capacity } => {
                Error::CapacityExceeded { needed, capacity }
            }
            Error::ViewportTooLarge { width, height } => Error::ViewportTooLarge { width, height },
            Error::Target(never) => match never {},
        }
    }
}

impl<T: fmt::Debug> fmt::Display for Error<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NonFinite => f.write_str("coordinate is NaN or infinite"),
            Error::OutOfRange => f.write_str("coordinate does not fit the fixed-point type"),
            Error::TooFewVertices { found } => {
                write!(f, "polygon has {found} vertices, at least 3 are needed")
            }
            Error::CapacityExceeded { needed, capacity } => {
                write!(f, "capacity {capacity} exceeded: {needed} needed")
            }
            Error::ViewportTooLarge { width, height } => write!(
                f,
                "target of {width}x{height} pixels exceeds the {0}x{0} maximum",
                crate::MAX_VIEWPORT
            ),
            Error::Target(e) => write!(f, "draw target failed: {e:?}"),
        }
    }
}
