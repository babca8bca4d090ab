//! Validation, lent capacities and garbage input.

use super::*;
use crate::Capacity;
use crate::Error;

#[test]
fn validation_errors_name_the_first_problem() {
    let v = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let six = [0, 1, 2, 1, 3, 2];
    let bad = |face| Err(Error::BadFaceOffsets { face });
    assert_eq!(Mesh::new(&v, &six, &[]).map(|_| ()), bad(0));
    assert_eq!(Mesh::new(&v, &six, &[1, 3, 6]).map(|_| ()), bad(0));
    assert_eq!(Mesh::new(&v, &six, &[0, 4, 3, 6]).map(|_| ()), bad(1));
    assert_eq!(Mesh::new(&v, &six, &[0, 3, 7]).map(|_| ()), bad(1));
    assert_eq!(Mesh::new(&v, &six, &[0, 3, u32::MAX]).map(|_| ()), bad(1));
    assert_eq!(Mesh::new(&v, &six, &[0, 3, 5]).map(|_| ()), bad(1));
    assert_eq!(Mesh::new(&v, &six, &[0, 3]).map(|_| ()), bad(0));
    assert_eq!(Mesh::new(&v, &six, &[0]).map(|_| ()), bad(0));
    assert_eq!(Mesh::new(&v, &[], &[0]).map(|_| ()), Err(Error::EmptyMesh));
    assert_eq!(Mesh::new(&[], &[], &[0]).map(|_| ()), Err(Error::EmptyMesh));

    static EMPTY_FACES: [u32; MAX_FACES + 2] = [0; MAX_FACES + 2];
    assert_eq!(
        Mesh::new(&v, &[], &EMPTY_FACES).map(|_| ()),
        Err(Error::TooManyFaces {
            faces: MAX_FACES + 1,
            max: MAX_FACES
        })
    );
    // Exactly MAX_FACES is allowed by the count (these empty faces are degenerate).
    assert_eq!(
        Mesh::new(&v, &[], &EMPTY_FACES[..=MAX_FACES]).map(|_| ()),
        Err(Error::DegenerateFace { face: 0 })
    );

    let mut nan = v;
    nan[2][1] = f32::NAN;
    nan[3][0] = f32::INFINITY;
    assert_eq!(
        Mesh::new(&nan, &six, &[0, 3, 6]).map(|_| ()),
        Err(Error::NonFiniteVertex { vertex: 2 })
    );
    // Vertices are checked before faces, even vertices no face uses.
    let mut unused = [[0.0f32; 3]; 5];
    unused[..4].copy_from_slice(&v);
    unused[4] = [0.0, f32::NEG_INFINITY, 0.0];
    assert_eq!(
        Mesh::new(&unused, &[0, 1, 9], &[0, 3]).map(|_| ()),
        Err(Error::NonFiniteVertex { vertex: 4 })
    );

    assert_eq!(
        Mesh::new(&v, &[0, 1, 2, 1, 4, u32::MAX], &[0, 3, 6]).map(|_| ()),
        Err(Error::IndexOutOfRange { face: 1, index: 4 })
    );
    assert_eq!(
        Mesh::new(&v, &[0, 1, 2, u32::MAX, 1, 2], &[0, 3, 6]).map(|_| ()),
        Err(Error::IndexOutOfRange {
            face: 1,
            index: u32::MAX
        })
    );
    // Faces in order: face 0's short list comes before face 1's bad index.
    assert_eq!(
        Mesh::new(&v, &[0, 1, 1, 9, 2], &[0, 2, 5]).map(|_| ()),
        Err(Error::DegenerateFace { face: 0 })
    );
    // A repeated index is no error (CONVENTIONS: 3 valid indices); a bad one is.
    assert_eq!(
        Mesh::new(&v, &[0, 0, 9], &[0, 3]).map(|_| ()),
        Err(Error::IndexOutOfRange { face: 0, index: 9 })
    );
    let degenerate = |indices: &[u32], offsets: &[u32]| Mesh::new(&v, indices, offsets).map(|_| ());
    assert_eq!(
        degenerate(&[0, 1, 2, 1, 2], &[0, 3, 5]),
        Err(Error::DegenerateFace { face: 1 })
    );
    // Repeated positions are valid faces with a zero normal: they cover nothing and
    // make no crease or silhouette.
    for (indices, offsets) in [
        (&[0u32, 1, 2, 3, 3, 3, 3][..], &[0u32, 3, 7][..]),
        (&[0, 1, 2, 2, 3, 2, 3], &[0, 3, 7]),
    ] {
        let mesh = Mesh::new(&v, indices, offsets).expect("repeated vertices are valid");
        assert_eq!(mesh.face_normal(1), [0.0; 3]);
    }
    // Distinct indices at bit-identical positions likewise.
    let twin = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];
    let mesh = Mesh::new(&twin, &[0, 1, 2], &[0, 3]).expect("valid");
    assert_eq!(mesh.face_normal(0), [0.0; 3]);
}

