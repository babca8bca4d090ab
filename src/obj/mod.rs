//! Wavefront OBJ files read into the library's mesh layout (feature `std`), following
//! [conventions](crate::conventions) "Meshes".
//!
//! Only two statements carry geometry:
//!
//! * `v x y z`: a vertex. The three coordinates must be finite numbers (Rust `f64`
//!   syntax: `1`, `-0.5`, `1e-3`; `nan`, `inf` and values that overflow are rejected).
//!   Up to three more numbers may follow and are ignored: the optional weight `w` of
//!   the OBJ specification, or the per-vertex colour `r g b` that `MeshLab` and others
//!   write. They must be finite numbers too; a seventh number or any non-number is an
//!   error.
//! * `f a b c ...`: a face of three or more vertex references. Each reference is `a`,
//!   `a/t`, `a//n` or `a/t/n`; only the first number (the vertex) is used, the others
//!   must be empty or integers. A positive index is 1-based and may name any vertex of
//!   the file (forward references are checked at the end of the file); a negative
//!   index counts back from the last `v` read before this line (`-1` is that vertex).
//!   Index 0, or an index that names no vertex, is an error.
//!
//! Faces are kept as written (no triangulation); face index = 0-based position of the
//! `f` line. Every other statement (`vn`, `vt`, `o`, `g`, `s`, `l`, `usemtl`, ...) is
//! ignored, as are blank lines and comments (`#` to the end of a line). Keywords are
//! case-sensitive. Invalid UTF-8 is replaced by U+FFFD ([`read`]), so it is only an
//! error inside a `v` or `f` line. A file without faces is an error.
//!
//! Every error is an [`ObjError`] that displays as one line, `FILE:LINE: what is wrong`
//! (`FILE:-: ...` for the whole file); nothing here panics.
//!
//! ```
//! let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\
//!             f 1 3 2\nf 1 2 4\nf 2 3 4\nf -4 -1 -2 # the fourth face, from the end\n";
//! let tetra = pbuffer::obj::parse(text, "tetra.obj")?;
//! assert_eq!((tetra.vertices.len(), tetra.face_count()), (4, 4));
//! assert_eq!(&tetra.indices[9..], &[0, 3, 2]);
//! let mesh = tetra.mesh().map_err(|e| e.to_string())?; // a `pbuffer::Mesh` borrowing `tetra`
//! assert_eq!(mesh.face_count(), 4);
//!
//! let bad = pbuffer::obj::parse("v 0 0 0\nv 1 nan 0\n", "bad.obj").unwrap_err();
//! assert_eq!(bad.to_string(), "bad.obj:2: `nan` is not a finite number in a `v` line");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod error;
#[cfg(test)]
mod tests;

pub use error::{ObjError, ObjProblem};

use std::path::Path;

use crate::{Error, Mesh};

/// An OBJ mesh in the library's layout, owned: positions, the vertex indices of every
/// face one after the other (0-based) and where each face starts (CSR, as
/// [`Mesh::new`] takes them). `T` is `f32` ([`parse`], [`read`]) or `f64`
/// ([`parse_f64`], [`read_f64`], for a reference that keeps the digits).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjMesh<T = f32> {
    /// Vertex positions, in the order of the `v` lines.
    pub vertices: Vec<[T; 3]>,
    /// Face corners: 0-based vertex indices, face after face.
    pub indices: Vec<u32>,
    /// Face `f` is `indices[offsets[f]..offsets[f + 1]]`; starts with 0.
    pub offsets: Vec<u32>,
}

impl<T> ObjMesh<T> {
    /// Number of faces (`f` lines).
    pub fn face_count(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The faces' vertex indices, face after face.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.offsets.windows(2).map(|w| match w {
            [a, b] => self.indices.get(*a as usize..*b as usize).unwrap_or(&[]),
            _ => &[],
        })
    }
}

impl ObjMesh<f32> {
    /// The validated [`Mesh`] borrowing these arrays: the errors of [`Mesh::new`]
    /// (the reader's checks leave only `TooManyFaces`).
    pub fn mesh(&self) -> Result<Mesh<'_>, Error> {
        Mesh::new(&self.vertices, &self.indices, &self.offsets)
    }
}

/// Parses OBJ text into `f32` positions (each coordinate read as `f64`, then rounded;
/// one that overflows `f32` is an error). `file` names the text in errors only.
pub fn parse(text: &str, file: &str) -> Result<ObjMesh<f32>, ObjError> {
    parse_as(text, file, |x, tok| {
        let y = x as f32;
        if y.is_finite() {
            Ok(y)
        } else {
            Err(ObjProblem::OutOfF32Range(tok.to_string()))
        }
    })
}

/// Parses OBJ text into `f64` positions, the numbers as written.
pub fn parse_f64(text: &str, file: &str) -> Result<ObjMesh<f64>, ObjError> {
    parse_as(text, file, |x, _| Ok(x))
}

/// Reads and parses an OBJ file into `f32` positions ([`parse`]); errors name `path`
/// as given.
pub fn read(path: impl AsRef<Path>) -> Result<ObjMesh<f32>, ObjError> {
    let (text, file) = read_text(path.as_ref())?;
    parse(&text, &file)
}

