//! Unit tests of the BSP tree (core only: no std here).

mod build;
mod fans;
mod rank;
mod rays;
mod scenes;
mod seams;

use super::*;
use crate::mesh::{Mesh, Viewpoint};
use crate::Error;
use rays::{check_grid, cross, ranks};
use scenes::sticks;

/// Storage big enough for the small scenes here.
struct Store {
    vertices: [[f32; 3]; 256],
    indices: [u32; 2048],
    offsets: [u32; 512],
    source: [u16; 512],
    nodes: [BspNode; 512],
    seams: [[u32; 2]; 256],
    work: [u32; 8192],
}

impl Store {
    fn new() -> Self {
        Self {
            vertices: [[0.0; 3]; 256],
            indices: [0; 2048],
            offsets: [0; 512],
            source: [0; 512],
            nodes: [BspNode::EMPTY; 512],
            seams: [[0; 2]; 256],
            work: [0; 8192],
        }
    }

    fn storage(&mut self) -> BspStorage<'_> {
        BspStorage {
            vertices: &mut self.vertices,
            indices: &mut self.indices,
            offsets: &mut self.offsets,
            source: &mut self.source,
            nodes: &mut self.nodes,
            seams: &mut self.seams,
            work: &mut self.work,
        }
    }
}
