//! The counts of one scene, their check against the limits, and its report line.

use std::fmt;

use super::{MISCLASSIFIED_LIMIT, MISSING_LIMIT, STRAY_LIMIT};

/// Surface counts of one scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceMetrics {
    pub pixels: usize,
    /// Pixels with a face: reference, library.
    pub ref_covered: usize,
    pub lib_covered: usize,
    /// (a), (b), (c), (d).
    pub holes: usize,
    pub wrong_faces: usize,
    pub depth_order: usize,
    pub far_diffs: usize,
    /// Face-id differences within 1 px of a projected edge (reported, not failed).
    pub near_diffs: usize,
    /// Library pixels showing a face the reference culls (reported).
    pub culled_face_pixels: usize,
    /// First pixel (x, y) of (a), (b), (c), (d), for reproduction.
    pub first: [Option<(usize, usize)>; 4],
}

/// Line counts of one scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineMetrics {
    /// Library line pixels (1 or 2).
    pub line_pixels: usize,
    /// (e) count, and the excepted pixels that would otherwise count.
    pub misclassified: usize,
    pub excepted: usize,
    /// Library line pixels with no reference sample within 1 px.
    pub stray: usize,
    /// (f): reference visible / hidden length on screen (px) and the missing parts.
    pub visible_len: f64,
    pub visible_missing: f64,
    pub hidden_len: f64,
    pub hidden_missing: f64,
    /// Hidden length left out because a visible sample lies within 1 px.
    pub hidden_excepted: f64,
    /// First misclassified pixel, first visible / hidden sample point missing.
    pub first_misclassified: Option<(usize, usize)>,
    pub first_visible_missing: Option<(f64, f64)>,
    pub first_hidden_missing: Option<(f64, f64)>,
}

impl LineMetrics {
    pub fn misclassified_fraction(&self) -> f64 {
        self.misclassified as f64 / (self.line_pixels.max(1)) as f64
    }
    /// Stray line pixels as a fraction of the library's line pixels.
    pub fn stray_fraction(&self) -> f64 {
        self.stray as f64 / (self.line_pixels.max(1)) as f64
    }
    pub fn visible_missing_fraction(&self) -> f64 {
        if self.visible_len > 0.0 {
            self.visible_missing / self.visible_len
        } else {
            0.0
        }
    }
    pub fn hidden_missing_fraction(&self) -> f64 {
        if self.hidden_len > 0.0 {
            self.hidden_missing / self.hidden_len
        } else {
            0.0
        }
    }
}

/// The metrics of one scene (one line of the report).
#[derive(Clone, Debug, Default)]
pub struct SceneMetrics {
    pub scene: String,
    pub surfaces: Option<SurfaceMetrics>,
    pub lines: Option<LineMetrics>,
    /// Milliseconds spent in the library and in the reference.
    pub lib_ms: f64,
    pub ref_ms: f64,
}

impl SceneMetrics {
    /// `Err` with the reasons when (a)-(d) are not 0 or a line limit is exceeded.
    pub fn check(&self) -> Result<(), String> {
        let mut why = Vec::new();
        if let Some(s) = &self.surfaces {
            let names = ["holes", "wrong faces", "depth-order errors", "far id diffs"];
            let counts = [s.holes, s.wrong_faces, s.depth_order, s.far_diffs];
            for k in 0..4 {
                if counts[k] > 0 {
                    why.push(format!(
                        "{} {} (first at pixel {:?})",
                        counts[k], names[k], s.first[k]
                    ));
                }
            }
        }
        if let Some(l) = &self.lines {
            if l.misclassified_fraction() > MISCLASSIFIED_LIMIT {
                why.push(format!(
                    "misclassified line pixels {:.3}% (first at {:?})",
                    100.0 * l.misclassified_fraction(),
                    l.first_misclassified
                ));
            }
            if l.stray_fraction() > STRAY_LIMIT {
                why.push(format!(
                    "stray line pixels {:.3}% ({} with no reference edge within 1 px)",
                    100.0 * l.stray_fraction(),
                    l.stray
                ));
            }
            if l.visible_missing_fraction() > MISSING_LIMIT {
                why.push(format!(
                    "visible length missing {:.3}% (first near {:?})",
                    100.0 * l.visible_missing_fraction(),
                    l.first_visible_missing
                ));
            }
            if l.hidden_missing_fraction() > MISSING_LIMIT {
                why.push(format!(
                    "hidden length missing {:.3}% (first near {:?})",
                    100.0 * l.hidden_missing_fraction(),
                    l.first_hidden_missing
                ));
            }
        }
        if why.is_empty() {
            Ok(())
        } else {
            Err(format!("{}: {}", self.scene, why.join("; ")))
        }
    }
}

impl fmt::Display for SceneMetrics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:<36}", self.scene)?;
        if let Some(s) = &self.surfaces {
            write!(
                f,
                " | px ref {:>6} lib {:>6} | holes {} wrong {} depth {} far-diff {} | near-diff {:>4} culled {}",
                s.ref_covered,
                s.lib_covered,
                s.holes,
                s.wrong_faces,
                s.depth_order,
                s.far_diffs,
                s.near_diffs,
                s.culled_face_pixels
            )?;
        }
        if let Some(l) = &self.lines {
            write!(
                f,
                " | lines {:>5} misclass {} ({:.3}%) exc {} stray {} | vis {:.0}px miss {:.3}% hid {:.0}px miss {:.3}% (exc {:.0}px)",
                l.line_pixels,
                l.misclassified,
                100.0 * l.misclassified_fraction(),
                l.excepted,
                l.stray,
                l.visible_len,
                100.0 * l.visible_missing_fraction(),
                l.hidden_len,
                100.0 * l.hidden_missing_fraction(),
                l.hidden_excepted
            )?;
        }
        write!(f, " | lib {:.0} ms ref {:.0} ms", self.lib_ms, self.ref_ms)
    }
}
