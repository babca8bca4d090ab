//! A rigid pose: a rotation, then a translation, in `f32` with a fixed order of
//! operations, so that the host and a Cortex-M4F pose a vertex to the same bits.

use crate::mesh::Viewpoint;

/// Where an instance's mesh sits in the world: its own origin moved by a rotation
/// about it and then a translation, `p' = R p + t`.
///
/// [`apply`](Self::apply) is the one definition of a posed vertex: a scene's
/// frame poses with it, and so does a union mesh built to check one (each
/// coordinate `((r0 x + r1 y) + r2 z) + t`, in `f32`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Pose {
    rows: [[f32; 3]; 3],
    translation: [f32; 3],
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// The mesh where it was baked.
    pub const IDENTITY: Self = Self {
        rows: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        translation: [0.0; 3],
    };

    /// Moved by `t`, not turned.
    pub const fn translation(t: [f32; 3]) -> Self {
        Self {
            rows: Self::IDENTITY.rows,
            translation: t,
        }
    }

    /// Turned by `degrees[0]` about x, then `degrees[1]` about y, then
    /// `degrees[2]` about z (right-handed, counter-clockwise seen from the axis's
    /// tip), all about the mesh's own origin, then moved by `t`: the `render`
    /// command's scene-file rotation. Sines and cosines are made in `f64` (the
    /// same bits everywhere; multiples of 90 degrees exact) and rounded once.
    /// Non-finite input gives a pose whose frames are refused
    /// (`NonFiniteVertex`).
    pub fn from_degrees(degrees: [f32; 3], t: [f32; 3]) -> Self {
        let [(sx, cx), (sy, cy), (sz, cz)] = degrees.map(sin_cos_deg);
        // R = Rz Ry Rx, in f64 and rounded once.
        let rows = [
            [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
            [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
            [-sy, cy * sx, cy * cx],
        ];
        Self {
            rows: rows.map(|r| r.map(|c| c as f32)),
            translation: t,
        }
    }

    /// `self`, then `outer`: the pose of a part carried by another (a robot arm's
    /// link on the one before it). The rotation and translation are composed in
    /// `f32`.
    pub fn then(&self, outer: &Pose) -> Pose {
        let columns = transpose(self.rows);
        let rows = outer.rows.map(|r| columns.map(|c| dot(r, c)));
        Pose {
            rows,
            translation: outer.apply(self.translation),
        }
    }

    /// The rotation's rows.
    pub fn rotation(&self) -> [[f32; 3]; 3] {
        self.rows
    }

    /// The translation.
    pub fn offset(&self) -> [f32; 3] {
        self.translation
    }

    /// `p` posed: `R p + t`.
    #[inline(always)]
    pub fn apply(&self, p: [f32; 3]) -> [f32; 3] {
        let t = self.translation;
        let [a, b, c] = self.rows;
        [dot(a, p) + t[0], dot(b, p) + t[1], dot(c, p) + t[2]]
    }

    /// A world direction in the mesh's own space: `R^T d`.
    fn turn_back(&self, d: [f32; 3]) -> [f32; 3] {
        transpose(self.rows).map(|column| dot(column, d))
    }

    /// The camera's `view` brought into the mesh's own space (`R^T (eye - t)`, or
    /// the direction turned back), so that its baked planes face it as the posed
    /// faces face the camera.
    pub(crate) fn view_in_mesh(&self, view: &Viewpoint) -> Viewpoint {
        match *view {
            Viewpoint::Perspective { eye } => {
                let t = self.translation;
                let d = [eye[0] - t[0], eye[1] - t[1], eye[2] - t[2]];
                Viewpoint::Perspective {
                    eye: self.turn_back(d),
                }
            }
            Viewpoint::Orthographic { direction_to_eye } => Viewpoint::Orthographic {
                direction_to_eye: self.turn_back(direction_to_eye),
            },
        }
    }
}

/// Rows to columns.
fn transpose([[a, b, c], [d, e, f], [g, h, i]]: [[f32; 3]; 3]) -> [[f32; 3]; 3] {
    [[a, d, g], [b, e, h], [c, f, i]]
}

#[inline(always)]
fn dot(a: [f32; 3], p: [f32; 3]) -> f32 {
    a[0] * p[0] + a[1] * p[1] + a[2] * p[2]
}

/// Sine and cosine of `deg` degrees in `f64`: reduced to a quarter turn and its
/// quadrant (so multiples of 90 are exact), then Taylor series.
fn sin_cos_deg(deg: f32) -> (f64, f64) {
    let deg = f64::from(deg);
    if !deg.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let turns = deg / 360.0;
    // Whole turns away (`as` saturates; a turn past 2^53 degrees has no fraction).
    let whole = turns as i64 as f64;
    let mut r = (turns - whole) * 360.0;
    if r < 0.0 {
        r += 360.0;
    }
    let quadrant = (r / 90.0) as i64;
    let x = (r - 90.0 * quadrant as f64).to_radians();
    let x2 = x * x;
    let (mut s, mut c, mut ts, mut tc) = (0.0f64, 0.0f64, x, 1.0f64);
    for k in 0..10 {
        s += ts;
        c += tc;
        let n = f64::from(2 * k + 2);
        ts *= -x2 / (n * (n + 1.0));
        tc *= -x2 / ((n - 1.0) * n);
    }
    match quadrant & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f32; 3], b: [f32; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
    }

    #[test]
    fn quarter_turns_are_exact_and_turn_x_then_y_then_z() {
        // 90 about x takes y to z; then 90 about y takes z to x.
        let p = Pose::from_degrees([90.0, 90.0, 0.0], [0.0; 3]);
        assert_eq!(p.apply([0.0, 1.0, 0.0]), [1.0, 0.0, 0.0]);
        let q = Pose::from_degrees([0.0, 0.0, -270.0], [1.0, 2.0, 3.0]);
        assert_eq!(q.apply([1.0, 0.0, 0.0]), [1.0, 3.0, 3.0]);
    }

    #[test]
    fn the_eye_brought_into_the_mesh_sees_what_the_world_eye_sees() {
        let pose = Pose::from_degrees([30.0, -50.0, 200.0], [1.0, -2.0, 0.5]);
        let local = [0.3, 0.7, -0.2];
        let eye = pose.apply(local);
        let view = pose.view_in_mesh(&Viewpoint::Perspective { eye });
        assert!(matches!(view, Viewpoint::Perspective { eye } if close(eye, local)));
    }

    #[test]
    fn then_poses_as_one_pose_after_the_other() {
        let inner = Pose::from_degrees([10.0, 20.0, 30.0], [1.0, 0.0, 0.0]);
        let outer = Pose::from_degrees([0.0, 0.0, 90.0], [0.0, 0.0, 2.0]);
        let p = [0.5, -1.0, 2.0];
        let both = inner.then(&outer);
        assert!(close(both.apply(p), outer.apply(inner.apply(p))));
    }
}
