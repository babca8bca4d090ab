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
//! - `PART_FACETS`, `PART_LINES`: the facets and feature lines active on one row
//!   at most over the bake's views ([`BakeOptions`]: by default 24 directions
//!   around the vertical axis at [`Camera::fit`]'s elevation, each fitted to a
//!   400 x 240 frame, with the default settings), for the `FACETS` and `LINES` of
//!   a [`BakedDrawing`](crate::BakedDrawing). They hold for those views only:
//!   another view, size or setting may need more, and then the draw's error
//!   names the need ([`Error::CapacitiesExceeded`]);
//! - `fn part_baked() -> Result<BakedMesh<'static>, pbuffer::Error>`: all of it
//!   checked once ([`BakedMesh::new`]), ready to draw.
//!
//! ```no_run
//! // build.rs, in `fn main`:
//! let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").unwrap());
//! pbuffer::bake::obj_to_rust("models/part.obj", "PART", out.join("part.rs"))
//!     .unwrap_or_else(|e| panic!("{e}"));
//! // src/main.rs: include!(concat!(env!("OUT_DIR"), "/part.rs"));
//! // and `BakedDrawing::<PART_V, PART_F, PART_E, PART_FACETS, PART_LINES>`
//! // `::with_mesh(part_baked()?)`
//! ```

use core::fmt::{self, Write as _};
use std::path::Path;

use crate::drawing::{FrameBuffers, DEFAULT_SETTINGS};
use crate::mesh::{planar_words, EdgeAdjacency, HalfEdgeRecord, MeshEdge};
use crate::obj::{self, ObjError};
use crate::order::planar_faces;
use crate::render::{
    BakedMesh, BakedSource, CompactEdge, FacePlane, FastRenderer, FastVertex, FastWorkspace,
    FrameNeeds, Piercing, SegmentSource, VertexFaces,
};
use crate::subpixel::U4;
use crate::{
    Camera, DrawingNeeds, Error, Mesh, Viewport, CLIPPED_CORNERS, CREASE_DEG, FIT_FOV_DEG,
    FIT_VIEW_DIRECTION,
};

/// The views the bake sizes `NAME_FACETS` and `NAME_LINES` for: `views`
/// directions around the vertical axis, the first [`FIT_VIEW_DIRECTION`] (the
/// view of [`Camera::fit`]) and the others turned from it by equal steps at the
/// same elevation, each [`Camera::fit_along`] the mesh in a `width` x `height`
/// frame, drawn with the default [`Settings`](crate::Settings) (dashed hidden
/// lines, as a [`BakedDrawing`](crate::BakedDrawing) draws).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BakeOptions {
    /// Frame width, pixels (default 400).
    pub width: u16,
    /// Frame height, pixels (default 240).
    pub height: u16,
    /// Directions around the vertical axis (default 24; 0 is taken as 1).
    pub views: u16,
}

impl Default for BakeOptions {
    fn default() -> Self {
        Self {
            width: 400,
            height: 240,
            views: 24,
        }
    }
}

impl BakeOptions {
    /// The cameras of these views of `mesh` (see [`BakeOptions`]).
    pub fn cameras(&self, mesh: &Mesh<'_>) -> Result<Vec<Camera>, Error> {
        let n = self.views.max(1);
        let [x, y, z] = FIT_VIEW_DIRECTION;
        (0..n)
            .map(|k| {
                let turn = core::f32::consts::TAU * f32::from(k) / f32::from(n);
                let (sin, cos) = turn.sin_cos();
                let direction = [x * cos + z * sin, y, z * cos - x * sin];
                let (w, h) = (u32::from(self.width), u32::from(self.height));
                Camera::fit_along(mesh, w, h, direction, FIT_FOV_DEG)
            })
            .collect()
    }

