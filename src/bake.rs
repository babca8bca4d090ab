//! A mesh baked for flash in one call of a `build.rs` (feature `std`): an OBJ file
//! in, a Rust source of `static`s out, with everything a frame needs that depends on
//! the mesh alone, so the firmware bakes nothing and sizes its buffers by the
//! generated constants.
//!
//! For a mesh named `PART`, [`obj_to_rust`] writes:
//! - `PART_V`, `PART_F`, `PART_E`, `PART_CORNERS`: vertices, faces, unique edges and
//!   face corners, for the const generics of a [`BakedDrawing`](crate::BakedDrawing)
//!   or the buffers of the long form;
//! - `PART_VERTICES`, `PART_INDICES`, `PART_OFFSETS`: the mesh (for [`Mesh::new`]);
//! - `PART_EDGE_LIST`: its edges at [`CREASE_DEG`] (for
//!   [`EdgeAdjacency::from_edges`]), as [`Drawing::bake`](crate::Drawing::bake)
//!   finds them;
//! - `PART_PLANAR`: which faces are planar (for [`Mesh::with_planar_faces`]);
//! - `PART_PLANES`, `PART_EDGES`: the fast engine's constants ([`BakedMesh::bake`],
//!   printed by [`BakedSource`]);
//! - `fn part_baked() -> Result<BakedMesh<'static>, pbuffer::Error>`: all of it
//!   checked once ([`BakedMesh::new`]), ready to draw.
//!
//! ```no_run
//! // build.rs, in `fn main`:
//! let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").unwrap());
//! pbuffer::bake::obj_to_rust("models/part.obj", "PART", out.join("part.rs"))
//!     .unwrap_or_else(|e| panic!("{e}"));
//! // src/main.rs: include!(concat!(env!("OUT_DIR"), "/part.rs"));
//! // and `BakedDrawing::<PART_V, PART_F, PART_E>::with_mesh(part_baked()?)`
//! ```

use core::fmt::{self, Write as _};
use std::path::Path;

use crate::mesh::{planar_words, EdgeAdjacency, HalfEdgeRecord, MeshEdge};
use crate::obj::{self, ObjError};
use crate::order::planar_faces;
use crate::render::{BakedMesh, BakedSource, CompactEdge, FacePlane};
use crate::{Error, Mesh, CREASE_DEG};

/// Why a bake failed. Displays as one line naming the file (and the line, for the
/// OBJ's own errors), fit for a build script's `panic!("{e}")`.
#[derive(Debug)]
pub enum BakeError {
    /// The OBJ file is unreadable or malformed.
    Obj(ObjError),
    /// The mesh is well-formed OBJ but the library rejects it (too many faces for the
    /// fast engine's 16-bit ids, for one).
    Mesh {
        /// The OBJ file.
        file: String,
        /// The library's reason.
        error: Error,
    },
    /// The name is not an upper-case Rust identifier (`A-Z`, `0-9`, `_`, starting
    /// with a letter).
    Name(String),
    /// The Rust source cannot be written.
    Write {
        /// The output file.
        file: String,
        /// The system's reason.
        why: String,
    },
}

impl fmt::Display for BakeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Obj(e) => write!(f, "{e}"),
            Self::Mesh { file, error } => write!(f, "{file}:-: the mesh is rejected: {error}"),
            Self::Name(name) => write!(
                f,
                "`{name}` is not an upper-case identifier (A-Z, 0-9, _, a letter first)"
            ),
            Self::Write { file, why } => write!(f, "{file}:-: cannot write: {why}"),
        }
    }
}

impl std::error::Error for BakeError {}

impl From<ObjError> for BakeError {
    fn from(e: ObjError) -> Self {
        Self::Obj(e)
    }
}

