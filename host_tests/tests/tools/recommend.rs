//! `pbuffer::recommend` holds on the scenes: rendered with the recommended sub-pixel
//! bits (code fill) and the recommended S and depth bits (Z-buffer), every pixel
//! whose face differs from the f64 reference lies within the error bound of an
//! exact edge (a face boundary or an intersection line), no face id differs away
//! from edges, there is no depth-order error and no hole, and the code-fill engine
//! needs no more code bits than the recommended words hold. The full check on every
//! scene and model is in `report/speed-vs-error.md` (`cargo run --release -p
//! host_tests --bin report`).

use host_tests::frame::RenderSpec;
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;
use host_tests::tools::report::errors::{depth_complexity, measure};
use host_tests::tools::report::run::{recommended_configs, scene_bounds, BOUND};
use host_tests::tools::report::{load_scene, SIZES};
use pbuffer::recommend::recommend;
use pbuffer::Viewport;

fn check(name: &str) -> Vec<String> {
    let scene = load_scene(name).expect("procedural scene");
    let mut failures = Vec::new();
    for size in SIZES {
        let cam = scene.camera(size.0, size.1, false);
        let base = RenderSpec {
            width: size.0,
            height: size.1,
            band: size.1,
            ..RenderSpec::default()
        };
        let rf = reference_frame(&scene.mesh, &cam, &base).expect("reference");
        let layers = depth_complexity(&rf);
        let bounds =
            scene_bounds(&scene.mesh, &cam, layers).with_coplanar_overlaps(name == "coplanar");
        let viewport = Viewport {
            width: size.0 as u16,
            height: size.1 as u16,
        };
        let rec = recommend(&bounds, viewport, &BOUND);
        assert!(rec.meets_bound, "{name}: {rec:?}");
        for config in recommended_configs(&rec) {
            let frame = render_frame(&scene.mesh, &cam, &config.spec(size)).expect("render");
            let e = measure(&frame, &rf);
            let code_bits = frame
                .stats
                .iter()
                .find(|s| s.0 == "code_bits")
                .map_or(0, |s| s.1);
            let label = format!("{name} {}x{} {}", size.0, size.1, config.label());
            println!(
                "{label}: edge max {:.3} px, far diffs {}, depth-order {}, holes {}, code bits {code_bits} (words {})",
                e.edge_max, e.far_diffs, e.depth_order, e.holes, rec.code_words
            );
            if e.edge_max > f64::from(BOUND.edge_px) {
                failures.push(format!("{label}: edge displacement {:.3} px", e.edge_max));
            }
            if e.far_diffs + e.depth_order + e.holes + e.wrong_faces > 0 {
                failures.push(format!("{label}: {e:?}"));
            }
            if code_bits > 32 * u64::from(rec.code_words) {
                failures.push(format!("{label}: {code_bits} code bits"));
            }
        }
    }
    failures
}

#[test]
fn recommendation_holds_on_procedural_scenes() {
    let failures: Vec<String> = ["boxes", "torus", "gear", "cyclic", "coplanar"]
        .iter()
        .flat_map(|n| check(n))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn coplanar_faces_get_four_bits_and_32_bit_depth() {
    let scene = load_scene("coplanar").expect("procedural scene");
    let cam = scene.camera(SIZES[0].0, SIZES[0].1, false);
    let bounds = scene_bounds(&scene.mesh, &cam, 3).with_coplanar_overlaps(true);
    let viewport = Viewport {
        width: 400,
        height: 240,
    };
    let rec = recommend(&bounds, viewport, &BOUND);
    assert_eq!((rec.subpixel_bits, rec.depth_bits), (4, 32));
    let plain = recommend(&bounds.with_coplanar_overlaps(false), viewport, &BOUND);
    assert_eq!((plain.subpixel_bits, plain.depth_bits), (2, 16));
}
