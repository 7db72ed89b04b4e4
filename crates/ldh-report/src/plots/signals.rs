//! Stacked time-series panels of one recording (paper Figures 3–4): the signals on a shared
//! time axis with heel-strike and toe-off lines and stance shading.

use plotters::prelude::*;

use super::{colour_of, legend, legend_room, perr, styled_mesh, Fonts, PrintWidth};
use ldh_core::error::{LdhError, Result};

/// The canvas width of [`signals_svg`], px.
const SIGNALS_W: u32 = 800;
/// How wide [`signals_svg`] prints.
pub const SIGNALS_PRINT: PrintWidth = PrintWidth::Full;

/// One panel of [`signals_svg`]: a y-axis label with its unit and named series sampled on the
/// common time axis.
#[derive(Debug, Clone)]
pub struct Panel {
    /// y-axis label with the unit, e.g. `acceleration (g)`.
    pub y_label: String,
    /// (name, samples) per series.
    pub series: Vec<(super::SeriesName, Vec<f64>)>,
}

/// Gait events drawn on every panel of [`signals_svg`], s on the plot's time axis.
#[derive(Debug, Clone, Default)]
pub struct EventMarks {
    /// Heel strikes (solid red lines).
    pub hs_s: Vec<f64>,
    /// Toe offs (blue lines).
    pub to_s: Vec<f64>,
    /// Stance phases (HS → TO), shaded grey.
    pub stance_s: Vec<(f64, f64)>,
}

/// Stacked time-series panels on a shared time axis `t0_s + i / fs_hz` (paper Figs. 3–4), with
/// HS/TO lines and stance shading when `marks` is given. The x axis is `time (s)`.
pub fn signals_svg(
    title: &str,
    t0_s: f64,
    fs_hz: f64,
    panels: &[Panel],
    marks: Option<&EventMarks>,
) -> Result<String> {
    if panels.is_empty() || !(fs_hz > 0.0) {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: nothing to plot"),
        ));
    }
    let n = panels
        .iter()
        .flat_map(|p| p.series.iter().map(|s| s.1.len()))
        .max()
        .unwrap_or(0);
    if n < 2 {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: nothing to plot"),
        ));
    }
    let (t_lo, t_hi) = (t0_s, t0_s + (n - 1) as f64 / fs_hz);
    let height = 70 + 230 * panels.len() as u32;
    let mut buf = String::new();
    {
        let f = Fonts::for_canvas(SIGNALS_W, SIGNALS_PRINT);
        let root = SVGBackend::with_string(&mut buf, (SIGNALS_W, height)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let root = root.titled(title, ("sans-serif", f.title)).map_err(perr)?;
        let areas = root.split_evenly((panels.len(), 1));
        let axis = TimeAxis {
            t0_s,
            fs_hz,
            t_lo,
            t_hi,
        };
        for (k, (area, p)) in areas.iter().zip(panels).enumerate() {
            draw_panel(area, p, k + 1 == panels.len(), &axis, marks, f)?;
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// The shared time axis of [`signals_svg`]: sample `i` is at `t0_s + i / fs_hz` s, the axis
/// runs from `t_lo` to `t_hi` s.
struct TimeAxis {
    t0_s: f64,
    fs_hz: f64,
    t_lo: f64,
    t_hi: f64,
}

/// A panel's chart: time (s) against the panel's values.
type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// One panel: its axes (the time label only on the `last`), the events, the series and the
/// legend in headroom above the data.
fn draw_panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    p: &Panel,
    last: bool,
    axis: &TimeAxis,
    marks: Option<&EventMarks>,
    f: Fonts,
) -> Result<()> {
    let (t_lo, t_hi) = (axis.t_lo, axis.t_hi);
    let vals = p
        .series
        .iter()
        .flat_map(|s| s.1.iter())
        .filter(|v| v.is_finite());
    let (lo, hi) = vals.fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (-1.0, 1.0) };
    let pad = ((hi - lo) * 0.08).max(1e-3);
    // Headroom above the data for the legend (upper right), so it never covers a curve.
    let room = legend_room(p.series.len(), hi - lo + 2.0 * pad);
    let (y_lo, y_hi) = (lo - pad, hi + pad + room);
    let mut chart = ChartBuilder::on(area)
        .margin(8)
        .x_label_area_size(if last { 2 * f.desc + 10 } else { f.label + 10 })
        .y_label_area_size(4 * f.label + f.desc)
        .build_cartesian_2d(t_lo..t_hi, y_lo..y_hi)
        .map_err(perr)?;
    let mut mesh = styled_mesh(&mut chart, &f);
    mesh.y_desc(p.y_label.as_str());
    if last {
        mesh.x_desc("time (s)");
    }
    mesh.draw().map_err(perr)?;
    if let Some(m) = marks {
        draw_marks(&mut chart, m, (t_lo, t_hi), (y_lo, y_hi))?;
    }
    for (j, (name, v)) in p.series.iter().enumerate() {
        draw_line(&mut chart, name, v, colour_of(name, j), axis)?;
    }
    legend(&mut chart, f.label)
}

/// Stance shading (grey) and heel-strike (red) and toe-off (blue) lines within the time range.
fn draw_marks(
    chart: &mut Chart,
    m: &EventMarks,
    (t_lo, t_hi): (f64, f64),
    (y_lo, y_hi): (f64, f64),
) -> Result<()> {
    chart
        .draw_series(m.stance_s.iter().map(|&(a, b)| {
            Rectangle::new(
                [(a.max(t_lo), y_lo), (b.min(t_hi), y_hi)],
                RGBColor(225, 225, 225).filled(),
            )
        }))
        .map_err(perr)?;
    for (times, color) in [
        (&m.hs_s, RGBColor(200, 30, 30)),
        (&m.to_s, RGBColor(30, 60, 200)),
    ] {
        chart
            .draw_series(
                times
                    .iter()
                    .filter(|t| (t_lo..=t_hi).contains(*t))
                    .map(|&t| PathElement::new(vec![(t, y_lo), (t, y_hi)], color.stroke_width(1))),
            )
            .map_err(perr)?;
    }
    Ok(())
}

/// One series as a line broken at non-finite samples, labelled (for the legend) on its first
/// drawn piece.
fn draw_line(chart: &mut Chart, name: &str, v: &[f64], c: RGBColor, axis: &TimeAxis) -> Result<()> {
    let mut seg: Vec<(f64, f64)> = Vec::new();
    let mut first = true;
    let mut flush = |seg: &mut Vec<(f64, f64)>, chart: &mut Chart| -> Result<()> {
        if seg.len() > 1 {
            let s = chart
                .draw_series(LineSeries::new(seg.drain(..), c.stroke_width(1)))
                .map_err(perr)?;
            if first {
                s.label(name.to_string()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(3))
                });
                first = false;
            }
        }
        seg.clear();
        Ok(())
    };
    for (i, &y) in v.iter().enumerate() {
        if y.is_finite() {
            seg.push((axis.t0_s + i as f64 / axis.fs_hz, y));
        } else {
            flush(&mut seg, chart)?;
        }
    }
    flush(&mut seg, chart)
}
