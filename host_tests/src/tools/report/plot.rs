//! The plots: line error (the main job) or face-id error against instructions per
//! frame, one panel per size, the Pareto front marked, the sweep's base settings
//! ringed, RAM per point (SVG, no system fonts).

use std::path::Path;

use plotters::prelude::*;

use super::Config;

/// One point: a configuration's mean instructions per frame and error (%).
#[derive(Clone, Debug)]
pub struct Point {
    pub config: Config,
    pub ir: f64,
    pub error: f64,
    /// The most working RAM (bytes) over its scenes.
    pub ram: u64,
}

/// The Pareto front of `points` (no other point is at most as costly and at most as
/// wrong, and better in one): indices, by increasing cost.
pub fn pareto(points: &[Point]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len()).collect();
    idx.sort_by(|&a, &b| {
        points[a]
            .ir
            .total_cmp(&points[b].ir)
            .then(points[a].error.total_cmp(&points[b].error))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].error < best {
            best = points[i].error;
            front.push(i);
        }
    }
    front
}

fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("plot: {e:?}")
}

/// Width of a label in pixels at the plot's 11-px font (a conservative estimate:
/// the SVG names no font file).
fn label_width(text: &str) -> i32 {
    (text.chars().count() as f64 * 6.6).ceil() as i32 + 2
}

/// A rectangle in pixels: left, top, right, bottom.
type Rect = (i32, i32, i32, i32);

fn overlaps(a: Rect, b: Rect) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// Does segment `a`-`b` cross segment `c`-`d` (proper crossing, shared ends aside)?
fn crosses(a: (i32, i32), b: (i32, i32), c: (i32, i32), d: (i32, i32)) -> bool {
    let side = |p: (i32, i32), q: (i32, i32), r: (i32, i32)| {
        let v = i64::from(q.0 - p.0) * i64::from(r.1 - p.1)
            - i64::from(q.1 - p.1) * i64::from(r.0 - p.0);
        v.signum()
    };
    let (d1, d2) = (side(a, b, c), side(a, b, d));
    let (d3, d4) = (side(c, d, a), side(c, d, b));
    d1 * d2 < 0 && d3 * d4 < 0
}

fn contains(r: Rect, p: (i32, i32)) -> bool {
    p.0 >= r.0 && p.0 <= r.2 && p.1 >= r.1 && p.1 <= r.3
}

/// Does segment `a`-`b` pass through rectangle `r` (sampled every 2 px)?
fn through(a: (i32, i32), b: (i32, i32), r: Rect) -> bool {
    let steps = (b.0 - a.0).abs().max((b.1 - a.1).abs()) / 2 + 1;
    (0..=steps).any(|k| {
        let x = a.0 + (b.0 - a.0) * k / steps;
        let y = a.1 + (b.1 - a.1) * k / steps;
        x > r.0 && x < r.2 && y > r.1 && y < r.3
    })
}

/// The leader from a marker at `at` to its label `r`, or `None` when the label sits
/// beside the marker and needs none.
fn leader(at: (i32, i32), r: Rect, w: i32) -> Option<((i32, i32), (i32, i32))> {
    let (lx, ly) = ((r.0 + r.2) / 2, (r.1 + r.3) / 2);
    if (lx - at.0).abs() > w / 2 + 12 || (ly - at.1).abs() > 16 {
        Some((at, (r.0.max(at.0.min(r.2)), r.1.max(at.1.min(r.3)))))
    } else {
        None
    }
}

/// What the labels placed so far occupy: rectangles (labels, markers, legend) and
/// leader lines.
#[derive(Default)]
struct Taken {
    rects: Vec<Rect>,
    leaders: Vec<((i32, i32), (i32, i32))>,
}

/// Places one label of size `(w, h)` for a point at `at`: the first spot, on rings
/// of growing distance around the point, that lies inside `bounds`, overlaps no
/// rectangle in `taken`, and whose leader (if it needs one) crosses no other leader
/// and runs through no other label. `own` is the point's own marker (its leader
/// starts inside it). `None` when there is no such spot within 120 px.
fn place(
    at: (i32, i32),
    (w, h): (i32, i32),
    bounds: Rect,
    taken: &Taken,
    own: Rect,
) -> Option<Rect> {
    let free = |r: Rect, strict: bool| {
        let inside = r.0 >= bounds.0 && r.1 >= bounds.1 && r.2 <= bounds.2 && r.3 <= bounds.3;
        inside
            && !taken.rects.iter().any(|&t| overlaps(r, t))
            && leader(at, r, w).is_none_or(|(a, b)| {
                let crossing = taken.leaders.iter().any(|&(c, d)| crosses(a, b, c, d));
                let under = |t: &Rect| *t != own && !contains(*t, at) && through(a, b, *t);
                let blocked = strict && taken.rects.iter().any(under);
                !crossing && !blocked
            })
    };
    for ring in 0..12 {
        let d = 7 + 10 * ring;
        let spots = [
            (d, -h / 2),
            (-d - w, -h / 2),
            (-w / 2, -d - h),
            (-w / 2, d),
            (d, -d - h),
            (d, d),
            (-d - w, -d - h),
            (-d - w, d),
        ];
        for (dx, dy) in spots {
            let r = (at.0 + dx, at.1 + dy, at.0 + dx + w, at.1 + dy + h);
            if free(r, true) {
                return Some(r);
            }
        }
    }
    // Crowded: the nearest free spot anywhere in the plotting area, and failing that
    // one whose leader may pass under another label (leaders still never cross).
    for strict in [true, false] {
        let mut best: Option<(i64, Rect)> = None;
        for y in (bounds.1..bounds.3 - h).step_by(7) {
            for x in (bounds.0..bounds.2 - w).step_by(10) {
                let r = (x, y, x + w, y + h);
                let (cx, cy) = (i64::from(x + w / 2 - at.0), i64::from(y + h / 2 - at.1));
                let dist = cx * cx + cy * cy;
                if best.is_none_or(|b| dist < b.0) && free(r, strict) {
                    best = Some((dist, r));
                }
            }
        }
        if best.is_some() {
            return best.map(|b| b.1);
        }
    }
    None
}

