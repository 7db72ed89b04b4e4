//! SVG figures of the cohort analysis (paper Figures 5–7): radar charts of the z-normalised
//! parameters per group and box plots per parameter and group. Drawn with plotters' SVG
//! backend (no system font libraries: text is laid out with plotters' built-in estimate and
//! rendered by the viewer). Sized for A4 width (800 px).

use plotters::prelude::*;

use crate::error::{LdhError, Result};

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

/// The start of the note [`radar_svg`] writes under a chart with clipped values.
pub const RADAR_CLIPPED: &str = "clipped at ±";

/// The scale label of [`radar_svg`] (drawn under the chart).
pub const RADAR_SCALE_LABEL: &str = "z-score (SD from the healthy mean)";
/// The x-axis label of [`boxplot_svg`].
pub const BOX_GROUP_LABEL: &str = "group (LDHH, LDHE, H)";
/// The axis labels of [`confusion_svg`].
pub const CONFUSION_LABELS: [&str; 2] = ["predicted class (count, % of row)", "true class (rows)"];

fn perr<E: std::fmt::Display>(e: E) -> LdhError {
    LdhError::signal("plot", e.to_string())
}

/// z-scores beyond ± this are drawn on the rim of [`radar_svg`] and marked as clipped.
pub const RADAR_Z_CLIP: f64 = 4.0;
/// |z| above which a radar point is marked abnormal (outside mean ± 1.96 SD).
pub const RADAR_Z_ABNORMAL: f64 = 1.96;

