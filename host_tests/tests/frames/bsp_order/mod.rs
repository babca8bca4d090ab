//! The BSP tree's depth order, checked against f64 ray casting (independent of the
//! tree): for every ray from the eye, the nearest fragment it meets ranks first among
//! the fragments it meets. Random triangle soups (seeded), perspective and
//! orthographic eyes; the fragments tile their source faces and lie in their planes.
//! Plus the test models: fragment counts, depth and build time, printed
//! (`cargo test --release -p host_tests --test frames bsp_order:: -- --nocapture`).
mod geometry;
mod rays;
mod scenes;
mod storage;
mod tiling;

use std::path::Path;
use std::time::Instant;

use host_tests::obj::load_obj;
use host_tests::random::Rng;
use pbuffer::order::{work_bound, BspOptions, BspSizes, BspTree};
use pbuffer::Viewpoint;

use geometry::{add, norm, sub, unit};
use rays::{check_ray, Tally};
use scenes::{random_direction, soup, target};
use storage::{Csr, Owned};
use tiling::{check_tiling, check_watertight};

#[test]
fn random_soups_rank_the_nearest_fragment_first() {
    let mut rng = Rng::new(0xB5B5_0001);
    let mut total = Tally::default();
    let (mut faces, mut fragments, mut worst_area) = (0usize, 0usize, 0.0f64);
    let (mut seam_edges, mut open_edges) = (0usize, 0usize);
    for scene in 0..200 {
        let n = 10 + rng.below(21) as usize;
        let csr = Csr::from_data(&soup(&mut rng, n));
        let mesh = csr.mesh();
        let (mut owned, _) = csr.storage_that_fits();
        let tree = BspTree::build(&mesh, owned.storage()).unwrap();
        faces += n;
        fragments += tree.fragment_count();
        assert!(
            tree.work_peak() <= work_bound(tree.fragment_count(), tree.fragments().indices().len())
        );
        worst_area = worst_area.max(check_tiling(&mesh, &tree, 1.0));
        let (edges, exempt) = check_watertight(&mesh, &tree, 1.0);
        seam_edges += edges;
        open_edges += exempt;
        let mut stack = vec![0u32; tree.depth()];
        let mut rank = vec![u32::MAX; tree.fragment_count()];
        for e in 0..4 {
            let (view, eye) = if e % 2 == 0 {
                // Outside the soup (e = 0) or inside it (e = 2).
                let r = if e == 0 {
                    rng.range(2.0, 5.0)
                } else {
                    rng.range(0.0, 0.8)
                };
                let eye = random_direction(&mut rng).map(|c| c * r);
                (
                    Viewpoint::Perspective {
                        eye: eye.map(|c| c as f32),
                    },
                    Some(eye),
                )
            } else {
                let d = random_direction(&mut rng);
                (
                    Viewpoint::Orthographic {
                        direction_to_eye: d.map(|c| c as f32),
                    },
                    None,
                )
            };
            rank.fill(u32::MAX);
            tree.rank_front_to_back(&view, &mut stack, &mut rank)
                .unwrap();
            let mut sorted = rank.clone();
            sorted.sort_unstable();
            assert!(
                sorted.iter().enumerate().all(|(i, &r)| r as usize == i),
                "not a permutation"
            );
            for _ in 0..50 {
                let target = target(&mut rng, &mesh, [-1.0; 3], [1.0; 3]);
                let (origin, dir) = match (view, eye) {
                    (Viewpoint::Perspective { eye: e32 }, Some(_)) => {
                        let o = e32.map(f64::from);
                        (o, unit(sub(target, o)))
                    }
                    (Viewpoint::Orthographic { direction_to_eye }, _) => {
                        let d = unit(direction_to_eye.map(f64::from));
                        (add(target, d.map(|c| 100.0 * c)), d.map(|c| -c))
                    }
                    _ => unreachable!(),
                };
                check_ray(&tree, &rank, origin, dir, 1e-9, &mut total);
            }
        }
        assert!(
            total.failures.is_empty(),
            "scene {scene}: {:#?}",
            total.failures
        );
    }
    println!(
        "soups: {faces} triangles -> {fragments} fragments ({:.2}x); rays {}: {} checked, \
         {} missed, {} near an edge, {} ties (<= 1e-9); worst area error {worst_area:.2e} relative",
        fragments as f64 / faces as f64,
        total.rays,
        total.checked,
        total.missed,
        total.edge,
        total.ties
    );
    println!(
        "soups: {seam_edges} fragment edges, {} with an opposite half, {open_edges} on open mesh edges",
        seam_edges - open_edges
    );
    assert!(
        fragments > faces + faces / 2,
        "soups this dense must split a lot"
    );
    assert!(total.checked > total.rays / 2, "{total:?}");
}