/// Reads the OBJ file `obj`, bakes it and writes the Rust source of the statics
/// named `NAME_...` (see the [module](self)) to `out`; prints
/// `cargo:rerun-if-changed` for `obj`, so the build script reruns when the model
/// changes. Returns the source written.
pub fn obj_to_rust(
    obj: impl AsRef<Path>,
    name: &str,
    out: impl AsRef<Path>,
) -> Result<String, BakeError> {
    let (obj, out) = (obj.as_ref(), out.as_ref());
    println!("cargo:rerun-if-changed={}", obj.display());
    let file = obj.display().to_string();
    let model = obj::read(obj)?;
    let mesh = model.mesh().map_err(|error| BakeError::Mesh {
        file: file.clone(),
        error,
    })?;
    let source = mesh_to_rust(&mesh, name, &file)?;
    std::fs::write(out, &source).map_err(|e| BakeError::Write {
        file: out.display().to_string(),
        why: e.to_string(),
    })?;
    Ok(source)
}

/// The Rust source of [`obj_to_rust`] for a mesh already in memory; `origin` names
/// where it came from (in the generated comment and in errors).
pub fn mesh_to_rust(mesh: &Mesh<'_>, name: &str, origin: &str) -> Result<String, BakeError> {
    let mut bytes = name.bytes();
    let upper = |b: u8| b.is_ascii_uppercase() || b.is_ascii_digit() || b == b'_';
    if !bytes.next().is_some_and(|b| b.is_ascii_uppercase()) || !bytes.all(upper) {
        return Err(BakeError::Name(name.to_string()));
    }
    let rejected = |error| BakeError::Mesh {
        file: origin.to_string(),
        error,
    };
    let corners = mesh.indices().len();
    let mut weld = vec![0u32; mesh.vertices().len()];
    let mut scratch = vec![HalfEdgeRecord::EMPTY; corners];
    let mut store = vec![MeshEdge::EMPTY; corners];
    let adjacency = EdgeAdjacency::build(mesh, CREASE_DEG, &mut weld, &mut scratch, &mut store)
        .map_err(rejected)?;
    let mut planar = vec![0u32; planar_words(mesh.face_count())];
    planar_faces(mesh, &mut planar).map_err(rejected)?;
    let mut planes = vec![FacePlane::default(); mesh.face_count()];
    let mut edges = vec![CompactEdge::EMPTY; adjacency.edges().len()];
    BakedMesh::bake(mesh, &adjacency, &mut planes, &mut edges).map_err(rejected)?;
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = write_source(&mut s, name, origin, mesh, adjacency.edges(), &planar);
    let _ = write!(
        s,
        "{}",
        BakedSource {
            name,
            planes: &planes,
            edges: &edges,
        }
    );
    Ok(s)
}

