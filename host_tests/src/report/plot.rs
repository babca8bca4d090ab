//! The plot: face-id error against instructions per frame, one panel per size, the
//! Pareto front marked and the default settings highlighted (SVG, no system fonts).

use std::path::Path;

use plotters::prelude::*;

use super::Config;

/// One point: a configuration's mean instructions per frame and error (%).
#[derive(Clone, Debug)]
pub struct Point {
    pub config: Config,
    pub ir: f64,
    pub error: f64,
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

/// Draws the panels (title, points) side by side into `path`.
pub fn draw(path: &Path, panels: &[(String, Vec<Point>)], y_desc: &str) -> Result<(), String> {
    let width = 560 * panels.len().max(1) as u32;
    let root = SVGBackend::new(path, (width, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, panels.len().max(1)));
    for ((title, points), area) in panels.iter().zip(&areas) {
        let xmax = points.iter().map(|p| p.ir).fold(0.0, f64::max) * 1.1 + 1e-9;
        let xmin = points.iter().map(|p| p.ir).fold(f64::INFINITY, f64::min) * 0.9;
        let ymax = points.iter().map(|p| p.error).fold(0.0, f64::max) * 2.0 + 1e-6;
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
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(xmin.min(xmax)..xmax, (ymin..ymax).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(WHITE)
            .x_desc("instructions per frame (millions, callgrind)")
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
                    .map(|p| Circle::new((p.ir, p.error), 4, BLUE.filled())),
            )
            .map_err(err)?
            .label("settings (one knob changed)")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLUE.filled()));
        chart
            .draw_series(
                points
                    .iter()
                    .filter(|p| p.config == Config::DEFAULT)
                    .map(|p| Circle::new((p.ir, p.error), 9, RED.stroke_width(3))),
            )
            .map_err(err)?
            .label("default (codefill S4, full frame)")
            .legend(|(x, y)| Circle::new((x + 10, y), 6, RED.stroke_width(2)));
        chart
            .draw_series(points.iter().enumerate().map(|(i, p)| {
                // Alternate the labels above and below their points.
                let dy = if i % 2 == 0 { -14 } else { 4 };
                EmptyElement::at((p.ir, p.error))
                    + Text::new(p.config.label(), (6, dy), ("sans-serif", 11).into_font())
            }))
            .map_err(err)?;
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}