/// Round frames-per-second values (1, 2, 5 a decade; 1 to 9 a decade when the axis
/// spans less than a decade) whose instruction counts lie between `lo` and `hi`.
fn fps_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let (fmin, fmax) = (CLOCK_MHZ / hi, CLOCK_MHZ / lo);
    let decades = |steps: &[f64]| -> Vec<f64> {
        let mut v = Vec::new();
        let mut p = 10f64.powi(fmin.log10().floor() as i32 - 1);
        while p <= fmax * 10.0 {
            for &s in steps {
                let f = s * p;
                if f >= fmin && f <= fmax {
                    v.push(f);
                }
            }
            p *= 10.0;
        }
        v
    };
    let coarse = decades(&[1.0, 2.0, 5.0]);
    if coarse.len() >= 4 {
        coarse
    } else {
        decades(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0])
    }
}

/// A value as the labels say it: `0`, or two significant digits (whole numbers from 10).
fn two_digits(v: f64) -> String {
    if v <= 0.0 {
        "0".into()
    } else if v >= 10.0 {
        format!("{v:.0}")
    } else {
        let digits = (1 - v.log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    }
}

/// A clock to put beside instruction counts: frames per second at 168 MHz (a
/// Cortex-M4 at its usual top clock) if one counted instruction took one cycle.
const CLOCK_MHZ: f64 = 168.0;

/// Draws the panels (title, points) side by side into `path`: error (`y_desc`, log
/// scale, an error of 0 on a row of its own at the bottom) against instructions per
/// frame (log scale), with round frames-per-second values at [`CLOCK_MHZ`] along the
/// top, outside the plotting area (an estimate, labelled), each point's marker sized by
/// its working RAM and labelled with its settings, error and RAM; no label over another,
/// over a marker or off the canvas, and no leader line crossing another. `default` is
/// the sweep's base settings, ringed.
pub fn draw(
    path: &Path,
    panels: &[(String, Vec<Point>)],
    y_desc: &str,
    default: Config,
) -> Result<(), String> {
    let width = 660 * panels.len().max(1) as u32;
    let root = SVGBackend::new(path, (width, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, panels.len().max(1)));
    let most_ram = panels
        .iter()
        .flat_map(|p| p.1.iter().map(|q| q.ram))
        .max()
        .unwrap_or(1)
        .max(1) as f64;
    let radius = |ram: u64| (3.0 + 7.0 * (ram as f64 / most_ram).sqrt()).round() as i32;
    for ((title, points), area) in panels.iter().zip(&areas) {
        let xmax = points.iter().map(|p| p.ir).fold(0.0, f64::max) * 1.25 + 1e-9;
        let xmin = points.iter().map(|p| p.ir).fold(f64::INFINITY, f64::min) * 0.8;
        let xmin = xmin.min(xmax / 2.0);
        let largest = points.iter().map(|p| p.error).fold(0.0, f64::max) + 1e-6;
        let smallest = points
            .iter()
            .map(|p| p.error)
            .filter(|e| *e > 0.0)
            .fold(f64::INFINITY, f64::min)
            .min(largest / 10.0);
        // An error of 0 has a row of its own below the smallest error drawn; above the
        // largest, a third of the height stays free for the legend.
        let zero_at = smallest / 4.0;
        let ymin = zero_at / 2.0;
        let ymax = largest * (largest / ymin).powf(0.5).max(3.0);
        let drawn = |p: &Point| p.error.max(zero_at);
        area.draw(&Text::new(
            title.clone(),
            (74, 8),
            ("sans-serif", 15).into_font(),
        ))
        .map_err(err)?;
        let mut chart = ChartBuilder::on(area)
            .margin(14)
            .margin_top(64)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((xmin..xmax).log_scale(), (ymin..ymax).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .bold_line_style(BLACK.mix(0.15))
            .x_desc("instructions per frame (millions, callgrind on the host; log scale)")
            .y_desc(y_desc)
            .x_label_formatter(&|v| two_digits(*v))
            .y_label_formatter(&|v| {
                if *v < smallest / 1.5 {
                    String::new()
                } else {
                    two_digits(*v)
                }
            })
            .draw()
            .map_err(err)?;
        // The zero row: a dotted rule and its value where the axis labels stand.
        chart
            .draw_series(LineSeries::new(
                [(xmin, zero_at), (xmax, zero_at)],
                BLACK.mix(0.25),
            ))
            .map_err(err)?;
        let front = pareto(points);
        chart
            .draw_series(LineSeries::new(
                front.iter().map(|&i| (points[i].ir, drawn(&points[i]))),
                RED.stroke_width(2),
            ))
            .map_err(err)?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart
            .draw_series(
                points
                    .iter()
                    .map(|p| Circle::new((p.ir, drawn(p)), radius(p.ram), BLUE.mix(0.6).filled())),
            )
            .map_err(err)?
            .label("settings (one knob changed): label = settings, error %, working RAM")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLUE.mix(0.6).filled()));
        chart
            .draw_series(
                points
                    .iter()
                    .filter(|p| p.config == default)
                    .map(|p| Circle::new((p.ir, drawn(p)), radius(p.ram) + 5, RED.stroke_width(2))),
            )
            .map_err(err)?
            .label(format!(
                "the default ({}); marker area ~ working RAM",
                default.label()
            ))
            .legend(|(x, y)| Circle::new((x + 10, y), 6, RED.stroke_width(2)));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(err)?;
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let base = area.get_base_pixel();
        let local = |(x, y): (i32, i32)| (x - base.0, y - base.1);
        let bounds = (
            xr.start - base.0,
            yr.start - base.1,
            xr.end - base.0,
            yr.end - base.1,
        );
        let font = ("sans-serif", 11).into_font();
        let (_, zero_y) = local(chart.backend_coord(&(xmin, zero_at)));
        area.draw(&Text::new("0", (bounds.0 - 14, zero_y - 6), font.clone()))
            .map_err(err)?;
        // Frames per second: a scale of its own above the plotting area.
        let top = bounds.1;
        area.draw(&Text::new(
            format!("fps at {CLOCK_MHZ:.0} MHz (estimate: one instruction a cycle)"),
            (bounds.0, top - 38),
            font.clone(),
        ))
        .map_err(err)?;
        let mut ticks: Vec<(i32, i32)> = Vec::new();
        for fps in fps_ticks(xmin, xmax) {
            let (x, _) = local(chart.backend_coord(&(CLOCK_MHZ / fps, ymax)));
            let text = two_digits(fps);
            let w = label_width(&text);
            let span = (x - w / 2 - 4, x + w / 2 + 4);
            let clash = ticks.iter().any(|t| span.0 < t.1 && t.0 < span.1);
            if clash || x < bounds.0 || x > bounds.2 {
                continue;
            }
            ticks.push(span);
            area.draw(&PathElement::new(vec![(x, top - 6), (x, top)], BLACK))
                .map_err(err)?;
            area.draw(&Text::new(text, (x - w / 2 + 1, top - 20), font.clone()))
                .map_err(err)?;
        }
        // Labels: none over another, a marker, the legend or the canvas edge; leaders
        // that cross no other leader.
        let legend_w = 430;
        let mut taken = Taken {
            rects: vec![(bounds.2 - legend_w, bounds.1, bounds.2, bounds.1 + 72)],
            leaders: Vec::new(),
        };
        let centres: Vec<(i32, i32)> = points
            .iter()
            .map(|p| local(chart.backend_coord(&(p.ir, drawn(p)))))
            .collect();
        let markers: Vec<Rect> = centres
            .iter()
            .zip(points)
            .map(|(c, p)| {
                let r = radius(p.ram) + if p.config == default { 6 } else { 1 };
                (c.0 - r, c.1 - r, c.0 + r, c.1 + r)
            })
            .collect();
        taken.rects.extend(&markers);
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&a, &b| points[a].ir.total_cmp(&points[b].ir));
        for i in order {
            let p = &points[i];
            let text = format!(
                "{} {}% {:.0} KB",
                p.config.label(),
                two_digits(p.error),
                p.ram as f64 / 1024.0
            );
            let size = (label_width(&text), 13);
            let at = centres[i];
            let Some(r) = place(at, size, bounds, &taken, markers[i]) else {
                continue;
            };
            taken.rects.push(r);
            if let Some((a, b)) = leader(at, r, size.0) {
                taken.leaders.push((a, b));
                area.draw(&PathElement::new(vec![a, b], BLACK.mix(0.4)))
                    .map_err(err)?;
            }
            area.draw(&Text::new(text, (r.0 + 1, r.1 + 1), font.clone()))
                .map_err(err)?;
        }
    }
    root.present().map_err(err)?;
    Ok(())
}