/// Everything but the fast engine's constants ([`BakedSource`] prints those).
fn write_source(
    s: &mut String,
    name: &str,
    origin: &str,
    mesh: &Mesh<'_>,
    edges: &[MeshEdge],
    planar: &[u32],
) -> fmt::Result {
    let (v, f, e) = (mesh.vertices().len(), mesh.face_count(), edges.len());
    let corners = mesh.indices().len();
    writeln!(
        s,
        "// Generated by pbuffer::bake from {origin}. Do not edit."
    )?;
    writeln!(
        s,
        "/// Vertices of the mesh.\npub const {name}_V: usize = {v};"
    )?;
    writeln!(
        s,
        "/// Faces of the mesh.\npub const {name}_F: usize = {f};"
    )?;
    writeln!(
        s,
        "/// Unique edges of the mesh (welded).\npub const {name}_E: usize = {e};"
    )?;
    writeln!(
        s,
        "/// Face corners.\npub const {name}_CORNERS: usize = {corners};"
    )?;
    // `{:?}` prints the shortest decimal that reads back to the same f32.
    writeln!(
        s,
        "/// Vertex positions.\npub static {name}_VERTICES: [[f32; 3]; {v}] = ["
    )?;
    for p in mesh.vertices() {
        writeln!(s, "    [{:?}, {:?}, {:?}],", p[0], p[1], p[2])?;
    }
    writeln!(s, "];")?;
    writeln!(
        s,
        "/// Face corners (CSR).\npub static {name}_INDICES: [u32; {corners}] = {:?};",
        mesh.indices()
    )?;
    writeln!(
        s,
        "/// Face offsets into `{name}_INDICES`.\npub static {name}_OFFSETS: [u32; {}] = {:?};",
        mesh.face_offsets().len(),
        mesh.face_offsets()
    )?;
    writeln!(
        s,
        "/// The edge list at 30 degrees, made on the host by `EdgeAdjacency::build`: in\n\
         /// flash, for `EdgeAdjacency::from_edges`.\n\
         pub static {name}_EDGE_LIST: [pbuffer::mesh::MeshEdge; {e}] = ["
    )?;
    for m in edges {
        writeln!(
            s,
            "    pbuffer::mesh::MeshEdge {{ a: {}, b: {}, faces: {:?}, face_count: {}, kind: pbuffer::mesh::EdgeKind::{:?} }},",
            m.a, m.b, m.faces, m.face_count, m.kind
        )?;
    }
    writeln!(s, "];")?;
    writeln!(
        s,
        "/// Which faces are planar (bit f % 32 of word f / 32), made on the host by\n\
         /// `pbuffer::order::planar_faces`: in flash, for `Mesh::with_planar_faces`.\n\
         pub static {name}_PLANAR: [u32; {}] = {:?};",
        planar.len(),
        planar
    )?;
    writeln!(
        s,
        "/// The mesh with its planarity bits and the fast engine's constants, checked\n\
         /// once (`BakedMesh::new`): what `BakedDrawing::new` takes.\n\
         pub fn {lower}_baked() -> Result<pbuffer::render::BakedMesh<'static>, pbuffer::Error> {{\n\
         \x20   pbuffer::Mesh::new(&{name}_VERTICES, &{name}_INDICES, &{name}_OFFSETS)\n\
         \x20       .and_then(|mesh| mesh.with_planar_faces(&{name}_PLANAR))\n\
         \x20       .and_then(|mesh| pbuffer::render::BakedMesh::new(mesh, &{name}_PLANES, &{name}_EDGES))\n\
         }}",
        lower = name.to_ascii_lowercase()
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const CUBE: &str = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n\
        v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
        f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n";

    #[test]
    fn a_cube_becomes_statics_and_sizes() {
        let model = obj::parse(CUBE, "cube.obj").unwrap();
        let s = mesh_to_rust(&model.mesh().unwrap(), "CUBE", "cube.obj").unwrap();
        for line in [
            "pub const CUBE_V: usize = 8;",
            "pub const CUBE_F: usize = 6;",
            "pub const CUBE_E: usize = 12;",
            "pub const CUBE_CORNERS: usize = 24;",
            "pub static CUBE_PLANAR: [u32; 1] = [63];",
            "pub static CUBE_PLANES: [pbuffer::render::FacePlane; 6] = [",
            "pub static CUBE_EDGES: [pbuffer::render::CompactEdge; 12] = [",
            "pub fn cube_baked() -> Result<pbuffer::render::BakedMesh<'static>, pbuffer::Error> {",
        ] {
            assert!(s.lines().any(|l| l == line), "{line} missing in\n{s}");
        }
    }

    #[test]
    fn errors_name_the_file() {
        let model = obj::parse(CUBE, "cube.obj").unwrap();
        let mesh = model.mesh().unwrap();
        for bad in ["cube", "1CUBE", "", "CU-BE"] {
            assert!(matches!(
                mesh_to_rust(&mesh, bad, "x"),
                Err(BakeError::Name(_))
            ));
        }
        let dir = std::env::temp_dir().join(format!("pbuffer-bake-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let obj = dir.join("bad.obj");
        std::fs::write(&obj, "v 0 0 0\nf 1 1 x\n").unwrap();
        let e = obj_to_rust(&obj, "BAD", dir.join("bad.rs")).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "{}:2: `x` is not a vertex reference (v, v/t, v//n or v/t/n)",
                obj.display()
            )
        );
        let good = dir.join("cube.obj");
        std::fs::write(&good, CUBE).unwrap();
        let e = obj_to_rust(&good, "CUBE", dir.join("no/such/dir/cube.rs")).unwrap_err();
        assert!(e.to_string().contains("cube.rs:-: cannot write"), "{e}");
        std::fs::remove_dir_all(dir).ok();
    }
}
