//! Per-stride and per-cycle figures of the subject report: a parameter stride by stride and the
//! mean ± SD gait-cycle curves against a reference band.

use plotters::prelude::*;

use super::{colour_of, framed_chart, legend, legend_room, perr, styled_mesh, Fonts, PrintWidth};
use ldh_core::error::{LdhError, Result};

/// The canvas width of [`stride_series_svg`], px.
const STRIDE_SERIES_W: u32 = 800;
/// How wide [`stride_series_svg`] prints.
pub const STRIDE_SERIES_PRINT: PrintWidth = PrintWidth::Full;
/// The canvas width of [`cycle_svg`], px.
const CYCLE_W: u32 = 800;
/// How wide [`cycle_svg`] prints.
pub const CYCLE_PRINT: PrintWidth = PrintWidth::Chart;

/// A parameter stride by stride: x = heel-strike time (s), one series per side; strides
/// excluded from the parameters are drawn as hollow circles, used ones filled.
pub fn stride_series_svg(title: &str, y_label: &str, series: &[Series]) -> Result<String> {
    let pts: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.1.iter().map(|p| (p.0, p.1)))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    if pts.is_empty() {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: no strides to plot"),
        ));
    }
    let (x_lo, x_hi, y_lo, y_hi) = pts.iter().fold(
        (f64::MAX, f64::MIN, f64::MAX, f64::MIN),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    let xp = ((x_hi - x_lo) * 0.03).max(0.5);
    let yp = ((y_hi - y_lo) * 0.1).max(1e-3 * y_hi.abs().max(1e-3));
    let mut buf = String::new();
    {
        let f = Fonts::for_canvas(STRIDE_SERIES_W, STRIDE_SERIES_PRINT);
        let root = SVGBackend::with_string(&mut buf, (STRIDE_SERIES_W, 320)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = framed_chart(&root, &f, title, 4 * f.label + f.desc)
            .build_cartesian_2d(
                x_lo - xp..x_hi + xp,
                y_lo - yp..y_hi + yp + legend_room(series.len(), y_hi - y_lo + 2.0 * yp),
            )
            .map_err(perr)?;
        styled_mesh(&mut chart, &f)
            .x_desc("heel-strike time (s)")
            .y_desc(y_label)
            .draw()
            .map_err(perr)?;
        for (k, (name, v)) in series.iter().enumerate() {
            let c = colour_of(name, k);
            let ok: Vec<(f64, f64)> = v
                .iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .map(|p| (p.0, p.1))
                .collect();
            if ok.is_empty() {
                continue;
            }
            chart
                .draw_series(LineSeries::new(
                    ok.iter().copied(),
                    c.mix(0.5).stroke_width(1),
                ))
                .map_err(perr)?
                .label(name.to_string())
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
            chart
                .draw_series(v.iter().filter(|p| p.0.is_finite() && p.1.is_finite()).map(
                    |&(x, y, valid)| {
                        let style = if valid { c.filled() } else { c.stroke_width(1) };
                        Circle::new((x, y), 4, style)
                    },
                ))
                .map_err(perr)?;
        }
        legend(&mut chart, f.label)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// One line of a per-stride plot: its label and `(x, y, valid)` points.
pub type Series = (super::SeriesName, Vec<(f64, f64, bool)>);

/// The x-axis label of [`cycle_svg`].
pub const CYCLE_X_LABEL: &str = "gait cycle (%)";

/// One curve of [`cycle_svg`]: name, mean and SD at equally spaced points over 0–100 %.
pub type CycleSeries = (super::SeriesName, Vec<f64>, Vec<f64>);

/// Gait-cycle curves: per series a line for the mean and a translucent band for mean ± SD,
/// coloured by side (left blue, right orange), over an optional reference band (grey, drawn
/// first, its line dashed-looking thin black). The legend sits in headroom above the data.
pub fn cycle_svg(
    title: &str,
    y_label: &str,
    series: &[CycleSeries],
    reference: Option<&CycleSeries>,
) -> Result<String> {
    let vals = series.iter().chain(reference).flat_map(|(_, m, s)| {
        m.iter()
            .zip(s)
            .flat_map(|(m, s)| [m - s, m + s])
            .filter(|v| v.is_finite())
    });
    let (lo, hi) = vals.fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    if !(lo <= hi) {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: nothing to plot"),
        ));
    }
    let pad = ((hi - lo) * 0.06).max(1e-3);
    let n_legend = series.len() + usize::from(reference.is_some());
    let room = legend_room(n_legend, hi - lo + 2.0 * pad);
    let mut buf = String::new();
    {
        let f = Fonts::for_canvas(CYCLE_W, CYCLE_PRINT);
        let root = SVGBackend::with_string(&mut buf, (CYCLE_W, 380)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = framed_chart(&root, &f, title, 4 * f.label + f.desc)
            .build_cartesian_2d(0.0..100.0, lo - pad..hi + pad + room)
            .map_err(perr)?;
        // Every 20 % as whole numbers ("90.0" and "100" ran into each other).
        styled_mesh(&mut chart, &f)
            .x_labels(6)
            .x_label_formatter(&|x| format!("{x:.0}"))
            .x_desc(CYCLE_X_LABEL)
            .y_desc(y_label)
            .draw()
            .map_err(perr)?;
        let grey = RGBColor(120, 120, 120);
        let all = reference.map(|r| (r, grey, true)).into_iter().chain(
            series
                .iter()
                .enumerate()
                .map(|(k, s)| (s, colour_of(&s.0, k), false)),
        );
        for ((name, mean, sd), c, is_ref) in all {
            let n = mean.len().min(sd.len());
            if n < 2 {
                continue;
            }
            let x = |i: usize| 100.0 * i as f64 / (n - 1) as f64;
            let band: Vec<(f64, f64)> = (0..n)
                .map(|i| (x(i), mean[i] + sd[i]))
                .chain((0..n).rev().map(|i| (x(i), mean[i] - sd[i])))
                .collect();
            let alpha = if is_ref { 0.30 } else { 0.22 };
            chart
                .draw_series(std::iter::once(Polygon::new(band, c.mix(alpha).filled())))
                .map_err(perr)?;
            let width = if is_ref { 1 } else { 2 };
            chart
                .draw_series(LineSeries::new(
                    (0..n).map(|i| (x(i), mean[i])),
                    c.stroke_width(width),
                ))
                .map_err(perr)?
                .label(name.to_string())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 16, y + 5)], c.mix(0.5).filled())
                });
        }
        legend(&mut chart, f.label)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}
