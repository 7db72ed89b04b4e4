//! Figures of `ldh agree`'s page (`docs/agreement.md`): the Bland–Altman plot of one parameter
//! (difference ldh − reference against the mean of the two, Bland & Altman 1986, 1999; the bias
//! and the limits of agreement with their confidence intervals drawn as pingouin's
//! `plot_blandaltman` draws them: bands around the lines) and the histogram of the event-timing
//! errors (ldh − reference, ms).

use plotters::prelude::*;

use super::{
    colour_of, framed_chart, legend, legend_room, perr, styled_mesh, Fonts, PrintWidth, COLORS,
};
use ldh_core::agreement::LimitsOfAgreement;
use ldh_core::error::{LdhError, Result};

/// The canvas width of [`bland_altman_svg`], px.
const BLAND_ALTMAN_W: u32 = 640;
/// How wide [`bland_altman_svg`] prints.
pub const BLAND_ALTMAN_PRINT: PrintWidth = PrintWidth::Chart;
/// The canvas width of [`timing_histogram_svg`], px.
const TIMING_W: u32 = 640;
/// How wide [`timing_histogram_svg`] prints.
pub const TIMING_PRINT: PrintWidth = PrintWidth::Chart;
/// The x-axis label of [`timing_histogram_svg`].
pub const TIMING_X_LABEL: &str = "timing error, ldh − reference (ms)";
/// The y-axis label of [`timing_histogram_svg`].
pub const TIMING_Y_LABEL: &str = "matched events (count)";
/// The fill of the histogram's bars (bluish green), by which a test counts them.
pub const TIMING_BAR_COLOUR: RGBColor = COLORS[2];

/// One series of a Bland–Altman plot: its name (`left`/`right` take the sides' colours) and
/// its points, (mean of ldh and reference, ldh − reference).
pub type BlandAltmanSeries = (super::SeriesName, Vec<(f64, f64)>);

/// A Bland–Altman plot: one dot per pair, the bias (solid line) and the limits of agreement
/// (dashed lines), each with its confidence interval as a translucent band across the plot
/// (grey for the bias, blue for the limits), and a thin line at 0. The legend names the bias
/// and the limits; the series' colours (left blue, right orange) are for the caption to say
/// (a legend entry per side would take half the plot's height). `x_label` and `y_label` name
/// the axes with their units. Errors: no finite point.
pub fn bland_altman_svg(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[BlandAltmanSeries],
    limits: &LimitsOfAgreement,
) -> Result<String> {
    let pts: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.1.iter().copied())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    if pts.is_empty() {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: no pairs to plot"),
        ));
    }
    let (x_lo, x_hi) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let ys = pts.iter().map(|p| p.1).chain([
        limits.lower_ci.0,
        limits.upper_ci.1,
        limits.bias_ci.0,
        limits.bias_ci.1,
        0.0,
    ]);
    let (y_lo, y_hi) = ys
        .filter(|v| v.is_finite())
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    let xp = ((x_hi - x_lo) * 0.05).max(1e-3 * x_hi.abs().max(1e-3));
    let yp = ((y_hi - y_lo) * 0.06).max(1e-6);
    let n_legend = 2;
    let (x0, x1) = (x_lo - xp, x_hi + xp);
    let (y0, y1) = (
        y_lo - yp,
        y_hi + yp + legend_room(n_legend, y_hi - y_lo + 2.0 * yp),
    );
    let mut buf = String::new();
    {
        let f = Fonts::for_canvas(BLAND_ALTMAN_W, BLAND_ALTMAN_PRINT);
        let root = SVGBackend::with_string(&mut buf, (BLAND_ALTMAN_W, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = framed_chart(&root, &f, title, 4 * f.label + f.desc)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(perr)?;
        styled_mesh(&mut chart, &f)
            .x_desc(x_label)
            .y_desc(y_label)
            .x_labels(5)
            .y_labels(6)
            .draw()
            .map_err(perr)?;
        let grey = RGBColor(110, 110, 110);
        let blue = RGBColor(70, 110, 200);
        let band = |ci: (f64, f64), c: RGBColor| {
            Rectangle::new([(x0, ci.0), (x1, ci.1)], c.mix(0.2).filled())
        };
        chart
            .draw_series([
                band(limits.bias_ci, grey),
                band(limits.lower_ci, blue),
                band(limits.upper_ci, blue),
            ])
            .map_err(perr)?;
        chart
            .draw_series(LineSeries::new(
                [(x0, 0.0), (x1, 0.0)],
                RGBColor(190, 190, 190).stroke_width(1),
            ))
            .map_err(perr)?;
        chart
            .draw_series(LineSeries::new(
                [(x0, limits.bias), (x1, limits.bias)],
                BLACK.stroke_width(2),
            ))
            .map_err(perr)?
            .label(format!("bias {:+.3} (95 % CI band)", limits.bias))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK.stroke_width(2)));
        for (i, level) in [limits.lower, limits.upper].into_iter().enumerate() {
            let anno = chart
                .draw_series(DashedLineSeries::new(
                    [(x0, level), (x1, level)],
                    8,
                    5,
                    BLACK.stroke_width(1),
                ))
                .map_err(perr)?;
            if i == 1 {
                anno.label(format!(
                    "limits {:+.3} to {:+.3} (bands: CI)",
                    limits.lower, limits.upper
                ))
                .legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new([(0, 0), (6, 0)], BLACK.stroke_width(1))
                        + PathElement::new([(10, 0), (16, 0)], BLACK.stroke_width(1))
                });
            }
        }
        for (k, (name, v)) in series.iter().enumerate() {
            let c = colour_of(name, k);
            chart
                .draw_series(
                    v.iter()
                        .filter(|p| p.0.is_finite() && p.1.is_finite())
                        .map(|&p| Circle::new(p, 3, c.filled())),
                )
                .map_err(perr)?;
        }
        legend(&mut chart, f.label)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// The bins of a histogram of `values`: a width of 1, 2 or 5 × 10ᵏ giving at most 24 bins over
