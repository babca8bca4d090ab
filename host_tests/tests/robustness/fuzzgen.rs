//! Generators and oracles of the fuzz / property tests (`fuzz_*.rs`): hostile numbers
//! (NaN, infinities, 1e35, i32 extremes, subnormals), meshes with repeated and
//! out-of-range indices and degenerate faces, degenerate cameras, each with the
//! precise error the library documents for it. Seeded and deterministic.
#![allow(dead_code)] // each fuzz file uses a different subset

use std::convert::Infallible;

use embedded_graphics::pixelcolor::BinaryColor;
use host_tests::random::Rng;
use pbuffer::{CameraProblem, Error, Projection, Span, SpanSink, Viewport};

/// A hostile `f32`: specials one time in four, otherwise ordinary or huge/tiny.
pub fn wild(rng: &mut Rng) -> f32 {
    match rng.below(24) {
        0 => f32::NAN,
        1 => f32::INFINITY,
        2 => f32::NEG_INFINITY,
        3 => 1e35,
        4 => -1e35,
        5 => i32::MAX as f32,
        6 => i32::MIN as f32,
        7 => f32::MIN_POSITIVE / 4.0, // subnormal
        8 => 0.0,
        9 => -0.0,
        10 => rng.range(-1e6, 1e6) as f32,
        11 => rng.range(-1e-4, 1e-4) as f32,
        _ => rng.range(-3.0, 3.0) as f32,
    }
}

/// A finite coordinate: mostly a scene of size ~2, sometimes far-flung or extreme.
pub fn finite(rng: &mut Rng) -> f32 {
    loop {
        let v = wild(rng);
        if v.is_finite() {
            return v;
        }
    }
}

/// A mesh as the library takes it, and the error `Mesh::new` must give (None: valid).
#[derive(Clone, Debug)]
pub struct RawMesh {
    pub vertices: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
    pub offsets: Vec<u32>,
    pub expected: Option<Error>,
}

/// `bad`: the chance of each kind of invalid input (non-finite vertex, short face,
/// out-of-range index, bad offsets, no faces).
pub fn raw_mesh(rng: &mut Rng, bad: f64, coordinate: fn(&mut Rng) -> f32) -> RawMesh {
    let n = 1 + rng.below(12) as usize;
    let vertices: Vec<[f32; 3]> = (0..n)
        .map(|_| {
            let mut v = [coordinate(rng), coordinate(rng), coordinate(rng)];
            if rng.chance(bad / 4.0) {
                v[rng.below(3) as usize] =
                    [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][rng.below(3) as usize];
            }
            v
        })
        .collect();
    let faces = if rng.chance(bad / 8.0) {
        0
    } else {
        1 + rng.below(8) as usize
    };
    let (mut indices, mut offsets) = (Vec::new(), vec![0u32]);
    for _ in 0..faces {
        let len = if rng.chance(bad / 4.0) {
            rng.below(3) as usize
        } else {
            3 + rng.below(6) as usize
        };
        for _ in 0..len {
            let i = match rng.below(40) {
                // Repeated: the previous index again (a zero-length edge).
                0..=2 if !indices.is_empty() => *indices.last().unwrap_or(&0),
                3 if rng.chance(bad) => n as u32 + rng.below(3) as u32,
                4 if rng.chance(bad) => u32::MAX,
                _ => rng.below(n as u64) as u32,
            };
            indices.push(i);
        }
        offsets.push(indices.len() as u32);
    }
    let mut corrupt = false;
    if faces > 0 && rng.chance(bad / 8.0) {
        *offsets.last_mut().expect("offsets") += 1;
        corrupt = true;
    }
    let expected = if corrupt {
        Some(Error::BadFaceOffsets { face: faces - 1 })
    } else if faces == 0 {
        Some(Error::EmptyMesh)
    } else if let Some(vertex) = vertices
        .iter()
        .position(|v| v.iter().any(|c| !c.is_finite()))
    {
        Some(Error::NonFiniteVertex { vertex })
    } else {
        (0..faces).find_map(|face| {
            let f = &indices[offsets[face] as usize..offsets[face + 1] as usize];
            if f.len() < 3 {
                Some(Error::DegenerateFace { face })
            } else {
                f.iter()
                    .find(|&&i| i as usize >= n)
                    .map(|&index| Error::IndexOutOfRange { face, index })
            }
        })
    };
    RawMesh {
        vertices,
        indices,
        offsets,
        expected,
    }
}

/// Camera parameters and the error `Camera::new` must give (None: valid).
#[derive(Clone, Copy, Debug)]
pub struct RawCamera {
    pub eye: [f32; 3],
    pub target: [f32; 3],
    pub up: [f32; 3],
    pub projection: Projection,
    pub near: f32,
    pub far: f32,
    pub expected: Option<Error>,
}

