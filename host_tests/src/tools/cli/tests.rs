//! Unit tests of the flags: defaults, values, errors, cameras, help; `report`'s and
//! `bench`'s flags.

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

/// The exact one-line messages of the cases clap reports (not our value parsers).
#[test]
fn clap_errors_are_our_one_liners() {
    for (args, want) in [
        (
            &["--frobnicate"][..],
            "--frobnicate: unknown flag (see --help)",
        ),
        (
            &["--frobnicate=3"],
            "--frobnicate: unknown flag (see --help)",
        ),
        (
            &["--fitt"],
            "--fitt: unknown flag (did you mean --fit? see --help)",
        ),
        (&["--out"], "--out: needs a value"),
        (&["--size="], "--size: needs a value"),
        (&["--stats=1"], "--stats: takes no value"),
        (&["--help=yes"], "--help: takes no value"),
        (&["--fov", "inf"], "--fov: `inf` is not a finite number"),
        (&["--fov=180"], "--fov: 180 is not in (0, 180) degrees"),
        (
            &["--size", "abc"],
            "--size: `abc` is not WxH with W and H in 1..=8192",
        ),
        (
            &["--eye", "1,nan,2"],
            "--eye: `1,nan,2` is not X,Y,Z (`nan` is not a finite number)",
        ),
        (&["--near", "nan"], "--near: `nan` is not a finite number"),
        (
            &["a.obj", "b.obj"],
            "b.obj: a second scene (already have a.obj); one SCENE.obj at most",
        ),
    ] {
        assert_eq!(p(args).unwrap_err(), want, "{args:?}");
    }
}

#[test]
fn values_after_the_flag_or_an_equals_sign() {
    // A value may start with `-` (it is taken as the value, as before).
    let o = p(&["--eye", "-1,2,-3", "--target=0,-0.5,0"]).unwrap();
    assert_eq!(o.eye, Some([-1.0, 2.0, -3.0]));
    assert_eq!(o.target, Some([0.0, -0.5, 0.0]));
    assert_eq!(
        p(&["--out", "-x.png"]).unwrap().out,
        Some(PathBuf::from("-x.png"))
    );
    // `--` ends the flags; `-` is a scene name.
    assert_eq!(
        p(&["--", "--stats"]).unwrap().scene,
        Some(PathBuf::from("--stats"))
    );
    assert_eq!(p(&["-"]).unwrap().scene, Some(PathBuf::from("-")));
    assert!(p(&["-h"]).unwrap().help && p(&["--help"]).unwrap().help);
}

#[test]
fn a_repeated_flag_overrides_the_earlier_one() {
    let o = p(&["--size", "10x10", "--size=20x30", "--stats", "--stats"]).unwrap();
    assert_eq!((o.spec.width, o.spec.height, o.spec.band), (20, 30, 30));
    // --fov and --ortho set one projection: the last given wins.
    let proj = |args: &[&str]| p(args).unwrap().projection;
    assert_eq!(
        proj(&["--fov", "60", "--ortho", "2"]),
        Some(ProjectionSpec::Orthographic { half_height: 2.0 })
    );
    assert_eq!(
        proj(&["--ortho", "2", "--fov", "60"]),
        Some(ProjectionSpec::Perspective { fov_deg: 60.0 })
    );
}

#[test]
fn help_describes_every_flag() {
    use clap::CommandFactory as _;
    Flags::command().debug_assert();
    let text = help();
    for arg in Flags::command()
        .get_arguments()
        .filter(|a| !a.is_hide_set())
    {
        if let Some(long) = arg.get_long() {
            let line = text
                .lines()
                .find(|l| {
                    l.trim_start().starts_with(&format!("--{long}"))
                        || l.contains(&format!(" --{long}"))
                })
                .unwrap_or_else(|| panic!("--{long} not in the help"));
            assert!(
                line.split_whitespace().count() > 2,
                "--{long} undescribed: {line}"
            );
        }
    }
    assert!(text.contains("exit status: 0 ok, 2 bad input"));
}

#[test]
fn report_flags() {
    use clap::CommandFactory as _;
    ReportFlags::command().debug_assert();
    let r = |args: &[&str]| parse_flags::<ReportFlags, _, _>("report", args);
    let d = r(&[]).unwrap();
    assert!(!d.is_engines() && !d.quick && d.counts() && d.jobs == 2);
    assert!(d.out_dir().ends_with("report"));
    let q = r(&["--quick", "engines", "--jobs", "1", "--no-counts"]).unwrap();
    assert!(q.is_engines() && q.quick && !q.counts() && q.jobs == 1);
    assert!(q.out_dir().ends_with("target/report-quick"));
    assert_eq!(r(&["--out=x"]).unwrap().out_dir(), PathBuf::from("x"));
    for (args, want) in [
        (
            &["--jobs", "two"][..],
            "--jobs: `two` is not a whole number",
        ),
        (&["--jobs"], "--jobs: needs a value"),
        (
            &["--quik"],
            "--quik: unknown flag (did you mean --quick? see --help)",
        ),
        (
            &["engine"],
            "engine: unknown argument: neither a flag nor `engines` (see --help)",
        ),
    ] {
        assert_eq!(r(args).unwrap_err(), want, "{args:?}");
    }
    assert!(help_text::<ReportFlags>().contains("--no-counts"));
}

#[test]
fn bench_flags() {
    use clap::CommandFactory as _;
    BenchFlags::command().debug_assert();
    let b = |args: &[&str]| parse_flags::<BenchFlags, _, _>("bench", args);
    let d = b(&[]).unwrap();
    assert!(!d.markdown && !d.scene3d && !d.ram && !d.firmware);
    assert_eq!((d.m4, d.jobs), (None, None));
    let f = b(&["--firmware", "--m4", "m4.txt", "--jobs=3", "--markdown"]).unwrap();
    assert!(f.firmware && f.markdown);
    assert_eq!((f.m4.as_deref(), f.jobs), (Some("m4.txt"), Some(3)));
    assert!(
        b(&["--scene3d", "--ram"]).is_ok(),
        "the run picks one, as before"
    );
    for (args, want) in [
        (&["--m4"][..], "--m4: needs a value"),
        (&["--jobs", "-1"], "--jobs: `-1` is not a whole number"),
        (
            &["--scene"],
            "--scene: unknown flag (did you mean --scene3d? see --help)",
        ),
    ] {
        assert_eq!(b(args).unwrap_err(), want, "{args:?}");
    }
    assert!(help_text::<BenchFlags>().contains("--firmware"));
}
