//! Unit tests of the flags: defaults, values, errors, cameras.

use std::path::PathBuf;

use super::*;
use crate::frame::{CullSpec, EngineSpec, MeshData, ModeSpec, ProjectionSpec, RenderSpec};
use crate::schemes::SchemeSpec;

fn p(args: &[&str]) -> Result<Options, String> {
    parse_args(args.iter().copied())
}

fn cube() -> MeshData {
    MeshData {
        vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        faces: vec![vec![0, 1, 2]],
    }
}

#[test]
fn defaults() {
    let o = p(&[]).unwrap();
    let fast = RenderSpec {
        engine: EngineSpec::Fast,
        ..RenderSpec::default()
    };
    assert_eq!(o.spec, fast);
    // A flag only the exact engines have picks the code-fill engine.
    for flags in [
        &["--depth-bits", "16"][..],
        &["--subpixel", "8"],
        &["--scheme", "path"],
    ] {
        assert_eq!(
            p(flags).unwrap().spec.engine,
            EngineSpec::CodeFill,
            "{flags:?}"
        );
    }
    assert_eq!(
        p(&["--engine", "zbuffer", "--subpixel", "8"])
            .unwrap()
            .spec
            .engine,
        EngineSpec::ZBuffer
    );
    assert!(o.fits() && o.scene.is_none() && !o.stats && !o.hash);
    assert_eq!(o.spec.band, 240);
}

#[test]
fn all_flags() {
    let o = p(&[
        "m.obj",
        "--size",
        "128x64",
        "--eye=1,2,3",
        "--target",
        "0,0.5,0",
        "--up",
        "0,0,1",
        "--fov",
        "60",
        "--near",
        "0.5",
        "--far",
        "50",
        "--crease",
        "45",
        "--cull",
        "off",
        "--mode",
        "surfaces+dashed",
        "--engine",
        "zbuffer",
        "--subpixel",
        "8",
        "--depth-bits",
        "16",
        "--band",
        "8",
        "--pattern",
        "dots",
        "--out",
        "a.png",
        "--ids",
        "i.pgm",
        "--lines",
        "l.pgm",
        "--stats",
        "--hash",
        "--look",
        "oled-blue",
        "--scale",
        "2",
    ])
    .unwrap();
    assert_eq!(o.scene, Some(PathBuf::from("m.obj")));
    assert_eq!((o.spec.width, o.spec.height, o.spec.band), (128, 64, 8));
    assert_eq!(o.eye, Some([1.0, 2.0, 3.0]));
    assert_eq!(o.spec.cull, CullSpec::Off);
    assert_eq!(o.spec.mode, ModeSpec::SurfacesDashed);
    assert_eq!((o.spec.subpixel, o.spec.depth_bits), (8, 16));
    assert_eq!(o.spec.pattern, "dots");
    assert_eq!(o.scheme, SchemeSpec::Priority);
    assert!(o.stats && o.hash && !o.fits());
    let c = o.camera(&cube()).unwrap();
    assert_eq!(c.up, [0.0, 0.0, 1.0]);
    assert_eq!(c.projection, ProjectionSpec::Perspective { fov_deg: 60.0 });
    assert_eq!((c.near, c.far), (0.5, 50.0));
    let o = p(&["--scheme", "combination"]).unwrap();
    assert_eq!(o.scheme, SchemeSpec::Combination);
    let o = p(&["--engine=codefill", "--scheme=path"]).unwrap();
    assert_eq!(o.scheme, SchemeSpec::Path);
    let o = p(&["--ortho", "2", "--eye", "0,0,5"]).unwrap();
    let c = o.camera(&cube()).unwrap();
    assert_eq!(
        c.projection,
        ProjectionSpec::Orthographic { half_height: 2.0 }
    );
    assert_eq!(c.target, [0.0; 3]);
}

#[test]
fn errors_name_the_flag() {
    for (args, flag) in [
        (&["--size", "0x10"][..], "--size"),
        (&["--size", "400"], "--size"),
        (&["--size", "9000x10"], "--size"),
        (&["--eye", "1,2"], "--eye"),
        (&["--eye", "1,nan,2"], "--eye"),
        (&["--target", "a,b,c"], "--target"),
        (&["--fov", "180"], "--fov"),
        (&["--fov", "inf"], "--fov"),
        (&["--ortho", "-1"], "--ortho"),
        (&["--near", "x"], "--near"),
        (&["--crease", "200"], "--crease"),
        (&["--cull", "maybe"], "--cull"),
        (&["--mode", "solid"], "--mode"),
        (&["--engine", "phong"], "--engine"),
        (&["--scheme", "gray"], "--scheme"),
        (&["--scheme", "path", "--engine", "zbuffer"], "--scheme"),
        (&["--subpixel", "13"], "--subpixel"),
        (&["--depth-bits", "24"], "--depth-bits"),
        (&["--band", "0"], "--band"),
        (&["--band", "300"], "--band"),
        (&["--scale", "0"], "--scale"),
        (&["--pick", "400,0"], "--pick"),
        (&["--pick", "3"], "--pick"),
        (&["--look", "crt"], "--look"),
        (&["--pattern", "zigzag"], "--pattern"),
        (&["--out", "a.jpg"], "--out"),
        (&["--grey", "a.pgm"], "--grey"),
        (&["--out"], "--out"),
        (&["--frobnicate"], "--frobnicate"),
        (&["--stats=1"], "--stats"),
        (&["--fit", "--eye", "1,1,1"], "--fit"),
        (&["a.obj", "b.obj"], "b.obj"),
    ] {
        let e = p(args).unwrap_err();
        assert!(e.starts_with(flag) && !e.contains('\n'), "{args:?}: {e}");
    }
}

#[test]
fn degenerate_cameras() {
    let m = cube();
    for (args, flag) in [
        (&["--eye", "1,1,1", "--target", "1,1,1"][..], "--eye"),
        (&["--eye", "0,5,0"], "--up"),
        (&["--eye", "0,0,5", "--up", "0,0,0"], "--up"),
        (&["--eye", "0,0,5", "--near", "0"], "--near"),
        (&["--eye", "0,0,5", "--near", "2", "--far", "1"], "--far"),
        (&["--near", "-1"], "--near"),
    ] {
        let e = p(args).unwrap().camera(&m).unwrap_err();
        assert!(e.starts_with(flag), "{args:?}: {e}");
    }
}
