//! The radar chart of paper Figure 5: one axis per parameter, one polygon of z-scores
//! (SD from the healthy mean, eq. 18) per group or side, with missing values as gaps, clipped
//! values on the rim and abnormal ones marked by shape.

use plotters::prelude::*;

use super::{colour_of, perr, Fonts, PrintWidth};
use ldh_core::error::Result;

/// The start of the note [`radar_svg`] writes under a chart with clipped values.
pub const RADAR_CLIPPED: &str = "clipped at ±";

/// The scale label of [`radar_svg`] (drawn under the chart).
pub const RADAR_SCALE_LABEL: &str = "z-score (SD from the reference mean)";
/// The start of the note under [`radar_svg`] that gives the rings' values, centre to rim.
const RADAR_RINGS: &str = "rings, centre to rim: z = ";
/// z-scores beyond ± this are drawn on the rim of [`radar_svg`] and marked as clipped.
pub const RADAR_Z_CLIP: f64 = 4.0;
/// |z| above which a radar point is marked abnormal (outside mean ± 1.96 SD).
pub const RADAR_Z_ABNORMAL: f64 = 1.96;

/// The canvas width of [`radar_svg`], px.
const RADAR_W: u32 = 800;
/// How wide [`radar_svg`] prints.
pub const RADAR_PRINT: PrintWidth = PrintWidth::Chart;
/// The most characters of a note line under the chart (at the chart's label font).
const NOTE_LINE_CHARS: usize = 60;

/// A radar chart: one axis per parameter (`codes`), one polygon per series of z-scores, its
/// colour by series (left/right by hue). The scale runs from −zmax (centre) to +zmax (rim),
/// zmax the largest |z| rounded up, between 2 and [`RADAR_Z_CLIP`]; rings at −zmax, −zmax/2, 0,
/// zmax/2, zmax, the z = 0 ring (the healthy mean) in black. A missing (NaN) value leaves a gap
/// in its polygon (never drawn as 0); a value beyond the rim is drawn on the rim as an open
/// triangle (clipped) and named under the chart; |z| > [`RADAR_Z_ABNORMAL`] is marked with a
/// black-edged dot. The legend sits above the chart, clear of the data.
pub fn radar_svg(
    title: &str,
    codes: &[String],
    series: &[(super::SeriesName, Vec<f64>)],
) -> Result<String> {
    let f = Fonts::for_canvas(RADAR_W, RADAR_PRINT);
    let zabs = series
        .iter()
        .flat_map(|s| s.1.iter())
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let title_lines = wrap_title(title, f.title);
    // Each title line beyond the first moves the chart and its notes down by one line.
    let drop = (title_lines.len() as i32 - 1) * (f.title + 4);
    let g = Geometry::new(zabs.ceil().clamp(2.0, RADAR_Z_CLIP), codes.len(), drop);
    let clipped = clipped_values(codes, series, g.z_max);
    let notes = note_lines(g.z_max, &clipped);
    let notes_top = NOTES_TOP + drop;
    let height = notes_top as u32 + notes.len() as u32 * (f.label as u32 + 6) + 8;
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (RADAR_W, height)).into_drawing_area();
        root.fill(&WHITE).map_err(perr)?;
        for (k, line) in title_lines.iter().enumerate() {
            let y = 12 + k as i32 * (f.title + 4);
            root.draw(&Text::new(line.clone(), (20, y), font(f.title)))
                .map_err(perr)?;
        }
        draw_rings(&root, &g)?;
        draw_axes(&root, &g, codes, f)?;
        let mut x_legend = 20i32;
        let y_legend = 20 + f.title + drop;
        for (k, (name, z)) in series.iter().enumerate() {
            let c = colour_of(name, k);
            draw_polygon(&root, &g, z, c)?;
            for (i, &v) in z.iter().enumerate().filter(|(_, v)| v.is_finite()) {
                draw_point(&root, &g, i, v, c)?;
            }
            root.draw(&Rectangle::new(
                [
                    (x_legend, y_legend + 2),
                    (x_legend + 24, y_legend + f.label * 3 / 4),
                ],
                c.filled(),
            ))
            .map_err(perr)?;
            root.draw(&Text::new(
                name.to_string(),
                (x_legend + 32, y_legend),
                font(f.label),
            ))
            .map_err(perr)?;
            x_legend += 64 + f.label * 6 / 10 * name.chars().count() as i32;
        }
        for (k, line) in notes.iter().enumerate() {
            let y = notes_top + k as i32 * (f.label + 6);
            root.draw(&Text::new(line.clone(), (20, y), font(f.label)))
                .map_err(perr)?;
        }
        root.present().map_err(perr)?;
    }
    Ok(buf)
}