#[test]
fn models_build_with_reasonable_sizes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/models");
    let mut rng = Rng::new(7);
    for name in [
        "suzanne", "beetle", "woody", "teapot", "cow", "spot", "fandisk",
    ] {
        let path = dir.join(format!("{name}.obj"));
        let Ok(data) = load_obj(&path) else {
            println!("{name}: not found at {}, skipped", path.display());
            continue;
        };
        let csr = Csr::from_data(&data);
        let mesh = csr.mesh();
        let (mut owned, _) = csr.storage_that_fits();
        let start = Instant::now();
        let tree = BspTree::build(&mesh, owned.storage()).unwrap();
        let time = start.elapsed();
        let (faces, fragments) = (mesh.face_count(), tree.fragment_count());
        let index_count = tree.fragments().indices().len();
        println!(
            "{name:8}: {faces:6} faces -> {fragments:6} fragments ({:.2}x), {} splits, {} nodes, \
             depth {}, {} split points, work peak {} words, build {:.1} ms",
            fragments as f64 / faces as f64,
            tree.splits(),
            tree.node_count(),
            tree.depth(),
            tree.fragments().vertices().len() - mesh.vertices().len(),
            tree.work_peak(),
            time.as_secs_f64() * 1e3
        );
        assert!(tree.work_peak() <= work_bound(fragments, index_count));
        // The documented sizes, for the splits this mesh needs, suffice.
        let sizes = BspSizes::for_mesh(
            mesh.vertices().len(),
            faces,
            mesh.indices().len(),
            tree.splits(),
        );
        let mut exact = Owned::new(sizes);
        let again = BspTree::build(&mesh, exact.storage()).expect("for_mesh sizes");
        assert_eq!(again.fragment_count(), fragments);

        // A sample of rays from three eyes around the model.
        let mut tally = Tally::default();
        let (lo, hi) = data
            .vertices
            .iter()
            .fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), v| {
                (
                    core::array::from_fn(|k| lo[k].min(v[k])),
                    core::array::from_fn(|k| hi[k].max(v[k])),
                )
            });
        let centre: [f64; 3] = core::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
        let radius = norm(sub(hi, lo));
        let scale = data
            .vertices
            .iter()
            .flatten()
            .fold(0.0f64, |m, c| m.max(c.abs()));
        let area_error = check_tiling(&mesh, &tree, scale);
        let (edges, exempt) = check_watertight(&mesh, &tree, scale);
        println!(
            "          watertight: {edges} fragment edges, {exempt} on open mesh edges; \
             kept {} bytes",
            std::mem::size_of_val(tree.fragments().vertices())
                + std::mem::size_of_val(tree.fragments().indices())
                + std::mem::size_of_val(tree.fragments().face_offsets())
                + std::mem::size_of_val(tree.source())
                + std::mem::size_of_val(tree.nodes())
        );
        let mut stack = vec![0u32; tree.depth()];
        let mut rank = vec![0u32; fragments];
        for _ in 0..3 {
            let eye = add(centre, random_direction(&mut rng).map(|c| c * 1.5 * radius));
            let e32 = eye.map(|c| c as f32);
            tree.rank_front_to_back(&Viewpoint::Perspective { eye: e32 }, &mut stack, &mut rank)
                .unwrap();
            let o = e32.map(f64::from);
            for _ in 0..40 {
                let target = target(&mut rng, &mesh, lo, hi);
                check_ray(
                    &tree,
                    &rank,
                    o,
                    unit(sub(target, o)),
                    1e-7 * radius,
                    &mut tally,
                );
            }
        }
        println!("          worst area error {area_error:.2e} relative; rays: {tally:?}");
        assert!(tally.failures.is_empty(), "{name}: {:#?}", tally.failures);
    }
}

/// Fragments and depth for a few splitter choices (`--ignored --nocapture`).
#[test]
#[ignore]
fn splitter_options_sweep() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/models");
    for name in ["suzanne", "beetle", "teapot", "cow", "spot", "fandisk"] {
        let Ok(data) = load_obj(&dir.join(format!("{name}.obj"))) else {
            continue;
        };
        let csr = Csr::from_data(&data);
        let mesh = csr.mesh();
        let sizes = BspSizes::for_mesh(
            mesh.vertices().len(),
            mesh.face_count(),
            mesh.indices().len(),
            8 * mesh.face_count(),
        );
        let mut owned = Owned::new(sizes);
        for candidates in [1u16, 4, 8, 16, 32] {
            for split_weight in [1u32, 4, 8, 32] {
                let start = Instant::now();
                let options = BspOptions {
                    candidates,
                    split_weight,
                };
                let tree = BspTree::build_with(&mesh, owned.storage(), options).unwrap();
                println!(
                    "{name:8} K {candidates:2} w {split_weight:2}: {:.2}x fragments, depth {:4}, {:6.1} ms",
                    tree.fragment_count() as f64 / mesh.face_count() as f64,
                    tree.depth(),
                    start.elapsed().as_secs_f64() * 1e3
                );
            }
        }
    }
}
