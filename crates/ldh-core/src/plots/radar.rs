//! The radar chart of paper Figure 5: one axis per parameter, one polygon of z-scores
//! (SD from the healthy mean, eq. 18) per group or side, with missing values as gaps, clipped
//! values on the rim and abnormal ones marked by shape.

use plotters::prelude::*;

use super::{colour_of, perr};
use crate::error::Result;

/// The start of the note [`radar_svg`] writes under a chart with clipped values.
pub const RADAR_CLIPPED: &str = "clipped at ±";

/// The scale label of [`radar_svg`] (drawn under the chart).
pub const RADAR_SCALE_LABEL: &str = "z-score (SD from the healthy mean)";
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
        let zabs = series
            .iter()
            .flat_map(|s| s.1.iter())
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let g = Geometry::new(zabs.ceil().clamp(2.0, RADAR_Z_CLIP), codes.len());
        root.draw(&Text::new(title.to_string(), (20, 15), font(24)))
            .map_err(perr)?;
        draw_rings(&root, &g)?;
        draw_axes(&root, &g, codes)?;
        let mut clipped: Vec<String> = Vec::new();
        let mut x_legend = 20i32;
        for (k, (name, z)) in series.iter().enumerate() {
            let c = colour_of(name, k);
            draw_polygon(&root, &g, z, c)?;
            for (i, &v) in z.iter().enumerate().filter(|(_, v)| v.is_finite()) {
                if draw_point(&root, &g, i, v, c)? {
                    clipped.push(format!(
                        "{name} {} z = {v:+.1}",
                        codes.get(i).map(String::as_str).unwrap_or("")
                    ));
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
        draw_notes(&root, g.z_max, &clipped)?;
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// The drawing area of a radar chart.
type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// The radar's text font at size `s`.
fn font(s: i32) -> FontDesc<'static> {
    ("sans-serif", s).into_font()
}

/// Where a radar chart puts things: centre, radius and the z scale from −`z_max` (centre) to
/// `z_max` (rim) over `n` axes.
struct Geometry {
    cx: f64,
    cy: f64,
    rad: f64,
    z_min: f64,
    z_max: f64,
    n: usize,
}

impl Geometry {
    /// The 800 × 720 chart's geometry for a scale of ± `z_max` and `n_codes` axes.
    fn new(z_max: f64, n_codes: usize) -> Self {
        let (w, h) = (800.0, 720.0);
        Geometry {
            cx: w / 2.0,
            cy: h / 2.0 + 30.0,
            rad: 250.0,
            z_min: -z_max,
            z_max,
            n: n_codes.max(1),
        }
    }

    /// The radius of z (clamped to the scale), px.
    fn to_r(&self, z: f64) -> f64 {
        (z.clamp(self.z_min, self.z_max) - self.z_min) / (self.z_max - self.z_min) * self.rad
    }

    /// The pixel at radius `r` on axis `i` (axis 0 points up, clockwise).
    fn pt(&self, i: usize, r: f64) -> (i32, i32) {
        let a = std::f64::consts::FRAC_PI_2 - i as f64 / self.n as f64 * std::f64::consts::TAU;
        (
            (self.cx + r * a.cos()) as i32,
            (self.cy - r * a.sin()) as i32,
        )
    }
}

/// The rings at −zmax, −zmax/2, 0 (black: the healthy mean), zmax/2 and zmax, labelled on axis 0.
fn draw_rings(root: &Area, g: &Geometry) -> Result<()> {
    let z_max = g.z_max;
    for z in [-z_max, -z_max / 2.0, 0.0, z_max / 2.0, z_max] {
        let ring: Vec<(i32, i32)> = (0..=g.n).map(|i| g.pt(i % g.n, g.to_r(z))).collect();
        let style = if z == 0.0 {
            BLACK.stroke_width(2)
        } else {
            RGBColor(180, 180, 180).stroke_width(1)
        };
        root.draw(&PathElement::new(ring, style)).map_err(perr)?;
        let (x, y) = g.pt(0, g.to_r(z));
        let label = if z == 0.0 {
            "z = 0 (healthy mean)".to_string()
        } else {
            format!("z = {z:+.1}")
        };
        root.draw(&Text::new(label, (x + 4, y - 14), font(13)))
            .map_err(perr)?;
    }
    Ok(())
}

/// One spoke per parameter, its code beyond the rim.
fn draw_axes(root: &Area, g: &Geometry, codes: &[String]) -> Result<()> {
    for (i, c) in codes.iter().enumerate() {
        root.draw(&PathElement::new(
            vec![(g.cx as i32, g.cy as i32), g.pt(i, g.rad)],
            RGBColor(200, 200, 200),
        ))
        .map_err(perr)?;
        let (x, y) = g.pt(i, g.rad + 22.0);
        root.draw(&Text::new(
            c.clone(),
            (x - 14, y - 8),
            ("sans-serif", 16).into_font(),
        ))
        .map_err(perr)?;
    }
    Ok(())
}

/// A series' polygon: segments between neighbouring axes that both have a value, a gap where
/// one is missing (a missing value is never drawn as 0).
fn draw_polygon(root: &Area, g: &Geometry, z: &[f64], c: RGBColor) -> Result<()> {
    let m = z.len();
    for i in 0..m {
        let j = (i + 1) % m;
        if m > 1 && z[i].is_finite() && z[j].is_finite() {
            root.draw(&PathElement::new(
                vec![g.pt(i, g.to_r(z[i])), g.pt(j, g.to_r(z[j]))],
                c.stroke_width(3),
            ))
            .map_err(perr)?;
        }
    }
    Ok(())
}

/// The point of value `v` on axis `i`: an open triangle on the rim when clipped (returns true),
/// a black-edged dot when abnormal, a plain dot otherwise.
fn draw_point(root: &Area, g: &Geometry, i: usize, v: f64, c: RGBColor) -> Result<bool> {
    let p = g.pt(i, g.to_r(v));
    if v.abs() > g.z_max {
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
        return Ok(true);
    }
    if v.abs() > RADAR_Z_ABNORMAL {
        root.draw(&Circle::new(p, 6, BLACK.filled()))
            .map_err(perr)?;
        root.draw(&Circle::new(p, 4, c.filled())).map_err(perr)?;
    } else {
        root.draw(&Circle::new(p, 3, c.filled())).map_err(perr)?;
    }
    Ok(false)
}

/// The key to the marks, the scale label and, when values were clipped, which ones.
fn draw_notes(root: &Area, z_max: f64, clipped: &[String]) -> Result<()> {
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
    Ok(())
}
