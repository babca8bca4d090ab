//! Procedural parts in fixed-size arrays (no allocation): boxes and octagonal
//! prisms ("cylinders"), each closed and wound counter-clockwise seen from
//! outside, put together into one mesh ([`Shape`]). `examples/embedded/build.rs`
//! bakes the robot arm's parts and the instance grids from them, and the host
//! bakes the very same arrays at run time, so both draw the same meshes.

/// A mesh in fixed arrays: `V` vertices, `I` corner indices and `O` face offsets
/// (faces + 1), filled by [`cuboid`](Self::cuboid) and [`prism`](Self::prism) in
/// the order they are called. Building more than the arrays hold panics (a
/// build-time mistake: the sizes are the part's constants).
#[derive(Debug, Clone)]
pub struct Shape<const V: usize, const I: usize, const O: usize> {
    /// Vertex positions.
    pub vertices: [[f32; 3]; V],
    /// Face corners (CSR).
    pub indices: [u32; I],
    /// Face offsets into `indices`.
    pub offsets: [u32; O],
    v: usize,
    i: usize,
    f: usize,
}

/// An axis of a prism.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    Y,
    Z,
}

/// The octagon's corners on the unit circle, at 22.5 + 45 k degrees (so that a
/// flat side faces each axis).
const OCTAGON: [[f32; 2]; 8] = [
    [0.923_879_5, 0.382_683_43],
    [0.382_683_43, 0.923_879_5],
    [-0.382_683_43, 0.923_879_5],
    [-0.923_879_5, 0.382_683_43],
    [-0.923_879_5, -0.382_683_43],
    [-0.382_683_43, -0.923_879_5],
    [0.382_683_43, -0.923_879_5],
    [0.923_879_5, -0.382_683_43],
];

/// Vertices, corners and faces of a box.
pub const BOX: [usize; 3] = [8, 24, 6];
/// Vertices, corners and faces of an octagonal prism.
pub const PRISM: [usize; 3] = [16, 48, 10];

impl<const V: usize, const I: usize, const O: usize> Shape<V, I, O> {
    /// Empty.
    pub const fn new() -> Self {
        Self {
            vertices: [[0.0; 3]; V],
            indices: [0; I],
            offsets: [0; O],
            v: 0,
            i: 0,
            f: 0,
        }
    }

    /// Is every array full (the part's constants right)?
    pub fn is_full(&self) -> bool {
        (self.v, self.i, self.f + 1) == (V, I, O)
    }

    fn vertex(&mut self, p: [f32; 3]) {
        self.vertices[self.v] = p;
        self.v += 1;
    }

    /// A face of the vertices `base + k` for `k` in `corners`.
    fn face(&mut self, base: usize, corners: impl IntoIterator<Item = usize>) {
        for k in corners {
            self.indices[self.i] = (base + k) as u32;
            self.i += 1;
        }
        self.f += 1;
        self.offsets[self.f] = self.i as u32;
    }

    /// The axis-aligned box from `lo` to `hi`.
    pub fn cuboid(mut self, lo: [f32; 3], hi: [f32; 3]) -> Self {
        let base = self.v;
        for k in 0..8 {
            let x = if matches!(k % 4, 1 | 2) { hi[0] } else { lo[0] };
            let y = if k % 4 >= 2 { hi[1] } else { lo[1] };
            let z = if k >= 4 { hi[2] } else { lo[2] };
            self.vertex([x, y, z]);
        }
        for quad in [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [2, 3, 7, 6],
            [1, 2, 6, 5],
            [0, 4, 7, 3],
        ] {
            self.face(base, quad);
        }
        self
    }

    /// An octagonal prism of circumradius `r` around `axis` through `centre`, from
    /// `centre - half` to `centre + half` along it.
    pub fn prism(mut self, axis: Axis, centre: [f32; 3], r: f32, half: f32) -> Self {
        // (u, v, axis) right-handed: the rings turn counter-clockwise about the axis.
        let (u, v, a) = match axis {
            Axis::Y => (2, 0, 1),
            Axis::Z => (0, 1, 2),
        };
        let base = self.v;
        for end in [-half, half] {
            for [c, s] in OCTAGON {
                let mut p = centre;
                p[u] += r * c;
                p[v] += r * s;
                p[a] += end;
                self.vertex(p);
            }
        }
        for k in 0..8 {
            let next = (k + 1) % 8;
            self.face(base, [k, next, 8 + next, 8 + k]);
        }
        self.face(base, 8..16);
        self.face(base, (0..8).rev());
        self
    }
}

impl<const V: usize, const I: usize, const O: usize> Shape<V, I, O> {
    /// `part` appended with its vertices posed by `pose` (`Pose::apply`, the
    /// bits a scene's frame poses them to): a union of instances as one mesh.
    pub fn posed<const V2: usize, const I2: usize, const O2: usize>(
        mut self,
        part: &Shape<V2, I2, O2>,
        pose: &pbuffer::Pose,
    ) -> Self {
        let base = self.v;
        for p in &part.vertices[..part.v] {
            self.vertex(pose.apply(*p));
        }
        for f in 0..part.f {
            let corners = &part.indices[part.offsets[f] as usize..part.offsets[f + 1] as usize];
            self.face(base, corners.iter().map(|&c| c as usize));
        }
        self
    }
}

impl<const V: usize, const I: usize, const O: usize> Default for Shape<V, I, O> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face's Newell normal points away from the shape's middle.
    fn outward<const V: usize, const I: usize, const O: usize>(s: &Shape<V, I, O>, mid: [f32; 3]) {
        assert!(s.is_full());
        for f in 0..O - 1 {
            let c = &s.indices[s.offsets[f] as usize..s.offsets[f + 1] as usize];
            let at = |k: usize| s.vertices[c[k % c.len()] as usize];
            let mut n = [0.0f32; 3];
            let mut centroid = [0.0f32; 3];
            for k in 0..c.len() {
                let (a, b) = (at(k), at(k + 1));
                n[0] += (a[1] - b[1]) * (a[2] + b[2]);
                n[1] += (a[2] - b[2]) * (a[0] + b[0]);
                n[2] += (a[0] - b[0]) * (a[1] + b[1]);
                (0..3).for_each(|j| centroid[j] += a[j] / c.len() as f32);
            }
            let d: f32 = (0..3).map(|j| n[j] * (centroid[j] - mid[j])).sum();
            assert!(d > 0.0, "face {f} faces inward");
        }
    }

    #[test]
    fn boxes_and_prisms_face_outward() {
        outward(
            &Shape::<8, 24, 7>::new().cuboid([0.0, -1.0, 2.0], [1.0, 0.5, 3.0]),
            [0.5, -0.25, 2.5],
        );
        for axis in [Axis::Y, Axis::Z] {
            outward(
                &Shape::<16, 48, 11>::new().prism(axis, [1.0, 2.0, 3.0], 0.5, 0.2),
                [1.0, 2.0, 3.0],
            );
        }
    }
}
