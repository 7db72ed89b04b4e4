//! SVG figures of the cohort analysis and the reports (paper Figures 3–7), drawn with plotters'
//! SVG backend (no system font libraries: text is laid out with plotters' built-in estimate and
//! rendered by the viewer), sized for A4 width (800 px): `radar.rs` z-score radar charts,
//! `cohort.rs` box plots and the confusion matrix, `signals.rs` time-series panels with events,
//! `series.rs` per-stride and gait-cycle plots. Here: the shared colours and legend.

use plotters::prelude::*;

use crate::error::{LdhError, Result};

mod cohort;
mod radar;
mod series;
mod signals;
#[cfg(test)]
mod tests;

pub use cohort::{boxplot_svg, confusion_svg, BOX_GROUP_LABEL, CONFUSION_LABELS};
pub use radar::{radar_svg, RADAR_CLIPPED, RADAR_SCALE_LABEL, RADAR_Z_ABNORMAL, RADAR_Z_CLIP};
pub use series::{cycle_svg, stride_series_svg, CycleSeries, Series, CYCLE_X_LABEL};
pub use signals::{signals_svg, EventMarks, Panel};

/// Series colours, colour-blind safe (Okabe & Ito 2008): left blue, right orange, then bluish
/// green and reddish purple. Sides differ by hue (never red against green), and no colour means
/// "abnormal": an abnormal value is marked by shape (▲/▼ in tables, a black-edged dot on the
/// radar), a clipped one by an open triangle.
const COLORS: [RGBColor; 4] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
];

/// The colour of the `k`-th series named `name`: a series named after a side (`left…`,
/// `right…`) gets that side's colour in every figure, others go by position.
fn colour_of(name: &str, k: usize) -> RGBColor {
    if name.starts_with("left") {
        COLORS[0]
    } else if name.starts_with("right") {
        COLORS[1]
    } else {
        COLORS[k % COLORS.len()]
    }
}

/// Values outside `[lo, hi]` (a physical range) set to the nearer bound, and how many were
/// (non-finite values are kept as gaps).
pub fn clip_to(values: &[f64], lo: f64, hi: f64) -> (Vec<f64>, usize) {
    let mut n = 0;
    let v = values
        .iter()
        .map(|&x| {
            if x.is_finite() && !(lo..=hi).contains(&x) {
                n += 1;
                x.clamp(lo, hi)
            } else {
                x
            }
        })
        .collect();
    (v, n)
}

/// A plotters error as an [`LdhError`] of the plot stage.
fn perr<E: std::fmt::Display>(e: E) -> LdhError {
    LdhError::signal("plot", e.to_string())
}

/// Extra y range above the data that keeps the upper-right legend of `n_series` entries clear
/// of the data (about 15 % of the plot height per entry), in data units of a range `span`.
fn legend_room(n_series: usize, span: f64) -> f64 {
    let share = (0.15 * n_series as f64).min(0.6);
    span * share / (1.0 - share)
}

/// The series legend in the upper right corner of a chart (drawn in the headroom that
/// [`legend_room`] adds above the data).
fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .label_font(("sans-serif", 13))
        .draw()
        .map_err(perr)
}