    /// Every size a [`BakedDrawing`](crate::BakedDrawing) (or a
    /// [`Drawing`](crate::Drawing)) and its [`FrameRows`](crate::FrameRows) need
    /// to draw `baked` in these views, as [`Drawing::measure`](crate::Drawing::measure)
    /// counts them, with buffers of any size made here.
    pub fn needs(&self, baked: &BakedMesh<'_>) -> Result<DrawingNeeds, Error> {
        let viewport = Viewport {
            width: self.width,
            height: self.height,
        };
        let mesh = baked.mesh();
        let (v, f, e) = (
            mesh.vertices().len(),
            mesh.face_count(),
            baked.edges().len(),
        );
        let (w, h) = (usize::from(self.width), usize::from(self.height));
        let mut vertices = vec![FastVertex::ZERO; v];
        let mut facing = vec![0u32; f.div_ceil(32)];
        let (mut face_links, mut slopes) = (vec![0u16; f], vec![0u16; f]);
        let mut line_links = vec![0u16; e];
        let mut heads = vec![0u16; 2 * h];
        let mut row = vec![0u32; w];
        let mut masks = vec![0u32; 3 * w.div_ceil(32)];
        let mut pool = vec![FastVertex::ZERO; CLIPPED_CORNERS];
        let mut ws = FastWorkspace {
            vertices: &mut vertices,
            facing: &mut facing,
            face_links: &mut face_links,
            line_links: &mut line_links,
            heads: &mut heads,
            row: &mut row,
            masks: &mut masks,
            pool: &mut pool,
            ids: &mut [],
            slopes: &mut slopes,
            phases: &mut [],
            segments: None,
        };
        let engine = FastRenderer::<U4, 0, 0>::new();
        let mut frames = FrameNeeds::default();
        for camera in self.cameras(mesh)? {
            let one = engine.needs(baked, &camera, &DEFAULT_SETTINGS, &mut ws, viewport)?;
            frames = frames.max(one);
        }
        Ok(FrameBuffers::<0, 0, 0, 0, 0>::sizes(
            baked, frames, viewport,
        ))
    }
}

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
/// named `NAME_...` (see the [module](self)) to `out`, with `NAME_FACETS` and
/// `NAME_LINES` for the default [`BakeOptions`] (400 x 240, 24 views); prints
/// `cargo:rerun-if-changed` for `obj`, so the build script reruns when the model
/// changes. Returns the source written.
pub fn obj_to_rust(
    obj: impl AsRef<Path>,
    name: &str,
    out: impl AsRef<Path>,
) -> Result<String, BakeError> {
    obj_to_rust_with(obj, name, out, &BakeOptions::default())
}

/// [`obj_to_rust`] with `NAME_FACETS` and `NAME_LINES` sized for the views of
/// `options` (the display's size, say).
pub fn obj_to_rust_with(
    obj: impl AsRef<Path>,
    name: &str,
    out: impl AsRef<Path>,
    options: &BakeOptions,
) -> Result<String, BakeError> {
    let (obj, out) = (obj.as_ref(), out.as_ref());
    println!("cargo:rerun-if-changed={}", obj.display());
    let file = obj.display().to_string();
    let model = obj::read(obj)?;
    let mesh = model.mesh().map_err(|error| BakeError::Mesh {
        file: file.clone(),
        error,
    })?;
    let source = mesh_to_rust_with(&mesh, name, &file, options)?;
    std::fs::write(out, &source).map_err(|e| BakeError::Write {
        file: out.display().to_string(),
        why: e.to_string(),
    })?;
    Ok(source)
}

/// The Rust source of [`obj_to_rust`] for a mesh already in memory; `origin` names
/// where it came from (in the generated comment and in errors).
pub fn mesh_to_rust(mesh: &Mesh<'_>, name: &str, origin: &str) -> Result<String, BakeError> {
    mesh_to_rust_with(mesh, name, origin, &BakeOptions::default())
}

