//! Baseline (i): the embedded-graphics painter's algorithm. Per frame: vertices to
//! screen in `f32`, back faces culled, the rest sorted far to near by mean distance,
//! each face filled with the background colour as fan `Triangle`s and its outline
//! stroked with the line colour (`Line`s, so quads show no diagonal). Hidden lines
//! are simply painted over: no dashes. Faces not wholly within near..far are skipped.
//! Shared with the host test through this crate.

use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Line, PrimitiveStyle, Triangle};
use pbuffer::mesh::Mesh;

use crate::plain::{facing, floor_i, newell, Cam, V3};
use crate::scenes::View;

/// Per-frame storage: `V` vertices, `F` faces. Zero-initialised.
#[derive(Debug)]
pub struct PainterBuffers<const V: usize, const F: usize> {
    pub screen: [(Point, f32); V],
    pub order: [(f32, u16); F],
    pub normals: [V3; F],
}

impl<const V: usize, const F: usize> PainterBuffers<V, F> {
    pub const fn new() -> Self {
        Self {
            screen: [(Point::zero(), 0.0); V],
            order: [(0.0, 0); F],
            normals: [[0.0; 3]; F],
        }
    }

    /// Once per mesh: the Newell normals.
    pub fn prepare(&mut self, mesh: &Mesh<'_>) {
        for (f, n) in self.normals.iter_mut().enumerate().take(mesh.face_count()) {
            *n = newell(mesh, f);
        }
    }

    /// Draws one frame into `target` (cleared by the caller).
    pub fn render<T: DrawTarget<Color = BinaryColor>>(
        &mut self,
        mesh: &Mesh<'_>,
        view: &View,
        target: &mut T,
    ) -> Result<(), T::Error> {
        let size = target.bounding_box().size;
        let cam = Cam::new(view, size.width as usize, size.height as usize);
        for (s, &p) in self.screen.iter_mut().zip(mesh.vertices()) {
            let e = cam.eye_space(p);
            let q = if e[2] > 0.0 { cam.project(e) } else { [0.0; 3] };
            *s = (Point::new(floor_i(q[0]), floor_i(q[1])), e[2]);
        }
        let mut n = 0;
        for f in 0..mesh.face_count() {
            if !facing(mesh, f, self.normals[f], cam.eye) {
                continue;
            }
            let face = mesh.face(f);
            let mut z = 0.0;
            let mut inside = true;
            for &v in face {
                let d = self.screen[v as usize].1;
                inside &= d >= cam.near && d <= cam.far;
                z += d;
            }
            if inside {
                self.order[n] = (z / face.len() as f32, f as u16);
                n += 1;
            }
        }
        // Far to near; equal distances by face index.
        self.order[..n].sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let fill = PrimitiveStyle::with_fill(BACKGROUND);
        let stroke = PrimitiveStyle::with_stroke(BinaryColor::On, 1);
        for &(_, f) in &self.order[..n] {
            let face = mesh.face(usize::from(f));
            let p = |k: usize| self.screen[face[k] as usize].0;
            for k in 1..face.len() - 1 {
                Triangle::new(p(0), p(k), p(k + 1))
                    .into_styled(fill)
                    .draw(target)?;
            }
            for k in 0..face.len() {
                Line::new(p(k), p((k + 1) % face.len()))
                    .into_styled(stroke)
                    .draw(target)?;
            }
        }
        Ok(())
    }
}

/// The background colour (the frame is cleared to it).
pub const BACKGROUND: BinaryColor = BinaryColor::Off;
