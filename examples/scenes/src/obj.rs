//! The OBJ converter of the firmware examples: the library's reader
//! (`pbuffer::obj`, feature `std`), so the firmware's build.rs (through
//! `pbuffer::bake`), the host test `host_tests/tests/firmware/firmware_examples.rs`
//! and the `render` command see the same `f32` bits.

use std::collections::{BTreeMap, BTreeSet};
use std::prelude::rust_2021::*;
use std::string::ToString;

pub use pbuffer::obj::ObjMesh;

/// Parses OBJ text; errors name `name` and the line.
pub fn parse(text: &str, name: &str) -> Result<ObjMesh, String> {
    pbuffer::obj::parse(text, name).map_err(|e| e.to_string())
}

/// Unique edges after welding bit-identical positions, counted here with sets (not
/// with the library's `EdgeAdjacency`, which the host test checks it against): the
/// size of the edge store that `EdgeAdjacency::build` needs.
pub fn unique_edges(mesh: &ObjMesh) -> usize {
    let mut first = BTreeMap::new();
    let weld: Vec<u32> = mesh
        .vertices
        .iter()
        .enumerate()
        .map(|(i, v)| *first.entry(v.map(f32::to_bits)).or_insert(i as u32))
        .collect();
    let mut edges = BTreeSet::new();
    for face in mesh.faces() {
        for k in 0..face.len() {
            let a = weld[face[k] as usize];
            let b = weld[face[(k + 1) % face.len()] as usize];
            edges.insert((a.min(b), a.max(b)));
        }
    }
    edges.len()
}
