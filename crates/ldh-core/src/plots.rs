//! SVG figures of the cohort analysis (paper Figures 5–7): radar charts of the z-normalised
//! parameters per group and box plots per parameter and group. Drawn with plotters' SVG
//! backend (no system font libraries: text is laid out with plotters' built-in estimate and
//! rendered by the viewer). Sized for A4 width (800 px).

use plotters::prelude::*;

use crate::error::{LdhError, Result};

const COLORS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];

fn perr<E: std::fmt::Display>(e: E) -> LdhError {
    LdhError::signal("plot", e.to_string())
}

/// A radar chart: one axis per parameter (`codes`), one closed polygon per series of z-scores.
/// The scale runs from −zmax (centre) to +zmax (rim), zmax the largest |z| rounded up (2–20);
/// rings at −zmax, −zmax/2, 0, zmax/2, zmax, the z = 0 ring (the healthy mean) in black.
pub fn radar_svg(title: &str, codes: &[String], series: &[(String, Vec<f64>)]) -> Result<String> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (800, 720)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        let (w, h) = (800.0, 720.0);
        let (cx, cy, rad) = (w / 2.0, h / 2.0 + 20.0, 260.0);
        let zabs = series
            .iter()
            .flat_map(|s| s.1.iter())
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let z_max = zabs.ceil().clamp(2.0, 20.0);
        let z_min = -z_max;
        let to_r = |z: f64| (z.clamp(z_min, z_max) - z_min) / (z_max - z_min) * rad;
        let n = codes.len().max(1);
        let pt = |i: usize, r: f64| {
            let a = std::f64::consts::FRAC_PI_2 - i as f64 / n as f64 * std::f64::consts::TAU;
            ((cx + r * a.cos()) as i32, (cy - r * a.sin()) as i32)
        };
        root.draw(&Text::new(
            title.to_string(),
            (20, 15),
            ("sans-serif", 24).into_font(),
        ))
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
            root.draw(&Text::new(
                label,
                (x + 4, y - 14),
                ("sans-serif", 13).into_font(),
            ))
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
        for (k, (name, z)) in series.iter().enumerate() {
            let c = COLORS[k % COLORS.len()];
            let poly: Vec<(i32, i32)> = (0..=z.len())
                .map(|i| pt(i % z.len().max(1), to_r(z[i % z.len().max(1)])))
                .collect();
            root.draw(&PathElement::new(poly, c.stroke_width(3)))
                .map_err(perr)?;
            root.draw(&Rectangle::new(
                [(20, 50 + 24 * k as i32), (40, 64 + 24 * k as i32)],
                c.filled(),
            ))
            .map_err(perr)?;
            root.draw(&Text::new(
                name.clone(),
                (48, 48 + 24 * k as i32),
                ("sans-serif", 16).into_font(),
            ))
            .map_err(perr)?;
        }
        root.draw(&Text::new(
            "z-score against the healthy baseline (eq. 18): (x − mean_H) / SD_H".to_string(),
            (20, 690),
            ("sans-serif", 14).into_font(),
        ))
        .map_err(perr)?;
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
            .x_desc("group")
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
mod tests {
    use super::*;

    #[test]
    fn svgs_have_titles_labels_and_shapes() {
        let r = radar_svg(
            "Fusion",
            &["SF".into(), "SL".into(), "ST".into()],
            &[
                ("LDHE".into(), vec![-1.0, -2.0, 1.5]),
                ("H".into(), vec![0.0; 3]),
            ],
        )
        .unwrap();
        assert!(
            r.starts_with("<svg")
                && r.contains("LDHE")
                && r.contains("SL")
                && r.contains("z-score")
        );
        let b = boxplot_svg(
            "ST",
            "stride time (s)",
            &[
                ("LDHH".into(), vec![1.0, 1.1, 1.2, 1.05]),
                ("H".into(), vec![0.9, 1.0, 0.95]),
            ],
        )
        .unwrap();
        assert!(b.contains("stride time (s)") && b.contains("group") && b.contains("LDHH"));
        assert!(boxplot_svg("x", "y", &[("A".into(), vec![])]).is_err());
    }
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
            "predicted class".to_string(),
            (left, top - 45),
            ("sans-serif", 15).into_font(),
        ))
        .map_err(perr)?;
        root.draw(&Text::new(
            "true class".to_string(),
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