/// A camera: usually valid, with each degeneracy of CONVENTIONS.md now and then
/// (eye = target, up zero or an exact multiple of an axis-aligned view, fov outside
/// (0, 180), half-height <= 0, near <= 0, far <= near, non-finite values).
pub fn raw_camera(rng: &mut Rng, bad: f64) -> RawCamera {
    let point = |rng: &mut Rng| {
        let mut p = [0f32; 3];
        for c in &mut p {
            *c = if rng.chance(0.1) {
                wild(rng)
            } else {
                rng.range(-8.0, 8.0) as f32
            };
        }
        p
    };
    let eye = point(rng);
    let mut target = point(rng);
    let mut up = [0.0, 1.0, 0.0];
    if rng.chance(0.3) {
        up = point(rng);
    }
    match rng.below(8) {
        0 if rng.chance(bad) => target = eye,
        1 if rng.chance(bad) => {
            // Axis-aligned view with up along it (exactly parallel in f32).
            let axis = rng.below(3) as usize;
            target = eye;
            target[axis] += 4.0;
            up = [0.0; 3];
            up[axis] = if rng.chance(0.5) { -2.5 } else { 0.5 };
        }
        2 if rng.chance(bad) => up = [0.0; 3],
        _ => {}
    }
    let projection = if rng.chance(0.3) {
        let h = if rng.chance(bad) {
            [0.0, -1.0, f32::NAN][rng.below(3) as usize]
        } else {
            rng.log_uniform(1e-3, 1e3) as f32
        };
        Projection::Orthographic { half_height: h }
    } else {
        let fov = if rng.chance(bad) {
            [0.0, 180.0, -10.0, 400.0, f32::INFINITY][rng.below(5) as usize]
        } else {
            rng.range(1.0, 179.0) as f32
        };
        Projection::Perspective { fov_y_deg: fov }
    };
    let mut near = rng.log_uniform(1e-4, 10.0) as f32;
    let mut far = near * rng.log_uniform(1.001, 1e6) as f32;
    if rng.chance(bad / 2.0) {
        near = [0.0, -1.0, f32::NAN][rng.below(3) as usize];
    }
    if rng.chance(bad / 2.0) {
        far = [near, near * 0.5, f32::INFINITY][rng.below(3) as usize];
    }
    let param = match projection {
        Projection::Perspective { fov_y_deg } => fov_y_deg,
        Projection::Orthographic { half_height } => half_height,
    };
    let all = eye
        .iter()
        .chain(&target)
        .chain(&up)
        .chain([&param, &near, &far]);
    let d = [0, 1, 2].map(|i| f64::from(target[i]) - f64::from(eye[i]));
    let u = up.map(f64::from);
    let cross = [
        d[1] * u[2] - d[2] * u[1],
        d[2] * u[0] - d[0] * u[2],
        d[0] * u[1] - d[1] * u[0],
    ];
    let problem = if !all.into_iter().all(|v| v.is_finite()) {
        Some(CameraProblem::NonFinite)
    } else if matches!(projection, Projection::Perspective { fov_y_deg } if !(fov_y_deg > 0.0 && fov_y_deg < 180.0))
    {
        Some(CameraProblem::FovOutOfRange)
    } else if matches!(projection, Projection::Orthographic { half_height } if half_height <= 0.0) {
        Some(CameraProblem::HalfHeightNotPositive)
    } else if near <= 0.0 {
        Some(CameraProblem::NearNotPositive)
    } else if far <= near {
        Some(CameraProblem::FarNotBeyondNear)
    } else if d == [0.0; 3] {
        Some(CameraProblem::EyeAtTarget)
    } else if cross == [0.0; 3] {
        Some(CameraProblem::UpParallelToView)
    } else {
        None
    };
    RawCamera {
        eye,
        target,
        up,
        projection,
        near,
        far,
        expected: problem.map(Error::BadCamera),
    }
}

/// A span sink that records, instead of drawing, every span outside its viewport
/// (and empty or reversed spans) as a failure, and counts the pixels written.
pub struct Recorder {
    pub viewport: Viewport,
    pub outside: Vec<(u16, u16, u16)>,
    pub pixels: u64,
}

impl Recorder {
    pub fn new(width: u16, height: u16) -> Self {
        Self {
            viewport: Viewport { width, height },
            outside: Vec::new(),
            pixels: 0,
        }
    }
}

impl SpanSink for Recorder {
    type Color = BinaryColor;
    type Error = Infallible;
    fn viewport(&self) -> Viewport {
        self.viewport
    }
    fn fill_span(&mut self, span: Span, _: BinaryColor) -> Result<(), Infallible> {
        if span.x0() < span.x1()
            && span.x1() <= self.viewport.width
            && span.y() < self.viewport.height
        {
            self.pixels += u64::from(span.x1() - span.x0());
        } else {
            self.outside.push((span.x0(), span.x1(), span.y()));
        }
        Ok(())
    }
}

/// The message of a caught panic.
pub fn panic_message(e: &(dyn std::any::Any + Send)) -> String {
    e.downcast_ref::<String>()
        .cloned()
        .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}
