//! The OBJ converter of the firmware examples, used by `examples/embedded/build.rs`
//! (which turns a model into const arrays) and by the host test
//! `host_tests/tests/firmware/firmware_examples.rs` (which parses the same file at run time), so
//! both see the same `f32` bits.
//!
//! Parsing follows ../shared/CONVENTIONS.md "Meshes": `v x y z` and `f a b c ...`
//! (1-based, negative counts back from the last `v`, `a/b/c` takes the first number);
//! coordinates are read as `f64` and rounded to `f32`, as the `render` command does;
//! anything malformed is an error naming the line.

use std::collections::BTreeSet;
use std::prelude::rust_2021::*;
use std::{format, vec};

/// A mesh in the library's layout: positions, CSR face indices and offsets.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjMesh {
    pub vertices: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
    pub offsets: Vec<u32>,
}

impl ObjMesh {
    /// Unique edges after welding bit-identical positions: the size of the edge
    /// store that `EdgeAdjacency::build` needs.
    // Used by host_tests (firmware_examples.rs includes this file), not by build.rs.
    #[allow(dead_code)]
    pub fn unique_edges(&self) -> usize {
        let mut first = std::collections::BTreeMap::new();
        let weld: Vec<u32> = self
            .vertices
            .iter()
            .enumerate()
            .map(|(i, v)| *first.entry(v.map(f32::to_bits)).or_insert(i as u32))
            .collect();
        let mut edges = BTreeSet::new();
        for f in self.offsets.windows(2) {
            let face = &self.indices[f[0] as usize..f[1] as usize];
            for k in 0..face.len() {
                let a = weld[face[k] as usize];
                let b = weld[face[(k + 1) % face.len()] as usize];
                edges.insert((a.min(b), a.max(b)));
            }
        }
        edges.len()
    }
}

/// Parses OBJ text; errors name `name` and the line.
pub fn parse(text: &str, name: &str) -> Result<ObjMesh, String> {
    let mut m = ObjMesh {
        offsets: vec![0],
        ..ObjMesh::default()
    };
    for (n, line) in text.lines().enumerate() {
        let err = |what: &str| format!("{name}:{}: {what}", n + 1);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let mut p = [0f32; 3];
                for c in &mut p {
                    let x: f64 = words
                        .next()
                        .and_then(|w| w.parse().ok())
                        .ok_or_else(|| err("a vertex needs three numbers"))?;
                    if !x.is_finite() || !(x as f32).is_finite() {
                        return Err(err("non-finite coordinate"));
                    }
                    *c = x as f32;
                }
                m.vertices.push(p);
            }
            Some("f") => {
                let count = m.vertices.len() as i64;
                let mut k = 0;
                for w in words {
                    let i: i64 = w
                        .split('/')
                        .next()
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(|| err("bad face index"))?;
                    let i = if i < 0 { count + i } else { i - 1 };
                    if i < 0 || i >= count {
                        return Err(err("face index out of range"));
                    }
                    m.indices.push(i as u32);
                    k += 1;
                }
                if k < 3 {
                    return Err(err("a face needs three indices"));
                }
                m.offsets.push(m.indices.len() as u32);
            }
            _ => {}
        }
    }
    if m.offsets.len() < 2 {
        return Err(format!("{name}: no faces"));
    }
    Ok(m)
}
