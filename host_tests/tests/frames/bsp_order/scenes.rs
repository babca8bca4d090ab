//! Random scenes and rays: directions, triangle soups, ray targets on faces.

use host_tests::frame::MeshData;
use host_tests::random::Rng;
use pbuffer::Mesh;

use super::geometry::{add, norm, pos, sub};

pub(super) fn random_direction(rng: &mut Rng) -> [f64; 3] {
    loop {
        let v = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let n = norm(v);
        if n > 0.1 && n <= 1.0 {
            return v.map(|c| c / n);
        }
    }
}

/// A soup of `n` random triangles in `[-1, 1]^3`, sizes 0.2 to 1.5.
pub(super) fn soup(rng: &mut Rng, n: usize) -> MeshData {
    let mut data = MeshData::default();
    for f in 0..n {
        let centre = [
            rng.range(-0.8, 0.8),
            rng.range(-0.8, 0.8),
            rng.range(-0.8, 0.8),
        ];
        let size = rng.range(0.2, 1.5);
        for _ in 0..3 {
            let d = random_direction(rng);
            let r = size * rng.range(0.3, 1.0);
            data.vertices.push(add(centre, d.map(|c| c * r)));
        }
        let k = 3 * f as u32;
        data.faces.push(vec![k, k + 1, k + 2]);
    }
    data
}

/// A target for a ray: a random point of a random face (three times in four, so
/// most rays meet something), else a random point of the box `lo..hi`.
pub(super) fn target(rng: &mut Rng, mesh: &Mesh<'_>, lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
    if rng.below(4) == 0 {
        return core::array::from_fn(|k| rng.range(lo[k], hi[k]));
    }
    let c = mesh.face(rng.below(mesh.face_count() as u64) as usize);
    let i = 1 + rng.below(c.len() as u64 - 2) as usize;
    let (a, b) = (rng.unit(), rng.unit());
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    let p0 = pos(mesh, c[0]);
    let e1 = sub(pos(mesh, c[i]), p0);
    let e2 = sub(pos(mesh, c[i + 1]), p0);
    core::array::from_fn(|k| p0[k] + a * e1[k] + b * e2[k])
}
