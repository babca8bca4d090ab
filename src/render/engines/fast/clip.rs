//! Clipping for the fast engine: polygons and segments cut to near..far in eye
//! space, then to the guard box on screen (where nearness is affine), in `f32`.
//! A cut point is always computed from the edge's inside end, so two faces that
//! share an edge get the very same point: shared edges stay watertight.

use heapless::Vec;

use super::view::{EyePoint, FastVertex, ScreenMap, ScreenPoint};
use crate::Capacity;
use crate::Error;

/// Most corners of a clipped polygon: a face of up to `CLIP_CORNERS - 6` corners
/// can be clipped (each of the six planes adds at most one).
pub(super) const CLIP_CORNERS: usize = 64;

type Poly<T> = Vec<T, CLIP_CORNERS>;

/// Keeps the part of `poly` where `inside(p)` holds; `cut(a, b)` is the point where
/// edge `a` (inside) to `b` (outside) leaves.
fn clip_by<T: Copy>(
    poly: &mut Poly<T>,
    inside: impl Fn(&T) -> bool,
    cut: impl Fn(&T, &T) -> T,
) -> Result<(), Error> {
    let Some(&last) = poly.last() else {
        return Ok(());
    };
    let mut out: Poly<T> = Vec::new();
    let mut prev = last;
    let full = Error::CapacityExceeded {
        what: Capacity::ClippedFaceCorners,
        needed: CLIP_CORNERS + 1,
        capacity: CLIP_CORNERS,
    };
    for &cur in poly.iter() {
        match (inside(&prev), inside(&cur)) {
            (true, true) => out.push(cur).map_err(|_| full)?,
            (true, false) => out.push(cut(&prev, &cur)).map_err(|_| full)?,
            (false, true) => {
                out.push(cut(&cur, &prev)).map_err(|_| full)?;
                out.push(cur).map_err(|_| full)?;
            }
            (false, false) => {}
        }
        prev = cur;
    }
    *poly = out;
    Ok(())
}

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + t * (b - a)
}

fn cut_eye(a: &EyePoint, b: &EyePoint, z: f32) -> EyePoint {
    let t = (z - a[2]) / (b[2] - a[2]);
    [lerp(a[0], b[0], t), lerp(a[1], b[1], t), z]
}

/// Which guard-box side: 0 x >= -L, 1 x <= L, 2 y >= -L, 3 y <= L.
fn in_box(p: &ScreenPoint, side: usize, l: f32) -> bool {
    match side {
        0 => p.x >= -l,
        1 => p.x <= l,
        2 => p.y >= -l,
        _ => p.y <= l,
    }
}

fn cut_box(a: &ScreenPoint, b: &ScreenPoint, side: usize, l: f32) -> ScreenPoint {
    let bound = if side % 2 == 0 { -l } else { l };
    let t = if side < 2 {
        (bound - a.x) / (b.x - a.x)
    } else {
        (bound - a.y) / (b.y - a.y)
    };
    let (x, y) = if side < 2 {
        (bound, lerp(a.y, b.y, t))
    } else {
        (lerp(a.x, b.x, t), bound)
    };
    ScreenPoint {
        x,
        y,
        q: lerp(a.q, b.q, t),
    }
}

/// The polygon with corners at world positions `corners`, clipped and snapped into
/// `out`; false when nothing of it is left.
pub(super) fn clip_polygon(
    map: &ScreenMap,
    corners: impl Iterator<Item = [f32; 3]>,
    out: &mut Poly<FastVertex>,
) -> Result<bool, Error> {
    out.clear();
    let mut eye: Poly<EyePoint> = Vec::new();
    for p in corners {
        eye.push(map.eye_space(p))
            .map_err(|_| Error::CapacityExceeded {
                what: Capacity::ClippedFaceCorners,
                needed: CLIP_CORNERS + 1,
                capacity: CLIP_CORNERS - 6,
            })?;
    }
    let (near, far) = (map.near, map.far);
    clip_by(&mut eye, |e| e[2] >= near, |a, b| cut_eye(a, b, near))?;
    clip_by(&mut eye, |e| e[2] <= far, |a, b| cut_eye(a, b, far))?;
    let mut screen: Poly<ScreenPoint> = Vec::new();
    for &e in &eye {
        // As many as `eye` holds: never full (and no panic path, unlike `collect`).
        screen
            .push(map.screen(e))
            .map_err(|_| Error::CapacityExceeded {
                what: Capacity::ClippedFaceCorners,
                needed: CLIP_CORNERS + 1,
                capacity: CLIP_CORNERS,
            })?;
    }
    let l = map.limit;
    for side in 0..4 {
        clip_by(
            &mut screen,
            |p| in_box(p, side, l),
            |a, b| cut_box(a, b, side, l),
        )?;
    }
    for p in &screen {
        let _ = out.push(map.snap(*p));
    }
    Ok(out.len() >= 3)
}

/// The segment between world positions `a` and `b`, clipped and snapped.
pub(super) fn clip_segment(
    map: &ScreenMap,
    a: [f32; 3],
    b: [f32; 3],
) -> Option<(FastVertex, FastVertex)> {
    let (mut ea, mut eb) = (map.eye_space(a), map.eye_space(b));
    for (z, keep_above) in [(map.near, true), (map.far, false)] {
        let ina = (ea[2] >= z) == keep_above;
        let inb = (eb[2] >= z) == keep_above;
        match (ina, inb) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => eb = cut_eye(&ea, &eb, z),
            (false, true) => ea = cut_eye(&eb, &ea, z),
        }
    }
    let (mut sa, mut sb) = (map.screen(ea), map.screen(eb));
    let l = map.limit;
    for side in 0..4 {
        match (in_box(&sa, side, l), in_box(&sb, side, l)) {
            (true, true) => {}
            (false, false) => return None,
            (true, false) => sb = cut_box(&sa, &sb, side, l),
            (false, true) => sa = cut_box(&sb, &sa, side, l),
        }
    }
    Some((map.snap(sa), map.snap(sb)))
}
