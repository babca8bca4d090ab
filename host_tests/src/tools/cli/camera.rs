//! The camera the options describe: fitted or from the flags, degenerate ones rejected.

use super::options::Options;
use crate::fit::fit_camera;
use crate::frame::{CameraSpec, MeshData, ProjectionSpec};

impl Options {
    /// Is the camera fitted to the mesh (`--fit`, or no `--eye`)?
    pub fn fits(&self) -> bool {
        self.fit || self.eye.is_none()
    }

    /// The camera for `mesh`: fitted (then `--target`, `--up`, `--fov`/`--ortho`,
    /// `--near`, `--far` override the fitted values) or from the flags with the
    /// defaults of [`CameraSpec`]. Degenerate cameras are errors naming the flags.
    pub fn camera(&self, mesh: &MeshData) -> Result<CameraSpec, String> {
        let mut c = if self.fits() {
            fit_camera(mesh, self.spec.width, self.spec.height)
        } else {
            CameraSpec {
                eye: self.eye.unwrap_or(CameraSpec::default().eye),
                target: [0.0; 3],
                ..CameraSpec::default()
            }
        };
        if let Some(t) = self.target {
            c.target = t;
        }
        if let Some(u) = self.up {
            c.up = u;
        }
        if let Some(p) = self.projection {
            c.projection = p;
        }
        if let Some(n) = self.near {
            c.near = n;
        }
        if let Some(f) = self.far {
            c.far = f;
        }
        check_camera(&c)?;
        Ok(c)
    }
}

/// Rejects the degenerate cameras of CONVENTIONS.md with a message naming the flags.
pub fn check_camera(c: &CameraSpec) -> Result<(), String> {
    let d = [
        c.target[0] - c.eye[0],
        c.target[1] - c.eye[1],
        c.target[2] - c.eye[2],
    ];
    let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if len(d) == 0.0 {
        return Err("--eye/--target: the eye is at the target (no view direction)".into());
    }
    let x = [
        d[1] * c.up[2] - d[2] * c.up[1],
        d[2] * c.up[0] - d[0] * c.up[2],
        d[0] * c.up[1] - d[1] * c.up[0],
    ];
    if len(c.up) == 0.0 || len(x) <= 1e-12 * len(d) * len(c.up) {
        return Err("--up: the up vector is zero or parallel to the view direction".into());
    }
    if let ProjectionSpec::Perspective { fov_deg } = c.projection {
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(format!("--fov: {fov_deg} is not in (0, 180) degrees"));
        }
    }
    // Written so that NaN fails too.
    if c.near.is_nan() || c.near <= 0.0 {
        return Err(format!("--near: {} is not > 0", c.near));
    }
    if c.far.is_nan() || c.far <= c.near {
        return Err(format!(
            "--far: {} is not greater than near ({})",
            c.far, c.near
        ));
    }
    Ok(())
}
