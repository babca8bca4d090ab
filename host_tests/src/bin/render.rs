//! `render`: draws a Wavefront OBJ model, or a `.scene` of posed parts
//! (`host_tests::posed`), as a line drawing with dashed hidden lines (or
//! the other modes) through the library's 3-D pipeline
//! (`host_tests::pipeline::render_frame`), and writes the picture and the
//! machine-readable outputs of ../shared/CONVENTIONS.md.
//!
//! ```text
//! cargo run --release -p host_tests --bin render -- [SCENE.obj] [flags]   (--help lists them)
//! ```
//!
//! Without SCENE it renders the repository's `models/suzanne.obj` (found from the
//! workspace root) to `target/render.png` (outside the tracked tree), and prints the
//! figures of the frame; a missing default model is an error (exit 2), as any file.
//!
//! Exit status: 0 on success; 2 on bad input (unreadable file, malformed OBJ, bad flag
//! or value, a camera or mesh the library rejects), with one line on stderr that names
//! the file and line or the flag; 1 when the library returns a malformed frame. A panic
//! is caught by a hook that prints one line and exits with 2.

use std::io::Write as _;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use host_tests::frame::{CameraSpec, Frame, MeshData};
use host_tests::grey::{render_grey, shades};
use host_tests::image::Look;
use host_tests::image::{fnv1a64, packed_pixel, packed_stride, write_rgb_png};
use host_tests::obj::{load_scene, workspace_root};
use host_tests::pipeline::render_frame;
use host_tests::posed::{load_scene_file, render_scene, union, union_obj, Part};
use host_tests::schemes::{render_scheme, SchemeError, SchemeSpec};
use host_tests::tools::cli::{help, parse_args, Options};

/// An error to report: the line to print and the exit status.
struct Fail(String, u8);

fn bad(msg: impl Into<String>) -> Fail {
    Fail(msg.into(), 2)
}

/// Every output's directory must exist: a missing one is a typo far more often than a
/// wish, so it is refused (exit 2, naming it) before anything is rendered, not created.
fn check_output_dirs(o: &Options) -> Result<(), Fail> {
    let outputs = [
        ("--out", &o.out),
        ("--ids", &o.ids),
        ("--lines", &o.lines),
        ("--grey", &o.grey),
        ("--dump-obj", &o.dump_obj),
    ];
    for (flag, path) in outputs {
        let Some(dir) = path.as_deref().and_then(Path::parent) else {
            continue;
        };
        if !dir.as_os_str().is_empty() && !dir.is_dir() {
            return Err(bad(format!(
                "{flag}: directory {} does not exist",
                dir.display()
            )));
        }
    }
    Ok(())
}

fn write_file(flag: &str, path: &Path, bytes: &[u8]) -> Result<(), Fail> {
    let io = || -> std::io::Result<()> {
        let mut f = std::fs::File::create(path)?;
        f.write_all(bytes)?;
        f.flush()
    };
    io().map_err(|e| bad(format!("{flag}: cannot write {}: {e}", path.display())))
}

/// `--ids`: P5, maxval 65535, big-endian 16-bit samples.
fn ids_pgm(frame: &Frame) -> Result<Vec<u8>, Fail> {
    let mut out = format!("P5\n{} {}\n65535\n", frame.width, frame.height).into_bytes();
    out.reserve(frame.ids.len() * 2);
    for &id in &frame.ids {
        let v = u16::try_from(id).map_err(|_| {
            Fail(
                format!("internal error: face id sample {id} does not fit 16 bits"),
                1,
            )
        })?;
        out.extend_from_slice(&v.to_be_bytes());
    }
    Ok(out)
}

/// `--lines`: P5, maxval 255, one byte per pixel (0, 1 or 2).
fn lines_pgm(frame: &Frame) -> Vec<u8> {
    let mut out = format!("P5\n{} {}\n255\n", frame.width, frame.height).into_bytes();
    out.extend_from_slice(&frame.lines);
    out
}

fn mix(a: [u8; 3], b: [u8; 3], t: f32) -> [u8; 3] {
    std::array::from_fn(|k| (f32::from(a[k]) * (1.0 - t) + f32::from(b[k]) * t).round() as u8)
}

