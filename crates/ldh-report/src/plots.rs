//! SVG figures of the cohort analysis and the reports (paper Figures 3–7), drawn with plotters'
//! SVG backend (no system font libraries: text is laid out with plotters' built-in estimate and
//! rendered by the viewer), sized so that no text prints under 8 pt ([`PrintWidth`], [`Fonts`]): `radar.rs` z-score radar charts,
//! `cohort.rs` box plots and the confusion matrix, `signals.rs` time-series panels with events,
//! `series.rs` per-stride and gait-cycle plots, `agreement.rs` `ldh agree`'s Bland–Altman plots
//! and event-timing histograms. Here: the shared colours and legend.

use plotters::chart::MeshStyle;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::Shift;
use plotters::prelude::*;

use ldh_core::error::{LdhError, Result};
use ldh_core::Side;

mod agreement;
mod cohort;
mod radar;
mod series;
mod signals;
#[cfg(test)]
pub(crate) mod tests;

pub use agreement::{
    bland_altman_svg, histogram_bins, timing_histogram_svg, BlandAltmanSeries, BLAND_ALTMAN_PRINT,
    TIMING_BAR_COLOUR, TIMING_PRINT, TIMING_X_LABEL, TIMING_Y_LABEL,
};
pub use cohort::{boxplot_svg, confusion_svg, BOX_PRINT, CONFUSION_LABELS, CONFUSION_PRINT};
pub use radar::{
    radar_svg, RADAR_CLIPPED, RADAR_PRINT, RADAR_SCALE_LABEL, RADAR_Z_ABNORMAL, RADAR_Z_CLIP,
};
pub use series::{
    cycle_svg, stride_series_svg, CycleSeries, Series, CYCLE_PRINT, CYCLE_X_LABEL,
    STRIDE_SERIES_PRINT,
};
pub use signals::{signals_svg, EventMarks, Panel, SIGNALS_PRINT};

/// The text width of an A4 page at the reports' 7 mm margins (the `@page` rule of the report
/// CSS), pt: 196 mm.
pub const A4_TEXT_WIDTH_PT: f64 = (210.0 - 2.0 * 7.0) / 25.4 * 72.0;
/// The smallest text a printed figure may hold, pt (issue 36: every plot readable on paper).
pub const MIN_PRINT_TEXT_PT: f64 = 8.0;
/// plotters' SVG backend writes a font requested at size `s` as `font-size = s / 1.24` (its
/// em box); [`Fonts`] undoes it so that the size written is the size meant.
pub const PLOTTERS_SVG_FONT_DIVISOR: f64 = 1.24;

/// How wide a figure prints on A4: the report CSS gives each figure exactly this width in
/// print, and every figure's fonts are sized from it ([`Fonts::for_canvas`]) so that no text
/// prints under [`MIN_PRINT_TEXT_PT`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrintWidth {
    /// The full text width (time series, gait-cycle curves): 550 pt.
    Full,
    /// A square-ish chart (radar, gait-cycle curves), centred: 290 pt.
    Chart,
    /// One of three side by side (the classifiers' confusion matrices): 178 pt.
    Third,
    /// One of five side by side (the cohort's box plots): 105 pt.
    Fifth,
}

impl PrintWidth {
    /// Every print width, for the CSS and the tests.
    pub const ALL: [PrintWidth; 4] = [
        PrintWidth::Full,
        PrintWidth::Chart,
        PrintWidth::Third,
        PrintWidth::Fifth,
    ];

    /// The printed width, pt.
    pub fn pt(self) -> f64 {
        match self {
            PrintWidth::Full => 550.0,
            PrintWidth::Chart => 290.0,
            PrintWidth::Third => 178.0,
            PrintWidth::Fifth => 105.0,
        }
    }

    /// The CSS class of a figure printed this wide.
    pub fn class(self) -> &'static str {
        match self {
            PrintWidth::Full => "print-full",
            PrintWidth::Chart => "print-chart",
            PrintWidth::Third => "print-third",
            PrintWidth::Fifth => "print-fifth",
        }
    }
}