/// A radar chart: one axis per parameter (`codes`), one polygon per series of z-scores, its
/// colour by series (left/right by hue). The scale runs from −zmax (centre) to +zmax (rim),
/// zmax the largest |z| rounded up, between 2 and [`RADAR_Z_CLIP`]; rings at −zmax, −zmax/2, 0,
/// zmax/2, zmax, the z = 0 ring (the healthy mean) in black. A missing (NaN) value leaves a gap
/// in its polygon (never drawn as 0); a value beyond the rim is drawn on the rim as an open
/// triangle (clipped) and named under the chart; |z| > [`RADAR_Z_ABNORMAL`] is marked with a
/// black-edged dot. The legend sits above the chart, clear of the data.
pub fn radar_svg(title: &str, codes: &[String], series: &[(String, Vec<f64>)]) -> Result<String> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (800, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let (w, h) = (800.0, 720.0);
        let (cx, cy, rad) = (w / 2.0, h / 2.0 + 30.0, 250.0);
        let zabs = series
            .iter()
            .flat_map(|s| s.1.iter())
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let z_max = zabs.ceil().clamp(2.0, RADAR_Z_CLIP);
        let z_min = -z_max;
        let to_r = |z: f64| (z.clamp(z_min, z_max) - z_min) / (z_max - z_min) * rad;
        let n = codes.len().max(1);
        let pt = |i: usize, r: f64| {
            let a = std::f64::consts::FRAC_PI_2 - i as f64 / n as f64 * std::f64::consts::TAU;
            ((cx + r * a.cos()) as i32, (cy - r * a.sin()) as i32)
        };
        let font = |s: i32| ("sans-serif", s).into_font();
        root.draw(&Text::new(title.to_string(), (20, 15), font(24)))
            .map_err(perr)?;
        for z in [-z_max, -z_max / 2.0, 0.0, z_max / 2.0, z_max] {
            let ring: Vec<(i32, i32)> = (0..=n).map(|i| pt(i % n, to_r(z))).collect();
            let style = if z == 0.0 {
                BLACK.stroke_width(2)
            } else {
                RGBColor(180, 180, 180).stroke_width(1)
            };
            root.draw(&PathElement::new(ring, style)).map_err(perr)?;
            let (x, y) = pt(0, to_r(z));
            let label = if z == 0.0 {
                "z = 0 (healthy mean)".to_string()
            } else {
                format!("z = {z:+.1}")
            };
            root.draw(&Text::new(label, (x + 4, y - 14), font(13)))
                .map_err(perr)?;
        }
        for (i, c) in codes.iter().enumerate() {
            root.draw(&PathElement::new(
                vec![(cx as i32, cy as i32), pt(i, rad)],
                RGBColor(200, 200, 200),
            ))
            .map_err(perr)?;
            let (x, y) = pt(i, rad + 22.0);
            root.draw(&Text::new(
                c.clone(),
                (x - 14, y - 8),
                ("sans-serif", 16).into_font(),
            ))
            .map_err(perr)?;
        }
        let mut clipped: Vec<String> = Vec::new();
        let mut x_legend = 20i32;
        for (k, (name, z)) in series.iter().enumerate() {
            let c = colour_of(name, k);
            let m = z.len();
            // Segments between neighbouring axes that both have a value: a gap where one is
            // missing (a missing value is never drawn as 0).
            for i in 0..m {
                let j = (i + 1) % m;
                if m > 1 && z[i].is_finite() && z[j].is_finite() {
                    root.draw(&PathElement::new(
                        vec![pt(i, to_r(z[i])), pt(j, to_r(z[j]))],
                        c.stroke_width(3),
                    ))
                    .map_err(perr)?;
                }
            }
            for (i, &v) in z.iter().enumerate().filter(|(_, v)| v.is_finite()) {
                let p = pt(i, to_r(v));
                if v.abs() > z_max {
                    let (x, y) = p;
                    root.draw(&Polygon::new(
                        vec![(x, y - 9), (x - 8, y + 6), (x + 8, y + 6)],
                        WHITE.filled(),
                    ))
                    .map_err(perr)?;
                    root.draw(&PathElement::new(
                        vec![(x, y - 9), (x - 8, y + 6), (x + 8, y + 6), (x, y - 9)],
                        c.stroke_width(2),
                    ))
                    .map_err(perr)?;
                    clipped.push(format!(
                        "{name} {} z = {v:+.1}",
                        codes.get(i).map(String::as_str).unwrap_or("")
                    ));
                } else if v.abs() > RADAR_Z_ABNORMAL {
                    root.draw(&Circle::new(p, 6, BLACK.filled()))
                        .map_err(perr)?;
                    root.draw(&Circle::new(p, 4, c.filled())).map_err(perr)?;
                } else {
                    root.draw(&Circle::new(p, 3, c.filled())).map_err(perr)?;
                }
            }
            root.draw(&Rectangle::new(
                [(x_legend, 52), (x_legend + 20, 66)],
                c.filled(),
            ))
            .map_err(perr)?;
            root.draw(&Text::new(name.clone(), (x_legend + 28, 50), font(16)))
                .map_err(perr)?;
            x_legend += 60 + 9 * name.chars().count() as i32;
        }
        root.draw(&Text::new(
            "● with black edge: beyond ±1.96 SD (abnormal) · △ on the rim: clipped · gap: not measured"
                .to_string(),
            (20, 76),
            font(13),
        ))
        .map_err(perr)?;
        root.draw(&Text::new(
            format!("{RADAR_SCALE_LABEL}: (x − mean_H) / SD_H, eq. 18"),
            (20, 675),
            font(14),
        ))
        .map_err(perr)?;
        if !clipped.is_empty() {
            root.draw(&Text::new(
                format!("{RADAR_CLIPPED}{z_max:.0} SD: {}", clipped.join(", ")),
                (20, 697),
                font(13),
            ))
            .map_err(perr)?;
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// Box plots of one parameter per group (quartiles, whiskers at 1.5 IQR) with axis labels.
pub fn boxplot_svg(title: &str, y_label: &str, groups: &[(String, Vec<f64>)]) -> Result<String> {
    let all: Vec<f64> = groups
        .iter()
        .flat_map(|g| g.1.iter().copied())
        .filter(|v| v.is_finite())
        .collect();
    if all.is_empty() {
        return Err(LdhError::signal(
            "plot",
            format!("{title}: no values to plot"),
        ));
    }
    let (lo, hi) = all
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    let pad = ((hi - lo) * 0.1).max(1e-6 * hi.abs().max(1.0));
    let names: Vec<String> = groups.iter().map(|g| g.0.clone()).collect();
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (800, 480)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                names.as_slice().into_segmented(),
                (lo - pad) as f32..(hi + pad) as f32,
            )
            .map_err(perr)?;
        chart
            .configure_mesh()
            .x_desc(BOX_GROUP_LABEL)
            .x_label_formatter(&|v| match v {
                SegmentValue::CenterOf(s) | SegmentValue::Exact(s) => s.to_string(),
                SegmentValue::Last => String::new(),
            })
            .y_desc(y_label)
            .axis_desc_style(("sans-serif", 16))
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(perr)?;
        for (k, (name, v)) in groups.iter().enumerate() {
            let v: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
            if v.is_empty() {
                continue;
            }
            let q = Quartiles::new(&v);
            let c = COLORS[k % COLORS.len()];
            chart
                .draw_series(std::iter::once(
                    Boxplot::new_vertical(SegmentValue::CenterOf(name), &q)
                        .width(60)
                        .style(c.stroke_width(2)),
                ))
                .map_err(perr)?;
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

#[cfg(test)]
mod tests;

/// A confusion matrix (rows true, columns predicted) as an SVG heat map with counts.
pub fn confusion_svg(title: &str, classes: &[String], m: &[Vec<usize>]) -> Result<String> {
    let k = classes.len();
    let cell = 110i32;
    let (left, top) = (150i32, 90i32);
    let w = (left + cell * k as i32 + 40) as u32;
    let h = (top + cell * k as i32 + 70) as u32;
    let max = m.iter().flatten().copied().max().unwrap_or(1).max(1) as f64;
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (w.max(420), h)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        root.draw(&Text::new(
            title.to_string(),
            (15, 15),
            ("sans-serif", 20).into_font(),
        ))
        .map_err(perr)?;
        root.draw(&Text::new(
            CONFUSION_LABELS[0].to_string(),
            (left, top - 45),
            ("sans-serif", 15).into_font(),
        ))
        .map_err(perr)?;
        root.draw(&Text::new(
            CONFUSION_LABELS[1].to_string(),
            (10, top + cell * k as i32 / 2),
            ("sans-serif", 15).into_font(),
        ))
        .map_err(perr)?;
        for (i, name) in classes.iter().enumerate() {
            let x = left + cell * i as i32;
            root.draw(&Text::new(
                name.clone(),
                (x + cell / 3, top - 22),
                ("sans-serif", 15).into_font(),
            ))
            .map_err(perr)?;
            root.draw(&Text::new(
                name.clone(),
                (left - 60, top + cell * i as i32 + cell / 2 - 8),
                ("sans-serif", 15).into_font(),
            ))
            .map_err(perr)?;
        }
        for (i, row) in m.iter().enumerate() {
            let total: usize = row.iter().sum();
            for (j, &v) in row.iter().enumerate() {
                let a = v as f64 / max;
                let shade = (255.0 - 200.0 * a) as u8;
                let (x, y) = (left + cell * j as i32, top + cell * i as i32);
                root.draw(&Rectangle::new(
                    [(x, y), (x + cell - 2, y + cell - 2)],
                    RGBColor(shade, shade, 255).filled(),
                ))
                .map_err(perr)?;
                let pct = if total > 0 {
                    100.0 * v as f64 / total as f64
                } else {
                    0.0
                };
                root.draw(&Text::new(
                    format!("{v} ({pct:.0} %)"),
                    (x + 18, y + cell / 2 - 8),
                    ("sans-serif", 15).into_font(),
                ))
                .map_err(perr)?;
            }
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
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

/// One panel of [`signals_svg`]: a y-axis label with its unit and named series sampled on the
/// common time axis.
#[derive(Debug, Clone)]
pub struct Panel {
    /// y-axis label with the unit, e.g. `acceleration (g)`.
    pub y_label: String,
    /// (name, samples) per series.
    pub series: Vec<(String, Vec<f64>)>,
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
        let root = SVGBackend::with_string(&mut buf, (800, height)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let root = root.titled(title, ("sans-serif", 20)).map_err(perr)?;
        let areas = root.split_evenly((panels.len(), 1));
        for (k, (area, p)) in areas.iter().zip(panels).enumerate() {
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
            let last = k + 1 == panels.len();
            let mut chart = ChartBuilder::on(area)
                .margin(8)
                .x_label_area_size(if last { 40 } else { 22 })
                .y_label_area_size(70)
                .build_cartesian_2d(t_lo..t_hi, y_lo..y_hi)
                .map_err(perr)?;
            let mut mesh = chart.configure_mesh();
            mesh.y_desc(p.y_label.as_str())
                .axis_desc_style(("sans-serif", 15))
                .label_style(("sans-serif", 13))
                .light_line_style(RGBColor(235, 235, 235))
                .max_light_lines(2);
            if last {
                mesh.x_desc("time (s)");
            }
            mesh.draw().map_err(perr)?;
            if let Some(m) = marks {
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
                        .draw_series(times.iter().filter(|t| (t_lo..=t_hi).contains(*t)).map(
                            |&t| {
                                PathElement::new(vec![(t, y_lo), (t, y_hi)], color.stroke_width(1))
                            },
                        ))
                        .map_err(perr)?;
                }
            }
            for (j, (name, v)) in p.series.iter().enumerate() {
                let c = colour_of(name, j);
                // Break the line at non-finite samples.
                let mut seg: Vec<(f64, f64)> = Vec::new();
                let mut first = true;
                let mut flush =
                    |seg: &mut Vec<(f64, f64)>, chart: &mut ChartContext<_, _>| -> Result<()> {
                        if seg.len() > 1 {
                            let s = chart
                                .draw_series(LineSeries::new(seg.drain(..), c.stroke_width(1)))
                                .map_err(perr)?;
                            if first {
                                s.label(name.clone()).legend(move |(x, y)| {
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
                        seg.push((t0_s + i as f64 / fs_hz, y));
                    } else {
                        flush(&mut seg, &mut chart)?;
                    }
                }
                flush(&mut seg, &mut chart)?;
            }
            legend(&mut chart)?;
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

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
        let root = SVGBackend::with_string(&mut buf, (800, 300)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(
                x_lo - xp..x_hi + xp,
                y_lo - yp..y_hi + yp + legend_room(series.len(), y_hi - y_lo + 2.0 * yp),
            )
            .map_err(perr)?;
        chart
            .configure_mesh()
            .x_desc("heel-strike time (s)")
            .y_desc(y_label)
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .light_line_style(RGBColor(235, 235, 235))
            .max_light_lines(2)
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
                .label(name.clone())
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
        legend(&mut chart)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// One line of a per-stride plot: its label and `(x, y, valid)` points.
pub type Series = (String, Vec<(f64, f64, bool)>);

/// The x-axis label of [`cycle_svg`].
pub const CYCLE_X_LABEL: &str = "gait cycle (%)";

/// One curve of [`cycle_svg`]: name, mean and SD at equally spaced points over 0–100 %.
pub type CycleSeries = (String, Vec<f64>, Vec<f64>);

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
        let root = SVGBackend::with_string(&mut buf, (800, 360)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..100.0, lo - pad..hi + pad + room)
            .map_err(perr)?;
        chart
            .configure_mesh()
            .x_desc(CYCLE_X_LABEL)
            .y_desc(y_label)
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .light_line_style(RGBColor(235, 235, 235))
            .max_light_lines(2)
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
                .label(name.clone())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 16, y + 5)], c.mix(0.5).filled())
                });
        }
        legend(&mut chart)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}
