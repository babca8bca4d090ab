//! Scenes of posed parts on the host: the `render` command's `.scene` files, the
//! union mesh that defines a scene's frame (`pbuffer::scene`), and a scene drawn
//! by the library's `SceneDrawing` as firmware draws it.
//!
//! A scene file is UTF-8 text, one part a line: `PATH [tx ty tz [rx ry rz]]`, the
//! path relative to the scene file, the rotation in degrees about the part's own
//! origin (x, then y, then z; `pbuffer::Pose::from_degrees`), then the
//! translation. `#` starts a comment; blank lines are skipped. Errors are one line,
//! `FILE:LINE: what is wrong`.

use std::path::Path;

use pbuffer::render::BakedMesh;
use pbuffer::{FrameRows, Pose, SceneDrawing};

use crate::fast::Baked;
use crate::frame::{CameraSpec, EngineSpec, Frame, MeshData, RenderSpec};
use crate::setup::{with_parts, Measured, PartSize, SceneStorage};

/// One part of a scene: its mesh (as read, in its own space) and its pose.
#[derive(Debug, Clone)]
pub struct Part {
    pub mesh: MeshData,
    pub pose: Pose,
}

/// Reads a scene file: each part's OBJ loaded relative to the file's directory.
pub fn load_scene_file(path: &Path) -> Result<Vec<Part>, String> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}:-: cannot read: {e}"))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    parse_scene(&text, &name, |part| crate::obj::load_obj(&dir.join(part)))
}

/// Parses scene text (`file_name` for messages), loading each part with `load`.
pub fn parse_scene(
    text: &str,
    file_name: &str,
    mut load: impl FnMut(&str) -> Result<MeshData, String>,
) -> Result<Vec<Part>, String> {
    let mut parts = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let at = |what: String| format!("{file_name}:{}: {what}", i + 1);
        let words: Vec<&str> = line
            .split('#')
            .next()
            .unwrap_or("")
            .split_whitespace()
            .collect();
        let Some((&path, numbers)) = words.split_first() else {
            continue;
        };
        if !matches!(numbers.len(), 0 | 3 | 6) {
            return Err(at(format!(
                "expected `PATH [tx ty tz [rx ry rz]]`, found {} numbers after the path",
                numbers.len()
            )));
        }
        let mut values = [0.0f32; 6];
        for (slot, word) in values.iter_mut().zip(numbers) {
            *slot = match word.parse::<f32>() {
                Ok(v) if v.is_finite() => v,
                _ => return Err(at(format!("`{word}` is not a finite number"))),
            };
        }
        let mesh = load(path).map_err(|e| at(format!("part {path}: {e}")))?;
        let [tx, ty, tz, rx, ry, rz] = values;
        parts.push(Part {
            mesh,
            pose: Pose::from_degrees([rx, ry, rz], [tx, ty, tz]),
        });
    }
    if parts.is_empty() {
        return Err(format!("{file_name}:-: no parts"));
    }
    Ok(parts)
}

/// The union mesh of `parts`: every part's vertices posed (`Pose::apply` on the
/// `f32` positions the library draws), faces in part order. What a scene's frame
/// means, and what `--dump-obj` writes.
pub fn union(parts: &[Part]) -> MeshData {
    let mut out = MeshData {
        vertices: Vec::new(),
        faces: Vec::new(),
    };
    for part in parts {
        let base = out.vertices.len() as u32;
        for v in &part.mesh.vertices {
            let posed = part.pose.apply(v.map(|c| c as f32));
            out.vertices.push(posed.map(f64::from));
        }
        for f in &part.mesh.faces {
            out.faces.push(f.iter().map(|&i| i + base).collect());
        }
    }
    out
}