/// The font sizes (plotters units) of a canvas so that its text prints at 8.5 pt (tick labels,
/// legends, notes), 9 pt (axis descriptions) and 10 pt (titles).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fonts {
    /// Tick labels, legend entries and notes: 8.5 pt in print.
    pub label: i32,
    /// Axis descriptions: 9 pt in print.
    pub desc: i32,
    /// The chart's title: 10 pt in print.
    pub title: i32,
}

impl Fonts {
    /// The fonts of a canvas `canvas_w_px` wide that prints `print` wide.
    pub fn for_canvas(canvas_w_px: u32, print: PrintWidth) -> Self {
        let px = |pt: f64| {
            (pt * f64::from(canvas_w_px) / print.pt() * PLOTTERS_SVG_FONT_DIVISOR).ceil() as i32
        };
        Fonts {
            label: px(8.5),
            desc: px(9.0),
            title: px(10.0),
        }
    }
}

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

/// A series' name as its legend shows it and, when the series is one side's, that side: a
/// side's series is drawn in the side's colour in every figure (left blue, right orange), any
/// other series in the next colour by its position. The colour is decided on the side, never
/// on the name's text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeriesName {
    /// The legend's text.
    pub text: String,
    /// The side the series is, when it is one.
    pub side: Option<Side>,
}

impl SeriesName {
    /// A series of `side`, shown as `text`.
    pub fn of_side(side: Side, text: impl Into<String>) -> SeriesName {
        SeriesName {
            text: text.into(),
            side: Some(side),
        }
    }
}

impl From<String> for SeriesName {
    fn from(text: String) -> SeriesName {
        SeriesName { text, side: None }
    }
}

impl From<&str> for SeriesName {
    fn from(text: &str) -> SeriesName {
        SeriesName::from(text.to_string())
    }
}

impl std::ops::Deref for SeriesName {
    type Target = str;
    fn deref(&self) -> &str {
        &self.text
    }
}

impl std::fmt::Display for SeriesName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

/// The colour of the `k`-th series, `name`: its side's ([`SeriesName::side`]) in every figure,
/// else by position.
fn colour_of(name: &SeriesName, k: usize) -> RGBColor {
    match name.side {
        Some(Side::Left) => COLORS[0],
        Some(Side::Right) => COLORS[1],
        None => COLORS[k % COLORS.len()],
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

/// The frame of a titled chart on `root`: the caption `title`, a 10 px margin, an x label area
/// for tick labels and the axis description, and a y label area `y_label_area_px` wide.
fn framed_chart<'a, 'b, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    f: &Fonts,
    title: &str,
    y_label_area_px: i32,
) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(title, ("sans-serif", f.title))
        .margin(10)
        .x_label_area_size(2 * f.desc + 10)
        .y_label_area_size(y_label_area_px);
    builder
}

/// The grid of a chart in the report's style: tick labels and axis descriptions in `f`'s sizes,
/// light grey minor lines, at most 2 between labels. The caller adds the axis descriptions.
fn styled_mesh<'a, 'b, X, Y, DB>(
    chart: &'b mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    f: &Fonts,
) -> MeshStyle<'a, 'b, X, Y, DB>
where
    DB: DrawingBackend,
    X: Ranged + ValueFormatter<X::ValueType>,
    Y: Ranged + ValueFormatter<Y::ValueType>,
{
    let mut mesh = chart.configure_mesh();
    mesh.axis_desc_style(("sans-serif", f.desc))
        .label_style(("sans-serif", f.label))
        .light_line_style(RGBColor(235, 235, 235))
        .max_light_lines(2);
    mesh
}

/// The series legend in the upper right corner of a chart (drawn in the headroom that
/// [`legend_room`] adds above the data).
fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    font_size: i32,
) -> Result<()> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .label_font(("sans-serif", font_size))
        .draw()
        .map_err(perr)
}