/// Where the notes under a radar chart start, px from the top (with a one-line title): below
/// a two-line axis name straight down (660 touched its second line).
const NOTES_TOP: i32 = 676;

/// The title in lines that fit the canvas at font size `size` (≈ 0.6 `size` px a character):
/// one line when it fits, else broken after its first ": " or, without one, at the space
/// nearest the middle. A long title ("Subject L01: z-scores against this cohort's healthy
/// subjects (n = 10)") was cut at the canvas's edge.
fn wrap_title(title: &str, size: i32) -> Vec<String> {
    let fits = ((RADAR_W as i32 - 40) / (size * 6 / 10).max(1)) as usize;
    if title.chars().count() <= fits {
        return vec![title.to_string()];
    }
    let at = title.find(": ").map(|i| (i + 1, i + 2)).or_else(|| {
        let mid = title.len() / 2;
        title
            .match_indices(' ')
            .map(|(i, _)| i)
            .min_by_key(|i| i.abs_diff(mid))
            .map(|i| (i, i + 1))
    });
    match at {
        Some((end, start)) => vec![title[..end].to_string(), title[start..].to_string()],
        None => vec![title.to_string()],
    }
}

/// The values beyond the rim `z_max`, named under the chart by the axis' readable name
/// ([`axis_name`]) on a person's legs, by its code on groups, and grouped by whose they are: (`"both legs"`, ["cadence -4.3"]) for a
/// value both legs' series share (a walk value drawn on both polygons), (`"left
/// (unaffected)"`, ["stance +4.2", …]) for the others, in series order. A simulated
/// hemiparetic walker's page read "left (unaffected) SF z = -4.3, … right (affected) SF z =
/// -4.3": codes, and the walk's one cadence twice.
fn clipped_values(
    codes: &[String],
    series: &[(super::SeriesName, Vec<f64>)],
    z_max: f64,
) -> Vec<(String, Vec<String>)> {
    let legs = series.len() == 2 && series.iter().all(|(n, _)| n.side.is_some());
    let shown = |v: f64| format!("{v:+.1}");
    let beyond = |v: f64| v.is_finite() && v.abs() > z_max;
    // An axis whose value every leg shares, clipped: named once, for both legs.
    let shared = |i: usize| {
        legs && series
            .iter()
            .all(|(_, z)| z.get(i).is_some_and(|v| beyond(*v)))
            && series
                .iter()
                .all(|(_, z)| shown(z[i]) == shown(series[0].1[i]))
    };
    // A person's legs are named in words (the clinical page names no codes); groups keep the
    // codes the cohort page's tables and box plots name them by (in words its note ran to 7
    // lines and pushed the demo's cohort page onto a third A4 page).
    let words = series.iter().any(|(n, _)| n.side.is_some());
    let name = |i: usize| {
        let code = codes.get(i).map_or("", String::as_str);
        if words {
            axis_name(code).join(" ")
        } else {
            code.to_string()
        }
    };
    let mut out = Vec::new();
    let both: Vec<String> = (0..codes.len())
        .filter(|&i| shared(i))
        .map(|i| format!("{} {}", name(i), shown(series[0].1[i])))
        .collect();
    if !both.is_empty() {
        out.push(("both legs".to_string(), both));
    }
    for (n, z) in series {
        let own: Vec<String> = z
            .iter()
            .enumerate()
            .filter(|&(i, v)| i < codes.len() && beyond(*v) && !shared(i))
            .map(|(i, v)| format!("{} {}", name(i), shown(*v)))
            .collect();
        if !own.is_empty() {
            out.push((n.to_string(), own));
        }
    }
    out
}

