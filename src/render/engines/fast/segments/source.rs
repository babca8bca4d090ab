//! The per-mesh tables of hidden lines by the segment printed as Rust source.

use core::fmt;

use super::{Piercing, VertexFaces};

/// [`VertexFaces`] and [`Piercing`] pairs printed as Rust source: `pub static
/// {NAME}_WELD`, `{NAME}_AROUND_STARTS`, `{NAME}_AROUND_FACES` and
/// `{NAME}_PIERCINGS`, for a `build.rs` to write into `OUT_DIR`.
#[derive(Debug, Clone, Copy)]
pub struct SegmentSource<'a> {
    /// Prefix of the statics' names.
    pub name: &'a str,
    /// What [`VertexFaces::bake`] wrote.
    pub vertex_faces: VertexFaces<'a>,
    /// What [`Piercing::bake`] wrote.
    pub piercings: &'a [Piercing],
}

fn list(
    out: &mut fmt::Formatter<'_>,
    doc: &str,
    (name, what): (&str, &str),
    items: &[u16],
) -> fmt::Result {
    writeln!(out, "/// {doc}")?;
    writeln!(out, "pub static {name}_{what}: [u16; {}] = [", items.len())?;
    for row in items.chunks(16) {
        write!(out, "   ")?;
        for v in row {
            write!(out, " {v},")?;
        }
        writeln!(out)?;
    }
    writeln!(out, "];")
}

impl fmt::Display for SegmentSource<'_> {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = self.name;
        let v = self.vertex_faces;
        list(
            out,
            "Each vertex's welded id, baked on the host by `VertexFaces::bake`.",
            (name, "WELD"),
            v.weld,
        )?;
        list(
            out,
            "Where each welded vertex's faces start, baked by `VertexFaces::bake`.",
            (name, "AROUND_STARTS"),
            v.starts,
        )?;
        list(
            out,
            "The faces around each welded vertex, baked by `VertexFaces::bake`.",
            (name, "AROUND_FACES"),
            v.faces,
        )?;
        writeln!(
            out,
            "/// The irregular vertices' bits, baked by `VertexFaces::bake`."
        )?;
        writeln!(
            out,
            "pub static {name}_IRREGULAR: [u32; {}] = {:?};",
            v.irregular.len(),
            v.irregular
        )?;
        writeln!(
            out,
            "/// The (edge, triangle) pairs that may meet, baked by `Piercing::bake`."
        )?;
        writeln!(
            out,
            "pub static {name}_PIERCINGS: [pbuffer::render::Piercing; {}] = [",
            self.piercings.len()
        )?;
        for p in self.piercings {
            writeln!(
                out,
                "    pbuffer::render::Piercing {{ edge: {}, face: {}, fan: {} }},",
                p.edge, p.face, p.fan
            )?;
        }
        writeln!(out, "];")?;
        writeln!(
            out,
            "/// The faces around each vertex as hidden lines by the segment read them."
        )?;
        writeln!(
            out,
            "pub const {name}_VERTEX_FACES: pbuffer::render::VertexFaces<'static> = \
             pbuffer::render::VertexFaces {{ weld: &{name}_WELD, starts: &{name}_AROUND_STARTS, \
             faces: &{name}_AROUND_FACES, irregular: &{name}_IRREGULAR }};"
        )
    }
}
