//! What is wrong with an OBJ file, and where.

use core::fmt;

/// An OBJ file rejected: the file's name, the line (`None` for a problem of the whole
/// file) and what is wrong. Displays as one line, `FILE:LINE: problem` or
/// `FILE:-: problem`, fit for a build script's panic or a command's error.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjError {
    /// The file's name as the caller gave it.
    pub file: String,
    /// The 1-based line, or `None` for the whole file.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: ObjProblem,
}

/// What is wrong in an OBJ file. Tokens are quoted as written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ObjProblem {
    /// The file cannot be read (the system's reason).
    Unreadable(String),
    /// A token of a `v` line is not a number.
    NotANumber(String),
    /// A number of a `v` line is NaN or infinite.
    NotFinite(String),
    /// A coordinate is finite as `f64` but overflows `f32`.
    OutOfF32Range(String),
    /// A `v` line with fewer than 3 numbers (how many it has).
    TooFewNumbers(usize),
    /// A seventh number in a `v` line.
    TooManyNumbers(String),
    /// A token of an `f` line is not `v`, `v/t`, `v//n` or `v/t/n`.
    NotAReference(String),
    /// A vertex index 0 (indices start at 1).
    IndexZero,
    /// A negative index reaching before the first vertex (`known` read so far).
    NegativeOutOfRange {
        /// The index as written.
        index: i64,
        /// Vertices read before the line.
        known: u64,
    },
    /// A positive index beyond the file's vertices.
    IndexOutOfRange {
        /// The 1-based index as written.
        index: u64,
        /// Vertices in the file.
        vertices: u64,
    },
    /// An index that does not fit 32 bits.
    IndexTooLarge(i64),
    /// A face with fewer than 3 vertices (how many it has).
    ShortFace(usize),
    /// More face corners than 32-bit offsets can name.
    TooManyCorners,
    /// No `f` line in the file.
    NoFaces,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.file, self.problem),
            None => write!(f, "{}:-: {}", self.file, self.problem),
        }
    }
}

impl std::error::Error for ObjError {}

impl fmt::Display for ObjProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const FORMS: &str = "(v, v/t, v//n or v/t/n)";
        match self {
            Self::Unreadable(why) => write!(f, "cannot read the file: {why}"),
            Self::NotANumber(tok) => write!(f, "`{tok}` is not a number in a `v` line"),
            Self::NotFinite(tok) => write!(f, "`{tok}` is not a finite number in a `v` line"),
            Self::OutOfF32Range(tok) => {
                write!(f, "`{tok}` is out of the f32 range in a `v` line")
            }
            Self::TooFewNumbers(n) => {
                write!(f, "a `v` line needs 3 numbers (x y z), found {n}")
            }
            Self::TooManyNumbers(tok) => write!(
                f,
                "a `v` line has at most 6 numbers (x y z, then w or r g b), found `{tok}` as the 7th"
            ),
            Self::NotAReference(tok) => write!(f, "`{tok}` is not a vertex reference {FORMS}"),
            Self::IndexZero => write!(f, "vertex index 0 (indices start at 1)"),
            Self::NegativeOutOfRange { index, known } => write!(
                f,
                "vertex index {index} out of range ({known} vertices read before this line)"
            ),
            Self::IndexOutOfRange { index, vertices } => write!(
                f,
                "vertex index {index} out of range (the file has {vertices} vertices)"
            ),
            Self::IndexTooLarge(index) => write!(
                f,
                "vertex index {index} out of range (more than 2^32 vertices)"
            ),
            Self::ShortFace(n) => write!(f, "a face needs at least 3 vertices, found {n}"),
            Self::TooManyCorners => write!(f, "more than 2^32 face corners"),
            Self::NoFaces => write!(f, "no faces (no `f` lines)"),
        }
    }
}
