//! Figures of the cohort tables: box plots of one parameter per group (paper Figures 6–7) and
//! the classifiers' confusion matrix.

use plotters::prelude::*;

use super::{perr, COLORS};
use crate::error::{LdhError, Result};

/// The x-axis label of [`boxplot_svg`].
pub const BOX_GROUP_LABEL: &str = "group (LDHH, LDHE, H)";
/// The axis labels of [`confusion_svg`].
pub const CONFUSION_LABELS: [&str; 2] = ["predicted class (count, % of row)", "true class (rows)"];

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