/// The lines under the chart: the scale, the rings' values (centre to rim) and, when values
/// were clipped, which ones ("clipped at ±4 SD, z-score:", then one group per line, "both
/// legs: cadence -4.3, walking speed -4.4", wrapped at [`NOTE_LINE_CHARS`]). The key to the
/// marks is in the figure's caption.
fn note_lines(z_max: f64, clipped: &[(String, Vec<String>)]) -> Vec<String> {
    let h = z_max / 2.0;
    let mut lines = vec![
        RADAR_SCALE_LABEL.to_string(),
        format!(
            "{RADAR_RINGS}{:+.1}, {:+.1}, 0 (black), {h:+.1}, {z_max:+.1}",
            -z_max, -h
        ),
    ];
    if clipped.is_empty() {
        return lines;
    }
    lines.push(format!("{RADAR_CLIPPED}{z_max:.0} SD, z-score:"));
    for (who, items) in clipped {
        let mut line = format!("{who}:");
        for (k, c) in items.iter().enumerate() {
            if line.chars().count() + c.chars().count() + 2 > NOTE_LINE_CHARS && k > 0 {
                lines.push(std::mem::take(&mut line) + ",");
                line = format!("  {c}");
                continue;
            }
            if k > 0 {
                line.push(',');
            }
            line.push(' ');
            line.push_str(c);
        }
        lines.push(line);
    }
    lines
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
    /// The chart's geometry (centre, radius) for a scale of ± `z_max` and `n_codes` axes,
    /// moved down by `drop` px (a title's extra lines).
    fn new(z_max: f64, n_codes: usize, drop: i32) -> Self {
        Geometry {
            cx: f64::from(RADAR_W) / 2.0,
            cy: 372.0 + f64::from(drop),
            rad: 230.0,
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

/// The rings at −zmax, −zmax/2, 0 (black: the reference mean), zmax/2 and zmax, their values
/// said in the notes under the chart ([`note_lines`]): a label on the chart ran into an axis's
/// name or a polygon wherever it stood.
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
    }
    Ok(())
}

/// The readable name of an axis: a parameter's name (from its definition, "stride time
/// variability") for its code, else the text as given; split in two lines at the space nearest
/// the middle when longer than 12 characters.
fn axis_name(code: &str) -> Vec<String> {
    let name = ldh_core::domain::Parameter::ALL
        .into_iter()
        .find(|p| p.code() == code)
        .map_or_else(|| code.to_string(), |p| p.name().to_string());
    if name.chars().count() <= 12 {
        return vec![name];
    }
    let mid = name.len() / 2;
    match name
        .match_indices(' ')
        .map(|(i, _)| i)
        .min_by_key(|i| i.abs_diff(mid))
    {
        Some(i) => vec![name[..i].to_string(), name[i + 1..].to_string()],
        None => vec![name],
    }
}

/// One spoke per parameter, its readable name ([`axis_name`]) beyond the rim, kept inside the
/// canvas.
fn draw_axes(root: &Area, g: &Geometry, codes: &[String], f: Fonts) -> Result<()> {
    for (i, c) in codes.iter().enumerate() {
        root.draw(&PathElement::new(
            vec![(g.cx as i32, g.cy as i32), g.pt(i, g.rad)],
            RGBColor(200, 200, 200),
        ))
        .map_err(perr)?;
        let lines = axis_name(c);
        let (x, y) = g.pt(i, g.rad + f64::from(f.label) * 1.3);
        let top = y - f.label / 2 - (lines.len() as i32 - 1) * f.label / 2;
        for (k, line) in lines.iter().enumerate() {
            let w = f.label * 6 / 10 * line.chars().count() as i32;
            let left = (x - w / 2).clamp(2, RADAR_W as i32 - w - 2);
            root.draw(&Text::new(
                line.clone(),
                (left, top + k as i32 * (f.label + 2)),
                font(f.label),
            ))
            .map_err(perr)?;
        }
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
