//! Figures of the cohort tables: box plots of one parameter per group (paper Figures 6–7) and
//! the classifiers' confusion matrix.

use plotters::prelude::*;

use super::{perr, Fonts, PrintWidth, COLORS};
use ldh_core::error::{LdhError, Result};

/// The axis labels of [`confusion_svg`].
pub const CONFUSION_LABELS: [&str; 2] = ["predicted class (count, % of row)", "true class (rows)"];

/// The canvas width of [`boxplot_svg`], px (five side by side across the page).
const BOX_W: u32 = 260;
/// The canvas height of [`boxplot_svg`] without its legend row, px.
const BOX_H: u32 = 190;
/// How wide [`boxplot_svg`] prints.
pub const BOX_PRINT: PrintWidth = PrintWidth::Fifth;
/// How wide [`confusion_svg`] prints (three side by side).
pub const CONFUSION_PRINT: PrintWidth = PrintWidth::Third;

/// Box plots of one parameter per group (quartiles, whiskers at 1.5 IQR), the groups in the
/// order given and told apart by colour (the series colours: blue, orange, green); `title`
/// names the parameter with its unit (the y axis has no other label: five of these stand side
/// by side). With `legend` the groups are also named in a row under the chart (for a file that
/// stands alone, without the report's caption).
pub fn boxplot_svg(title: &str, groups: &[(String, Vec<f64>)], legend: bool) -> Result<String> {
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
        let f = Fonts::for_canvas(BOX_W, BOX_PRINT);
        let legend_h = if legend { f.label as u32 + 12 } else { 0 };
        let whole =
            SVGBackend::with_string(&mut buf, (BOX_W, BOX_H + legend_h)).into_drawing_area();
        whole.fill(&WHITE).map_err(perr)?;
        let (root, under) = whole.split_vertically(BOX_H);
        if legend {
            let mut x = 6i32;
            for (k, name) in names.iter().enumerate() {
                let c = COLORS[k % COLORS.len()];
                under
                    .draw(&Rectangle::new(
                        [(x, 6), (x + f.label / 2, 6 + f.label / 2)],
                        c.filled(),
                    ))
                    .map_err(perr)?;
                under
                    .draw(&Text::new(
                        name.clone(),
                        (x + f.label * 2 / 3, 2),
                        ("sans-serif", f.label).into_font(),
                    ))
                    .map_err(perr)?;
                x += f.label + f.label * 6 / 10 * name.chars().count() as i32;
            }
        }
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", f.title))
            .margin(6)
            .x_label_area_size(8)
            .y_label_area_size(5 * f.label / 2)
            .build_cartesian_2d(
                names.as_slice().into_segmented(),
                (lo - pad) as f32..(hi + pad) as f32,
            )
            .map_err(perr)?;
        chart
            .configure_mesh()
            // The groups are told apart by colour (blue LDHH, orange LDHE, green H, as on the
            // radar; said in the caption): five charts side by side leave no room for names.
            .x_label_formatter(&|_| String::new())
            .label_style(("sans-serif", f.label))
            .y_labels(5)
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
                        .width(30)
                        .style(c.stroke_width(2)),
                ))
                .map_err(perr)?;
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// The canvas width of [`confusion_svg`], px, whatever the number of classes.
const CONFUSION_W: u32 = 600;

/// A confusion matrix (rows true, columns predicted) as an SVG heat map: in each cell the count
/// and, under it, the share of its row. The axis names are the figure's labels
/// ([`CONFUSION_LABELS`]), the column axis above the matrix, the row axis turned along the
/// left edge.
pub fn confusion_svg(title: &str, classes: &[String], m: &[Vec<usize>]) -> Result<String> {
    let k = classes.len().max(1) as i32;
    let f = Fonts::for_canvas(CONFUSION_W, CONFUSION_PRINT);
    let line = f.label + 6;
    let name_w =
        classes.iter().map(|c| c.chars().count()).max().unwrap_or(1) as i32 * f.label * 6 / 10;
    let (left, top) = (line + name_w + 12, 10 + f.title + 2 * line + 8);
    let cell = ((CONFUSION_W as i32 - left - 10) / k).max(2 * line);
    let h = (top + cell * k + 10) as u32;
    let max = m.iter().flatten().copied().max().unwrap_or(1).max(1) as f64;
    let font = |s: i32| ("sans-serif", s).into_font();
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (CONFUSION_W, h)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        root.draw(&Text::new(title.to_string(), (8, 8), font(f.title)))
            .map_err(perr)?;
        root.draw(&Text::new(
            CONFUSION_LABELS[0].to_string(),
            (8, 10 + f.title + 4),
            font(f.label),
        ))
        .map_err(perr)?;
        root.draw(&Text::new(
            CONFUSION_LABELS[1].to_string(),
            (4, top + cell * k),
            font(f.label).transform(FontTransform::Rotate270),
        ))
        .map_err(perr)?;
        for (i, name) in classes.iter().enumerate() {
            let x = left + cell * i as i32;
            root.draw(&Text::new(name.clone(), (x + 6, top - line), font(f.label)))
                .map_err(perr)?;
            let y = top + cell * i as i32 + cell / 2 - f.label / 2;
            root.draw(&Text::new(name.clone(), (line + 6, y), font(f.label)))
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
                let y0 = y + cell / 2 - line;
                root.draw(&Text::new(format!("{v}"), (x + 8, y0), font(f.label)))
                    .map_err(perr)?;
                root.draw(&Text::new(
                    format!("{pct:.0} %"),
                    (x + 8, y0 + line),
                    font(f.label),
                ))
                .map_err(perr)?;
            }
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}