/// The picture as the display would show it: each frame pixel a `scale x scale` block;
/// from scale 3 up (not for `paper`) the last row and column of each block are a shade
/// towards the glass colour, a faint pixel grid that keeps lines continuous.
fn write_png(o: &Options, path: &Path, frame: &Frame) -> Result<(), Fail> {
    let (w, h, s) = (frame.width, frame.height, o.scale);
    let (off, on) = o.look.colours();
    let grid = s >= 3 && o.look != Look::Paper;
    let (on_edge, off_edge) = (mix(on, off, 0.3), mix(off, [0, 0, 0], 0.06));
    let mut rgb = Vec::with_capacity(w * s * h * s * 3);
    for y in 0..h {
        for sy in 0..s {
            for x in 0..w {
                let lit = packed_pixel(&frame.packed, w, x, y);
                for sx in 0..s {
                    let edge = grid && (sx == s - 1 || sy == s - 1);
                    rgb.extend_from_slice(&match (lit, edge) {
                        (true, false) => on,
                        (true, true) => on_edge,
                        (false, false) => off,
                        (false, true) => off_edge,
                    });
                }
            }
        }
    }
    write_rgb_png(path, &rgb, w * s, h * s, 1)
        .map_err(|e| bad(format!("--out: cannot write {}: {e}", path.display())))
}

/// `--grey`: the frame rendered again with anti-aliased face edges
/// (`host_tests::grey`), each pixel a `scale x scale` block of grey.
fn write_grey(o: &Options, path: &Path, mesh: &MeshData, camera: &CameraSpec) -> Result<(), Fail> {
    // Every error names its flag (`--help`).
    let frame =
        render_grey(mesh, camera, &o.spec, &shades()).map_err(|e| bad(format!("--grey: {e}")))?;
    let (w, h, s) = (frame.width, frame.height, o.scale);
    let mut rgb = Vec::with_capacity(w * s * h * s * 3);
    for y in 0..h {
        for _ in 0..s {
            for x in 0..w {
                let g = frame.grey[y * w + x];
                for _ in 0..s {
                    rgb.extend_from_slice(&[g, g, g]);
                }
            }
        }
    }
    write_rgb_png(path, &rgb, w * s, h * s, 1)
        .map_err(|e| bad(format!("--grey: cannot write {}: {e}", path.display())))
}