/// the range (at least `min_width`), the first bin starting at a multiple of the width; each
/// bin's lower edge and count (empty bins included). Non-finite values are skipped; no value:
/// no bins.
pub fn histogram_bins(values: &[f64], min_width: f64) -> (f64, Vec<(f64, usize)>) {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    let Some((lo, hi)) = v
        .iter()
        .map(|&x| (x, x))
        .reduce(|a, b| (a.0.min(b.0), a.1.max(b.1)))
    else {
        return (min_width, Vec::new());
    };
    let raw = ((hi - lo) / 24.0).max(min_width);
    let p = 10f64.powf(raw.log10().floor());
    let width = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|w| *w >= raw * (1.0 - 1e-12))
        .unwrap_or(10.0 * p);
    let start = (lo / width).floor();
    let n = ((hi / width).floor() - start) as usize + 1;
    let mut counts = vec![0usize; n];
    for x in v {
        let i = ((x / width).floor() - start) as usize;
        counts[i.min(n - 1)] += 1;
    }
    let bins = counts
        .into_iter()
        .enumerate()
        .map(|(i, c)| ((start + i as f64) * width, c))
        .collect();
    (width, bins)
}

/// A histogram of event-timing errors (ms, ldh − reference) in the bins of
/// [`histogram_bins`] (at least 1 ms wide): one bar per non-empty bin (filled with
/// [`TIMING_BAR_COLOUR`], which nothing else uses), a dashed line at 0 and a solid one at the
/// mean (the bias, in the legend). Errors: no finite value.
pub fn timing_histogram_svg(title: &str, errors_ms: &[f64]) -> Result<String> {
    let (width, bins) = histogram_bins(errors_ms, 1.0);
    let finite: Vec<f64> = errors_ms
        .iter()
        .copied()
        .filter(|x| x.is_finite())
        .collect();
    if bins.is_empty() {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: no matched events"),
        ));
    }
    let mean = finite.iter().sum::<f64>() / finite.len() as f64;
    let x0 = bins[0].0.min(0.0) - width;
    let x1 = (bins[bins.len() - 1].0 + width).max(0.0) + width;
    let top = bins.iter().map(|b| b.1).max().unwrap_or(1) as f64;
    let mut buf = String::new();
    {
        let f = Fonts::for_canvas(TIMING_W, TIMING_PRINT);
        let root = SVGBackend::with_string(&mut buf, (TIMING_W, 400)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = framed_chart(&root, &f, title, 4 * f.label + 2 * f.desc)
            .build_cartesian_2d(x0..x1, 0.0..top * 1.1 + legend_room(2, top * 1.1))
            .map_err(perr)?;
        styled_mesh(&mut chart, &f)
            .x_desc(TIMING_X_LABEL)
            .y_desc(TIMING_Y_LABEL)
            .x_labels(7)
            .y_labels(5)
            .y_label_formatter(&|v| format!("{v:.0}"))
            .draw()
            .map_err(perr)?;
        chart
            .draw_series(bins.iter().filter(|b| b.1 > 0).map(|&(lo, c)| {
                Rectangle::new(
                    [(lo, 0.0), (lo + width, c as f64)],
                    TIMING_BAR_COLOUR.filled(),
                )
            }))
            .map_err(perr)?;
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, 0.0), (0.0, top * 1.1)],
                6,
                4,
                RGBColor(120, 120, 120).stroke_width(1),
            ))
            .map_err(perr)?;
        chart
            .draw_series(LineSeries::new(
                [(mean, 0.0), (mean, top * 1.1)],
                BLACK.stroke_width(2),
            ))
            .map_err(perr)?
            .label(format!("bias {mean:+.1} ms"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK.stroke_width(2)));
        legend(&mut chart, f.label)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}