/// The union as OBJ text: each coordinate the shortest decimal of its `f64`
/// (the posed `f32`, exactly), so reading it back gives the same bits.
pub fn union_obj(parts: &[Part]) -> String {
    let mesh = union(parts);
    let mut text =
        String::from("# The posed union of a scene: world space, faces in part order.\n");
    for v in &mesh.vertices {
        text += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in &mesh.faces {
        let corners: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        text += &format!("f {}\n", corners.join(" "));
    }
    text
}

/// Draws `parts` seen by `cam`: the default engine (fast, S = 4, dashes by the
/// screen pattern) through the library's `SceneDrawing`; every other engine, and
/// dashes along the edges, through the union mesh (what the frame means), its edges
/// made part by part as the library's are (`setup::with_parts`: vertices of two
/// parts that coincide bit for bit do not weld).
pub fn render_scene(parts: &[Part], cam: &CameraSpec, spec: &RenderSpec) -> Result<Frame, String> {
    let library = spec.engine == EngineSpec::Fast
        && spec.subpixel == 4
        && spec.dashes == pbuffer::Dashes::Screen;
    if !library {
        let sizes: Vec<PartSize> = parts
            .iter()
            .map(|p| PartSize {
                vertices: p.mesh.vertices.len(),
                faces: p.mesh.faces.len(),
            })
            .collect();
        let mesh = union(parts);
        return with_parts(&sizes, || crate::pipeline::render_frame(&mesh, cam, spec));
    }
    // Room for large scenes: several megabytes, on the heap of a thread whose
    // stack can hold the drawing while it is made.
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(256 << 20)
            .spawn_scoped(s, || render_scene_fast(parts, cam, spec))
            .map_err(|e| format!("cannot start the scene's thread: {e}"))?
            .join()
            .map_err(|_| "the scene's thread panicked".to_string())?
    })
}

/// Room of the host's scenes.
const N: usize = 256;
const V: usize = 65_535;
const F: usize = 65_535;
const E: usize = 65_535;
const C: usize = 400_000;
const ROWS: usize = 2048;
const FACETS: usize = crate::fast::FACETS;
const LINES: usize = crate::fast::LINES;

type HostScene<'m> = SceneDrawing<'m, N, V, F, E, C, FACETS, LINES>;

fn render_scene_fast(parts: &[Part], cam: &CameraSpec, spec: &RenderSpec) -> Result<Frame, String> {
    let mut storages: Vec<SceneStorage> =
        parts.iter().map(|p| SceneStorage::new(&p.mesh)).collect();
    let mut inputs = Vec::new();
    for storage in &mut storages {
        inputs.push(storage.scene(cam, spec)?);
    }
    let baked: Vec<Baked> = inputs.iter().map(Baked::new).collect::<Result<_, _>>()?;
    let mut scene: Box<HostScene<'_>> = Box::new(SceneDrawing::new());
    for ((one, b), part) in inputs.iter().zip(&baked).zip(parts) {
        let mesh = BakedMesh::new(one.mesh, &b.planes, &b.edges)
            .map_err(|e| format!("baked mesh: {e}"))?;
        scene
            .add(mesh, part.pose)
            .map_err(|e| format!("scene: {e}"))?;
    }
    let first = inputs.first().ok_or("a scene needs a part")?;
    let camera = first.camera;
    scene.settings = first.settings;
    let mut rows: Box<FrameRows<ROWS, ROWS>> = Box::new(FrameRows::new());
    let (w, h) = (spec.width, spec.height);
    let mut ids = vec![0u16; w];
    let measured = Measured::run(w, h, |target, probe| {
        scene.draw_spans(&camera, &mut rows, target, probe, &mut ids)
    })?;
    Ok(measured.frame(0, 0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle(_: &str) -> Result<MeshData, String> {
        Ok(MeshData {
            vertices: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            faces: vec![vec![0, 1, 2]],
        })
    }

    #[test]
    fn a_part_line_is_a_path_then_three_or_six_numbers() {
        let text = "# two parts\na.obj\n\nb.obj 1 2 3 0 0 90  # turned\n";
        let parts = parse_scene(text, "s.scene", triangle).unwrap();
        assert_eq!(parts.len(), 2);
        assert_eq!(parts[0].pose, Pose::IDENTITY);
        assert_eq!(parts[1].pose.apply([1.0, 0.0, 0.0]), [1.0, 3.0, 3.0]);
        let union = union(&parts);
        assert_eq!(union.faces, vec![vec![0, 1, 2], vec![3, 4, 5]]);
    }

    #[test]
    fn a_bad_line_is_refused_naming_file_and_line() {
        let e = parse_scene("a.obj\na.obj 1 2\n", "s.scene", triangle).unwrap_err();
        assert!(e.starts_with("s.scene:2: expected `PATH"), "{e}");
        let e = parse_scene("a.obj 1 2 nan\n", "s.scene", triangle).unwrap_err();
        assert_eq!(e, "s.scene:1: `nan` is not a finite number");
        let missing = |p: &str| Err(format!("{p}:-: cannot read"));
        let e = parse_scene("\n\nx.obj\n", "s.scene", missing).unwrap_err();
        assert_eq!(e, "s.scene:3: part x.obj: x.obj:-: cannot read");
        assert_eq!(
            parse_scene("# none\n", "s.scene", triangle).unwrap_err(),
            "s.scene:-: no parts"
        );
    }
}
