//! Meshes are watertight: drawing every triangle of a mesh covers each pixel whose centre
//! is inside the mesh's outer boundary exactly once, and no pixel outside it; so the XOR
//! (parity) of the coverage is 1 inside and 0 outside. Checked with the scan converter
//! and with the XOR filler, on piglit-style triangle fans (vertices stepping 0..1 px along
//! a circle, which may be larger than the screen) and on jittered triangulated grids.

use crate::support;

use host_tests::random::{fan, grid, Mesh, RawPolygon, Rng};
use host_tests::reference::{winding_map, Polygon, Rule};
use support::{fill_raw, CountSink, Filler};

#[derive(Clone, Copy, Debug)]
enum Kind {
    Fan,
    Grid,
}

fn random_mesh(rng: &mut Rng, kind: Kind, s: u32, width: u32, height: u32) -> Mesh {
    let full = f64::from(width.max(height));
    match kind {
        Kind::Fan => {
            let r = rng.log_uniform(4.0, 3.0 * full);
            fan(rng, s, width, height, r)
        }
        Kind::Grid => {
            let min_cell = 1.5f64.max(1.5 / f64::from(1u32 << s));
            let cell = rng.log_uniform(min_cell, full / 4.0);
            // A grid covering a random part of the frame, often beyond its borders.
            let origin = (
                rng.range(-0.3, 0.7) * f64::from(width),
                rng.range(-0.3, 0.7) * f64::from(height),
            );
            let nx = 1 + (rng.range(0.1, 1.3) * f64::from(width) / cell) as usize;
            let ny = 1 + (rng.range(0.1, 1.3) * f64::from(height) / cell) as usize;
            grid(rng, s, origin, nx, ny, cell)
        }
    }
}

/// Draws all triangles and checks coverage == |winding of the boundary| (0 or 1) per pixel;
/// returns the number of inside pixels.
fn check_mesh(mesh: &Mesh, filler: Filler, width: u16, height: u16) -> Result<usize, String> {
    let mut sink = CountSink::new(width, height);
    for t in 0..mesh.triangles.len() {
        fill_raw(mesh.s, &mesh.triangle_raw(t), filler, &mut sink)
            .map_err(|e| format!("fill failed: {e:?}"))?;
    }
    let wind = winding_map(&mesh.boundary_f64(), u32::from(width), u32::from(height));
    let w = usize::from(width);
    let mut inside = 0;
    for (i, (&count, &n)) in sink.counts.iter().zip(&wind).enumerate() {
        // All triangles turn the same way as the boundary, whose winding is thus 0 or +-1.
        let n = n.abs();
        assert!(n <= 1, "generator bug: boundary winding {n}");
        inside += n as usize;
        if count != n as u32 || count % 2 != n as u32 {
            let (x, y) = (i % w, i / w);
            return Err(format!(
                "pixel ({x},{y}) covered {count} times, expected {n} (parity {}); {}",
                count % 2,
                culprit(mesh, filler, width, height, x, y)
            ));
        }
    }
    Ok(inside)
}

/// The triangles whose library coverage of pixel (x, y) disagrees with the reference.
fn culprit(mesh: &Mesh, filler: Filler, width: u16, height: u16, x: usize, y: usize) -> String {
    let mut out = Vec::new();
    for t in 0..mesh.triangles.len() {
        let mut one = CountSink::new(width, height);
        // A failing fill was reported already; here only coverage is compared.
        if fill_raw(mesh.s, &mesh.triangle_raw(t), filler, &mut one).is_err() {
            continue;
        }
        let got = one.counts[y * usize::from(width) + x] > 0;
        let tri = Polygon::new(&mesh.triangle_f64(t), f64::from(width.max(height)));
        let want = tri.covered(Rule::EvenOdd, x as f64 + 0.5, y as f64 + 0.5);
        if got != want {
            let p = RawPolygon {
                s: mesh.s,
                pts: mesh.triangle_raw(t).to_vec(),
            };
            out.push(format!(
                "triangle S={} raw {:?} = {:?}: drawn {got}, reference {want}",
                p.s,
                p.pts,
                p.to_f64()
            ));
        }
    }
    if out.is_empty() {
        "every triangle alone agrees with the reference".to_string()
    } else {
        out.join("; ")
    }
}

fn run(seed: u64, count: usize, kinds: &[Kind], filler: Filler, width: u16, height: u16) {
    let mut rng = Rng::new(seed);
    let (mut triangles, mut inside) = (0usize, 0usize);
    let mut failures = Vec::new();
    for _ in 0..count {
        let s = rng.pick(&[0, 4, 8]);
        let kind = rng.pick(kinds);
        let mesh = random_mesh(&mut rng, kind, s, u32::from(width), u32::from(height));
        triangles += mesh.triangles.len();
        match check_mesh(&mesh, filler, width, height) {
            Ok(n) => inside += n,
            Err(e) => failures.push(format!(
                "{kind:?} mesh, S={s}, {} triangles: {e}",
                mesh.triangles.len()
            )),
        }
    }
    println!(
        "{filler:?} {width}x{height}: {count} meshes, {triangles} triangles, {inside} inside pixels, {} failures",
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {count} meshes leak or overlap:\n{}",
        failures.len(),
        failures[..failures.len().min(3)].join("\n")
    );
}

#[test]
fn triangle_fans_cover_each_inside_pixel_once_with_scan_converter() {
    run(
        0xfa40_0001,
        5_000,
        &[Kind::Fan],
        Filler::Scan(Rule::EvenOdd),
        64,
        64,
    );
}

#[test]
fn triangulated_grids_cover_each_inside_pixel_once_with_scan_converter() {
    run(
        0x6a1d_0001,
        5_000,
        &[Kind::Grid],
        Filler::Scan(Rule::NonZero),
        64,
        64,
    );
}

#[test]
fn triangle_fans_cover_each_inside_pixel_once_with_xor_filler() {
    run(0xfa40_0002, 5_000, &[Kind::Fan], Filler::Xor, 64, 64);
}

#[test]
fn triangulated_grids_cover_each_inside_pixel_once_with_xor_filler() {
    run(0x6a1d_0002, 5_000, &[Kind::Grid], Filler::Xor, 64, 64);
}

#[test]
fn large_meshes_cover_each_inside_pixel_once_on_1000x1000_with_scan_converter() {
    run(
        0x1000_0001,
        24,
        &[Kind::Fan, Kind::Grid],
        Filler::Scan(Rule::EvenOdd),
        1000,
        1000,
    );
}

#[test]
fn large_meshes_cover_each_inside_pixel_once_on_1000x1000_with_xor_filler() {
    run(
        0x1000_0002,
        12,
        &[Kind::Fan, Kind::Grid],
        Filler::Xor,
        1000,
        1000,
    );
}