/// Reads and parses an OBJ file into `f64` positions ([`parse_f64`]).
pub fn read_f64(path: impl AsRef<Path>) -> Result<ObjMesh<f64>, ObjError> {
    let (text, file) = read_text(path.as_ref())?;
    parse_f64(&text, &file)
}

/// The file's text (invalid UTF-8 replaced) and its name for errors.
fn read_text(path: &Path) -> Result<(String, String), ObjError> {
    let file = path.display().to_string();
    match std::fs::read(path) {
        Ok(bytes) => Ok((String::from_utf8_lossy(&bytes).into_owned(), file)),
        Err(e) => Err(ObjError {
            file,
            line: None,
            problem: ObjProblem::Unreadable(e.to_string()),
        }),
    }
}

/// A face whose largest positive index is checked once the whole file is read.
struct Pending {
    line: usize,
    max_positive: u64,
}

/// The parser, with `coordinate` turning a finite `f64` (and its token) into `T`.
fn parse_as<T: Copy + Default>(
    text: &str,
    file: &str,
    coordinate: impl Fn(f64, &str) -> Result<T, ObjProblem>,
) -> Result<ObjMesh<T>, ObjError> {
    let mut mesh = ObjMesh {
        vertices: Vec::new(),
        indices: Vec::new(),
        offsets: std::vec![0],
    };
    let mut pending: Vec<Pending> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let at = |problem| ObjError {
            file: file.to_string(),
            line: Some(line),
            problem,
        };
        let content = raw.split('#').next().unwrap_or("");
        let mut tokens = content.split_whitespace();
        match tokens.next() {
            Some("v") => {
                let v = parse_vertex(tokens, &coordinate).map_err(at)?;
                mesh.vertices.push(v);
            }
            Some("f") => {
                let known = mesh.vertices.len() as u64;
                let max_positive = parse_face(tokens, known, &mut mesh.indices).map_err(at)?;
                if max_positive > known {
                    pending.push(Pending { line, max_positive });
                }
                let end = u32::try_from(mesh.indices.len())
                    .map_err(|_| at(ObjProblem::TooManyCorners))?;
                mesh.offsets.push(end);
            }
            _ => {}
        }
    }
    let whole = |line, problem| ObjError {
        file: file.to_string(),
        line,
        problem,
    };
    let vertices = mesh.vertices.len() as u64;
    if let Some(p) = pending.iter().find(|p| p.max_positive > vertices) {
        let problem = ObjProblem::IndexOutOfRange {
            index: p.max_positive,
            vertices,
        };
        return Err(whole(Some(p.line), problem));
    }
    if mesh.face_count() == 0 {
        return Err(whole(None, ObjProblem::NoFaces));
    }
    Ok(mesh)
}

/// The numbers of a `v` line: x y z, then at most three ignored ones.
fn parse_vertex<'a, T: Copy + Default>(
    tokens: impl Iterator<Item = &'a str>,
    coordinate: impl Fn(f64, &str) -> Result<T, ObjProblem>,
) -> Result<[T; 3], ObjProblem> {
    let mut xyz = [T::default(); 3];
    let mut n = 0usize;
    for tok in tokens {
        let x: f64 = tok
            .parse()
            .map_err(|_| ObjProblem::NotANumber(tok.to_string()))?;
        if !x.is_finite() {
            return Err(ObjProblem::NotFinite(tok.to_string()));
        }
        if let Some(slot) = xyz.get_mut(n) {
            *slot = coordinate(x, tok)?;
        } else if n >= 6 {
            return Err(ObjProblem::TooManyNumbers(tok.to_string()));
        }
        n += 1;
    }
    if n < 3 {
        return Err(ObjProblem::TooFewNumbers(n));
    }
    Ok(xyz)
}

/// Appends the 0-based indices of an `f` line's references to `indices`; `known` =
/// vertices read so far. Returns the largest positive 1-based index (0 if none), for
/// the end-of-file check.
fn parse_face<'a>(
    tokens: impl Iterator<Item = &'a str>,
    known: u64,
    indices: &mut Vec<u32>,
) -> Result<u64, ObjProblem> {
    let mut max_positive = 0u64;
    let mut corners = 0usize;
    for tok in tokens {
        let not_a_reference = || ObjProblem::NotAReference(tok.to_string());
        let mut parts = tok.split('/');
        let first = parts.next().unwrap_or("");
        let mut others = 0;
        for part in parts {
            others += 1;
            if others > 2 || !part.is_empty() && part.parse::<i64>().is_err() {
                return Err(not_a_reference());
            }
        }
        let index: i64 = first.parse().map_err(|_| not_a_reference())?;
        let zero_based = match index {
            0 => return Err(ObjProblem::IndexZero),
            1.. => {
                let k = index.unsigned_abs();
                max_positive = max_positive.max(k);
                k - 1
            }
            _ => {
                let back = index.unsigned_abs();
                if back > known {
                    return Err(ObjProblem::NegativeOutOfRange { index, known });
                }
                known - back
            }
        };
        let i = u32::try_from(zero_based).map_err(|_| ObjProblem::IndexTooLarge(index))?;
        indices.push(i);
        corners += 1;
    }
    if corners < 3 {
        return Err(ObjProblem::ShortFace(corners));
    }
    Ok(max_positive)
}