/// [`mesh_to_rust`] with `NAME_FACETS` and `NAME_LINES` sized for the views of
/// `options`.
pub fn mesh_to_rust_with(
    mesh: &Mesh<'_>,
    name: &str,
    origin: &str,
    options: &BakeOptions,
) -> Result<String, BakeError> {
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
    // Sized as `NAME_baked()` draws: with the planarity bits.
    let drawn = mesh.with_planar_faces(&planar).map_err(rejected)?;
    let baked = BakedMesh::new(drawn, &planes, &edges).map_err(rejected)?;
    let needs = options.needs(&baked).map_err(rejected)?;
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = write_source(&mut s, name, origin, mesh, adjacency.edges(), &planar);
    let _ = write_peaks(&mut s, name, &needs, options);
    let _ = write!(
        s,
        "{}",
        BakedSource {
            name,
            planes: &planes,
            edges: &edges,
        }
    );
    let v = mesh.vertices().len();
    let (mut weld, mut starts, mut around) =
        (vec![0u16; v], vec![0u16; v + 1], vec![0u16; corners]);
    let mut irregular = vec![0u32; v.div_ceil(32)];
    let vertex_faces = VertexFaces::bake(mesh, &mut weld, &mut starts, &mut around, &mut irregular)
        .map_err(rejected)?;
    let mut pairs = vec![Piercing::default(); edges.len() * 4 + 16];
    let n = loop {
        match Piercing::bake(mesh, &edges, &mut pairs) {
            Ok(n) => break n,
            Err(Error::CapacityExceeded { needed, .. }) => {
                pairs.resize(needed, Piercing::default());
            }
            Err(e) => return Err(rejected(e)),
        }
    };
    let _ = write!(
        s,
        "{}",
        SegmentSource {
            name,
            vertex_faces,
            piercings: pairs.get(..n).unwrap_or_default(),
        }
    );
    Ok(s)
}

/// `NAME_FACETS` and `NAME_LINES`, with the views they hold for.
fn write_peaks(
    s: &mut String,
    name: &str,
    needs: &DrawingNeeds,
    options: &BakeOptions,
) -> fmt::Result {
    let views = format!(
        "over {} views turned about the vertical axis at `Camera::fit`'s elevation,\n\
         /// each fitted to a {} x {} frame (`pbuffer::bake::BakeOptions`), default settings.\n\
         /// Other views or sizes may need more: then the draw's error names the need.",
        options.views.max(1),
        options.width,
        options.height
    );
    writeln!(
        s,
        "/// Facets active on one row at most (`FACETS`), {views}\n\
         pub const {name}_FACETS: usize = {};",
        needs.facets
    )?;
    writeln!(
        s,
        "/// Feature lines active on one row at most (`LINES`), {views}\n\
         pub const {name}_LINES: usize = {};",
        needs.lines
    )
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
    fn facets_and_lines_are_the_peaks_over_the_stated_views() {
        let model = obj::parse(CUBE, "cube.obj").unwrap();
        let mesh = model.mesh().unwrap();
        let views = BakeOptions {
            width: 128,
            height: 64,
            views: 8,
        };
        let s = mesh_to_rust_with(&mesh, "CUBE", "cube.obj", &views).unwrap();
        // What a drawing measures over the same cameras.
        let mut drawing = crate::Drawing::<8, 6, 12>::new();
        drawing.bake(mesh).unwrap();
        let cameras = views.cameras(&mesh).unwrap();
        assert_eq!(cameras.len(), 8);
        let viewport = Viewport::new(128, 64).unwrap();
        let mut rows = crate::FrameRows::<128, 64>::new();
        let needs = drawing.measure(&cameras, &mut rows, viewport).unwrap();
        for line in [
            format!("pub const CUBE_FACETS: usize = {};", needs.facets),
            format!("pub const CUBE_LINES: usize = {};", needs.lines),
            "/// each fitted to a 128 x 64 frame (`pbuffer::bake::BakeOptions`), default settings."
                .to_string(),
        ] {
            assert!(s.lines().any(|l| l == line), "{line} missing in\n{s}");
        }
        assert!(needs.facets > 0 && needs.lines > 0);
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
