//! The firmware's cube scene rendered on the host: its hash must be the constant the
//! firmware checks on the emulated Cortex-M4 (`scripts/thumb-check`), so a run there
//! that passes proves the two produce the same bits.

use pbuffer_firmware::cube;

#[test]
fn firmware_cube_hash_matches_the_host() {
    let mut fb = cube::CubeFrame::new();
    let stats = cube::render_cube(&mut fb).expect("renders");
    let lit: u32 = fb.as_bytes().iter().map(|b| b.count_ones()).sum();
    assert!(lit > 200, "the cube is drawn: {lit} pixels");
    assert_eq!(
        (stats.faces, stats.faces_drawn, stats.feature_edges),
        (6, 3, 12)
    );
    let hash = cube::fnv1a64(fb.as_bytes());
    assert_eq!(hash, cube::EXPECTED_CUBE, "host hash {hash:016x}");
}
