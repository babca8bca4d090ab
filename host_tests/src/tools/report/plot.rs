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

/// Places one label of size `(w, h)` for a point at `at`: the first spot, on rings
/// of growing distance around the point, that lies inside `bounds` and overlaps no
/// rectangle in `taken` (labels and markers). `None` when there is none within
/// 120 px.
fn place(at: (i32, i32), (w, h): (i32, i32), bounds: Rect, taken: &[Rect]) -> Option<Rect> {
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
            let inside = r.0 >= bounds.0 && r.1 >= bounds.1 && r.2 <= bounds.2 && r.3 <= bounds.3;
            if inside && !taken.iter().any(|&t| overlaps(r, t)) {
                return Some(r);
            }
        }
    }
    None
}

/// A clock to put beside instruction counts: frames per second at 168 MHz (a
/// Cortex-M4 at its usual top clock) if one counted instruction took one cycle.
const CLOCK_MHZ: f64 = 168.0;

/// Draws the panels (title, points) side by side into `path`: error (`y_desc`, log
/// scale, 0 at the bottom) against instructions per frame, with frames per second
/// at [`CLOCK_MHZ`] along the top (an estimate, labelled), each point's marker
/// sized by its working RAM and labelled with its settings and RAM, no label over
/// another or over a marker or off the canvas. `default` is the sweep's base
/// settings, ringed.
pub fn draw(
    path: &Path,
    panels: &[(String, Vec<Point>)],
    y_desc: &str,
    default: Config,
) -> Result<(), String> {
    let width = 620 * panels.len().max(1) as u32;
    let root = SVGBackend::new(path, (width, 560)).into_drawing_area();
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
        let xmax = points.iter().map(|p| p.ir).fold(0.0, f64::max) * 1.15 + 1e-9;
        let xmin = points.iter().map(|p| p.ir).fold(f64::INFINITY, f64::min) * 0.85;
        let ymax = points.iter().map(|p| p.error).fold(0.0, f64::max) * 3.0 + 1e-6;
        let ymin = points
            .iter()
            .map(|p| p.error)
            .filter(|e| *e > 0.0)
            .fold(f64::INFINITY, f64::min)
            .min(ymax)
            / 2.0;
        // A log axis: an error of 0 is drawn at its bottom.
        let points: Vec<Point> = points
            .iter()
            .map(|p| Point {
                error: p.error.max(ymin),
                ..p.clone()
            })
            .collect();
        let points = &points;
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{title}   (ticks along the top: frames per second at {CLOCK_MHZ:.0} MHz, estimated as one instruction a cycle)"),
                ("sans-serif", 13),
            )
            .margin(14)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(xmin.min(xmax)..xmax, (ymin..ymax).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .bold_line_style(BLACK.mix(0.15))
            .x_desc("instructions per frame (millions, callgrind on the host)")
            .y_desc(y_desc)
            .x_label_formatter(&|v| format!("{v:.1}"))
            .y_label_formatter(&|v| format!("{v:.2}"))
            .draw()
            .map_err(err)?;
        let front = pareto(points);
        chart
            .draw_series(LineSeries::new(
                front.iter().map(|&i| (points[i].ir, points[i].error)),
                RED.stroke_width(2),
            ))
            .map_err(err)?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
        chart
            .draw_series(
                points
                    .iter()
                    .map(|p| Circle::new((p.ir, p.error), radius(p.ram), BLUE.mix(0.6).filled())),
            )
            .map_err(err)?
            .label("settings (one knob changed); marker area ~ working RAM")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLUE.mix(0.6).filled()));
        chart
            .draw_series(
                points
                    .iter()
                    .filter(|p| p.config == default)
                    .map(|p| Circle::new((p.ir, p.error), radius(p.ram) + 5, RED.stroke_width(2))),
            )
            .map_err(err)?
            .label(format!("the sweep's base ({})", default.label()))
            .legend(|(x, y)| Circle::new((x + 10, y), 6, RED.stroke_width(2)));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(err)?;
        // Frames per second along the top, inside the frame, at the instruction
        // counts they stand for (not under the legend).
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let base = area.get_base_pixel();
        let local = |(x, y): (i32, i32)| (x - base.0, y - base.1);
        let bounds = (
            xr.start - base.0,
            yr.start - base.1,
            xr.end - base.0,
            yr.end - base.1,
        );
        let top = bounds.1;
        let font = ("sans-serif", 11).into_font();
        let legend_w = 370;
        let legend: Rect = (bounds.2 - legend_w, bounds.1, bounds.2, bounds.1 + 72);
        let mut taken: Vec<Rect> = vec![legend];
        for fps in [
            0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0,
        ] {
            let ir = CLOCK_MHZ / fps;
            if ir < xmin || ir > xmax {
                continue;
            }
            let (x, _) = local(chart.backend_coord(&(ir, ymax)));
            let text = format!("{fps} fps");
            let r = (x - 2, top, x + label_width(&text) + 2, top + 16);
            if taken.iter().any(|&t| overlaps(r, t)) {
                continue;
            }
            taken.push(r);
            area.draw(&PathElement::new(vec![(x, top), (x, top + 6)], BLACK))
                .map_err(err)?;
            area.draw(&Text::new(text, (x + 2, top + 3), font.clone()))
                .map_err(err)?;
        }
        // Labels: none over another, a marker, the legend or the canvas edge.
        let centres: Vec<(i32, i32)> = points
            .iter()
            .map(|p| local(chart.backend_coord(&(p.ir, p.error))))
            .collect();
        for (c, p) in centres.iter().zip(points) {
            let r = radius(p.ram) + if p.config == default { 6 } else { 1 };
            taken.push((c.0 - r, c.1 - r, c.0 + r, c.1 + r));
        }
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&a, &b| points[a].ir.total_cmp(&points[b].ir));
        for i in order {
            let p = &points[i];
            let text = format!("{} {:.1} KB", p.config.label(), p.ram as f64 / 1024.0);
            let size = (label_width(&text), 13);
            let at = centres[i];
            let Some(r) = place(at, size, bounds, &taken) else {
                continue;
            };
            taken.push(r);
            // A leader line when the label sits away from its marker.
            let (lx, ly) = ((r.0 + r.2) / 2, (r.1 + r.3) / 2);
            if (lx - at.0).abs() > size.0 / 2 + 12 || (ly - at.1).abs() > 16 {
                let end = (r.0.max(at.0.min(r.2)), r.1.max(at.1.min(r.3)));
                area.draw(&PathElement::new(vec![at, end], BLACK.mix(0.4)))
                    .map_err(err)?;
            }
            area.draw(&Text::new(text, (r.0 + 1, r.1 + 1), font.clone()))
                .map_err(err)?;
        }
    }
    root.present().map_err(err)?;
    Ok(())
}