fn run() -> Result<(), Fail> {
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let o = parse_args(&args).map_err(bad)?;
    if o.help {
        print!("{}", help());
        return Ok(());
    }
    check_output_dirs(&o)?;

    // The scene: one model, or posed parts whose union the frame means.
    let is_parts = o
        .scene
        .as_deref()
        .is_some_and(|p| p.extension().is_some_and(|e| e == "scene"));
    let (parts, mesh, scene_name) = match o.scene.as_deref() {
        Some(p) if is_parts => {
            let parts = load_scene_file(p).map_err(bad)?;
            let mesh = union(&parts);
            (Some(parts), mesh, p.display().to_string())
        }
        other => {
            let (mesh, name) = load_scene(other).map_err(bad)?;
            (None, mesh, name)
        }
    };
    if let Some(p) = &o.dump_obj {
        let parts = parts.clone().unwrap_or_else(|| {
            vec![Part {
                mesh: mesh.clone(),
                pose: pbuffer::Pose::IDENTITY,
            }]
        });
        write_file("--dump-obj", p, union_obj(&parts).as_bytes())?;
    }
    if o.ids.is_some() && mesh.faces.len() > 65_535 {
        return Err(bad(format!(
            "--ids: {scene_name} has {} faces; a 16-bit id image holds at most 65535",
            mesh.faces.len()
        )));
    }
    let camera = o.camera(&mesh).map_err(bad)?;

    // The frame.
    let t = Instant::now();
    let frame = if o.scheme == SchemeSpec::Priority {
        let drawn = match &parts {
            // The default engine draws the parts through the library's scene.
            Some(parts) => render_scene(parts, &camera, &o.spec),
            None => render_frame(&mesh, &camera, &o.spec),
        };
        drawn.map_err(|e| {
            // A depth sort that cannot settle is a rendering failure of valid input
            // (exit 1); the pipeline's other errors are about the input (exit 2).
            let msg = format!("{scene_name}: {e}");
            if e.contains("did not settle") {
                Fail(msg, 1)
            } else {
                bad(msg)
            }
        })?
    } else {
        // A scheme the view cannot have (the named condition) is a rendering failure.
        let (frame, _) = render_scheme(&mesh, &camera, &o.spec, o.scheme).map_err(|e| match e {
            SchemeError::Library(e) => Fail(
                format!("{scene_name}: --scheme {}: {e}", o.scheme.name()),
                1,
            ),
            SchemeError::Host(e) => bad(format!("{scene_name}: {e}")),
        })?;
        frame
    };
    let time_us = t.elapsed().as_micros();
    let (w, h) = (o.spec.width, o.spec.height);
    if frame.width != w
        || frame.height != h
        || frame.ids.len() != w * h
        || frame.lines.len() != w * h
        || frame.packed.len() != packed_stride(w) * h
    {
        return Err(Fail(
            format!(
                "internal error: the library returned a malformed {}x{} frame (ids {}, lines {}, packed {} bytes) for {w}x{h}",
                frame.width,
                frame.height,
                frame.ids.len(),
                frame.lines.len(),
                frame.packed.len()
            ),
            1,
        ));
    }

    // Outputs.
    let out = match (&o.out, &o.scene) {
        (Some(p), _) => Some(p.clone()),
        (None, None) => Some(workspace_root().join("target").join("render.png")),
        (None, Some(_)) => None,
    };
    if let Some(p) = &out {
        write_png(&o, p, &frame)?;
    }
    if let Some(p) = &o.ids {
        write_file("--ids", p, &ids_pgm(&frame)?)?;
    }
    if let Some(p) = &o.lines {
        write_file("--lines", p, &lines_pgm(&frame))?;
    }
    if let Some(p) = &o.grey {
        write_grey(&o, p, &mesh, &camera)?;
    }
    let mut text = String::new();
    if o.hash {
        text += &format!("hash: {:016x}\n", fnv1a64(&frame.packed));
    }
    if let Some((x, y)) = o.pick {
        let picked = host_tests::pick::pick_pixels(&mesh, &camera, &o.spec, &[(x, y)])
            .map_err(|e| bad(format!("{scene_name}: {e}")))?;
        for p in &picked {
            text += &format!("pick: {},{}\n", p.x, p.y);
            match p.pick.face {
                Some(f) => text += &format!("pick_face: {f}\n"),
                None => text += "pick_face: none\n",
            }
            for ((pe, _), [a, b]) in p.edges.iter().zip(&p.ends) {
                text += &format!("pick_edge: {a} {b} in_front {}\n", pe.faces_in_front);
            }
        }
    }
    let asked_other = o.hash
        || o.out.is_some()
        || o.ids.is_some()
        || o.lines.is_some()
        || o.pick.is_some()
        || o.grey.is_some()
        || o.dump_obj.is_some();
    if o.stats || !asked_other {
        text += &format!("scene: {scene_name}\n");
        text += &format!("size: {w}x{h}\n");
        if !frame.stats.iter().any(|(k, _)| k == "faces") {
            text += &format!("faces: {}\n", mesh.faces.len());
        }
        for (k, v) in &frame.stats {
            text += &format!("{k}: {v}\n");
        }
        if frame.depth_step != [0.0; 2] {
            let [near, far] = frame.depth_step;
            text += &format!("depth_step_near: {near:.3e}\ndepth_step_far: {far:.3e}\n");
        }
        // The library's own `time_us` (the render call proper) when it reports one;
        // `call_time_us` is the whole `render_frame` call (mesh set-up included).
        if !frame.stats.iter().any(|(k, _)| k == "time_us") {
            text += &format!("time_us: {time_us}\n");
        }
        text += &format!("call_time_us: {time_us}\n");
        if let Some(p) = &out {
            text += &format!("wrote: {}\n", p.display());
        }
    }
    let mut stdout = std::io::stdout().lock();
    // A closed pipe (`render --stats | head -1`) is not an error worth a message.
    let _ = stdout.write_all(text.as_bytes());
    let _ = stdout.flush();
    Ok(())
}

fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        let first = msg.lines().next().unwrap_or("");
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!("render: internal error: {first}{at}");
        std::process::exit(2);
    }));
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(Fail(msg, code)) => {
            eprintln!("render: {msg}");
            ExitCode::from(code)
        }
    }
}