#[test]
fn capacity_errors_give_the_exact_size_needed() {
    let quads = quad_indices();
    let mesh = Mesh::new(&CUBE, &quads, &QUAD_OFFSETS).unwrap();
    let (mut weld, mut scratch, mut out) = (
        [0u32; 8],
        [HalfEdgeRecord::EMPTY; 24],
        [MeshEdge::EMPTY; 12],
    );
    let exceeded = |what, needed, capacity| {
        Err(Error::CapacityExceeded {
            what,
            needed,
            capacity,
        })
    };
    assert_eq!(
        EdgeAdjacency::build(
            &mesh,
            30.0,
            &mut weld[..7],
            &mut scratch[..0],
            &mut out[..0]
        )
        .map(|_| ()),
        exceeded(Capacity::Vertices, 8, 7)
    );
    assert_eq!(
        EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch[..23], &mut out[..0]).map(|_| ()),
        exceeded(Capacity::HalfEdges, 24, 23)
    );
    assert_eq!(
        EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut out[..11]).map(|_| ()),
        exceeded(Capacity::Edges, 12, 11)
    );
    assert_eq!(
        EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut out[..0]).map(|_| ()),
        exceeded(Capacity::Edges, 12, 0)
    );
    // The crease angle is checked first.
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(
            EdgeAdjacency::build(&mesh, bad, &mut weld[..0], &mut scratch, &mut out).map(|_| ()),
            Err(Error::NonFinite)
        );
    }
    assert_eq!(
        EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut out)
            .map(|a| a.edges().len()),
        Ok(12)
    );

    let triangles = triangle_indices();
    let mesh = Mesh::new(&CUBE, &triangles, &TRI_OFFSETS).unwrap();
    let (mut scratch, mut out) = ([HalfEdgeRecord::EMPTY; 36], [MeshEdge::EMPTY; 18]);
    assert_eq!(
        EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch[..35], &mut out).map(|_| ()),
        exceeded(Capacity::HalfEdges, 36, 35)
    );
    assert_eq!(
        EdgeAdjacency::build(&mesh, 30.0, &mut weld, &mut scratch, &mut out[..17]).map(|_| ()),
        exceeded(Capacity::Edges, 18, 17)
    );
    // Larger buffers than needed are fine.
    let mut buffers = Buffers::new();
    assert_eq!(buffers.build(&mesh, 30.0).edges().len(), 18);
}

/// xorshift32: a deterministic stream of garbage.
struct Garbage(u32);

impl Garbage {
    fn next(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }

    fn below(&mut self, n: u32) -> u32 {
        self.next() % n
    }

    /// A coordinate: wild when `wild`, else one of few values, so that positions
    /// often coincide.
    fn coordinate(&mut self, wild: bool) -> f32 {
        if !wild {
            return [0.0, 1.0, 2.0, -0.0][self.below(4) as usize];
        }
        match self.below(10) {
            0 => f32::NAN,
            1 => f32::INFINITY,
            2 => -0.0,
            3 => f32::MAX,
            4 => f32::from_bits(self.next()),
            _ => self.below(3) as f32,
        }
    }
}

#[test]
fn garbage_never_panics() {
    let mut rng = Garbage(0x2545_f491);
    let mut ok = 0;
    for round in 0..20_000 {
        // One round in four is wild; the others are near misses that often pass.
        let wild = round % 4 == 0;
        let vertex_count = rng.below(9) as usize;
        let mut vertices = [[0.0f32; 3]; 8];
        for v in vertices.iter_mut() {
            *v = [
                rng.coordinate(wild),
                rng.coordinate(wild),
                rng.coordinate(wild),
            ];
        }
        let index_count = rng.below(17) as usize;
        let mut indices = [0u32; 16];
        for i in indices.iter_mut() {
            *i = match rng.below(if wild { 4 } else { 40 }) {
                0 => u32::MAX,
                1 => rng.next(),
                _ => rng.below(vertex_count.max(1) as u32),
            };
        }
        let offset_count = rng.below(7) as usize;
        let mut offsets = [0u32; 6];
        let mut at = 0;
        for o in offsets.iter_mut().skip(1) {
            at += 3 + rng.below(3);
            *o = match rng.below(if wild { 3 } else { 30 }) {
                0 => u32::MAX,
                1 => rng.below(20),
                _ => at.min(index_count as u32),
            };
        }
        if !wild && offset_count > 0 {
            offsets[offset_count - 1] = index_count as u32;
        }
        let Ok(mesh) = Mesh::new(
            &vertices[..vertex_count],
            &indices[..index_count],
            &offsets[..offset_count],
        ) else {
            continue;
        };
        ok += 1;
        let view = Viewpoint::Perspective {
            eye: [
                rng.coordinate(wild),
                rng.coordinate(wild),
                rng.coordinate(wild),
            ],
        };
        for f in [0, 1, mesh.face_count(), usize::MAX] {
            let _ = (mesh.face(f), mesh.face_normal(f), mesh.face_centroid(f));
            let _ = mesh.faces_viewpoint(f, &view);
        }
        let crease = [30.0, -1.0, 0.0, 180.0, 1e30, f32::NAN][rng.below(6) as usize];
        let mut buffers = Buffers::new();
        let small = rng.below(17) as usize;
        let _ = EdgeAdjacency::build(
            &mesh,
            crease,
            &mut buffers.weld[..small],
            &mut buffers.scratch[..small],
            &mut buffers.out[..small],
        );
        if let Ok(adjacency) = EdgeAdjacency::build(
            &mesh,
            crease,
            &mut buffers.weld,
            &mut buffers.scratch,
            &mut buffers.out,
        ) {
            let _ = adjacency.is_closed();
            for e in adjacency.edges() {
                assert!(e.a < e.b && e.face_count >= 1);
                assert!(face_owns_edge(&mesh, e, e.faces[0] as usize));
                assert!(face_owns_edge(&mesh, e, e.faces[1] as usize));
                let _ = e.is_feature(&mesh, &view);
            }
        }
    }
    // The generator must reach the adjacency often enough to mean something.
    assert!(ok > 500, "only {ok} valid meshes");
}
