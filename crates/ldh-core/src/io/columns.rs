//! Column resolution: where a format's time, acceleration and angular-velocity columns are in a
//! header row (docs/input.md, "Column maps").
//!
//! A map names a column (case-insensitive), lists alternative names (the first present wins:
//! exports that spell the same column two ways) or gives its 1-based number. In a file holding
//! several sensors, `[sensor] prefix` is put before every name, and `[sensor] block = n` reads
//! the n-th occurrence of names the header repeats once per sensor. A name the map reads that
//! occurs twice in the header, without `block`, is refused: neither the first nor the last
//! may silently win.
//!
//! The default `ldh` format also accepts unit-suffixed names (`acc_x_g`, `acc_x_mps2`,
//! `acc_x_m_s2`, `gyro_x_dps`, `gyro_x_deg_s`, `gyro_x_rads`, `gyro_x_rad_s`, `time_s`,
//! `time_ms`), the names ldh's Python API writes; see [`unit_suffixed`].

use super::format::{AccUnit, ColumnRef, FormatSpec, GyroUnit, TimeUnit};

/// Positions (0-based) of the columns a format reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Columns {
    /// Time column, if the format has one.
    pub time: Option<usize>,
    /// Acceleration x, y, z.
    pub acc: [usize; 3],
    /// Angular velocity x, y, z.
    pub gyro: [usize; 3],
}

/// A column the map wants that the header lacks.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Missing {
    /// The column as the map gives it (`acc_x`, `RS_acc_x|acc_rs_x`, `#40`).
    pub wanted: String,
    /// The names accepted for it (prefix included), compared with the header for suggestions.
    pub names: Vec<String>,
}

/// Why a header row does not fit a format.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Unresolved {
    /// Columns not found.
    Missing(Vec<Missing>),
    /// A column the map reads occurs more than once (1-based positions).
    Duplicate {
        /// The column name.
        column: String,
        /// Where it occurs.
        positions: Vec<usize>,
    },
}

/// The missing columns and the header's closest names, for messages:
/// `["acc_x", "gyro_x"]` and `; closest in the header: acc_x → AccX; gyro_x → GyrX, Gyr_X`.
/// Header names the map itself reads are not suggested.
pub(crate) fn describe_missing(
    missing: &[Missing],
    header: &[String],
    spec: &FormatSpec,
) -> (Vec<String>, String) {
    let prefix = spec.sensor.prefix.as_str();
    let taken: Vec<String> = spec
        .time
        .column
        .iter()
        .chain(spec.acc.columns.iter())
        .chain(spec.gyro.columns.iter())
        .flat_map(|c| c.names().iter().map(|n| norm(&format!("{prefix}{n}"))))
        .collect();
    let free: Vec<String> = header
        .iter()
        .filter(|h| !taken.contains(&norm(h)))
        .cloned()
        .collect();
    let names = missing.iter().map(|m| m.wanted.clone()).collect();
    let close: Vec<String> = missing
        .iter()
        .filter_map(|m| {
            let c = closest(&m.names, &free);
            (!c.is_empty()).then(|| format!("{} → {}", m.wanted, c.join(", ")))
        })
        .collect();
    let hint = if close.is_empty() {
        String::new()
    } else {
        format!("; closest in the header: {}", close.join("; "))
    };
    (names, hint)
}

fn norm(s: &str) -> String {
    s.trim().to_ascii_lowercase()
}

/// Up to three header names closest to any of `wanted` (normalised Levenshtein similarity
/// ≥ 0.5 after lower-casing; ties keep header order).
fn closest(wanted: &[String], header: &[String]) -> Vec<String> {
    let mut scored: Vec<(f64, usize)> = header
        .iter()
        .enumerate()
        .filter(|(_, h)| !h.trim().is_empty())
        .map(|(i, h)| {
            let best = wanted
                .iter()
                .map(|w| strsim::normalized_levenshtein(&norm(w), &norm(h)))
                .fold(0.0, f64::max);
            (best, i)
        })
        .filter(|(s, _)| *s >= 0.5)
        .collect();
    scored.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut out: Vec<String> = Vec::new();
    for (_, i) in scored {
        if !out.contains(&header[i]) {
            out.push(header[i].clone());
        }
        if out.len() == 3 {
            break;
        }
    }
    out
}

/// Find one column reference in the header.
fn find(
    r: &ColumnRef,
    spec: &FormatSpec,
    header: &[String],
) -> std::result::Result<usize, Unresolved> {
    let prefix = spec.sensor.prefix.as_str();
    if let ColumnRef::Index(i) = r {
        return if (1..=header.len()).contains(i) {
            Ok(i - 1)
        } else {
            Err(Unresolved::Missing(vec![Missing {
                wanted: format!("#{i} (the row has {} columns)", header.len()),
                names: Vec::new(),
            }]))
        };
    }
    for name in r.names() {
        let want = norm(&format!("{prefix}{name}"));
        let at: Vec<usize> = header
            .iter()
            .enumerate()
            .filter(|(_, h)| norm(h) == want)
            .map(|(i, _)| i)
            .collect();
        match (at.len(), spec.sensor.block) {
            (0, _) => continue,
            (_, Some(b)) if b >= 1 && at.len() >= b => return Ok(at[b - 1]),
            (_, Some(_)) => continue,
            (1, None) => return Ok(at[0]),
            (_, None) => {
                return Err(Unresolved::Duplicate {
                    column: header[at[0]].trim().to_string(),
                    positions: at.iter().map(|i| i + 1).collect(),
                })
            }
        }
    }
    let mut what = r.describe(prefix);
    if let Some(b) = spec.sensor.block {
        what.push_str(&format!(" (block {b})"));
    }
    Err(Unresolved::Missing(vec![Missing {
        wanted: what,
        names: r.names().iter().map(|n| format!("{prefix}{n}")).collect(),
    }]))
}

/// Locate every column `spec` reads in `header`. A duplicate is reported before missing
/// columns (it means the row is the header but cannot be read unambiguously).
pub(crate) fn resolve(
    spec: &FormatSpec,
    header: &[String],
) -> std::result::Result<Columns, Unresolved> {
    let mut missing = Vec::new();
    let mut get = |r: &ColumnRef| -> std::result::Result<usize, Unresolved> {
        match find(r, spec, header) {
            Ok(i) => Ok(i),
            Err(Unresolved::Missing(m)) => {
                missing.extend(m);
                Ok(usize::MAX)
            }
            Err(d) => Err(d),
        }
    };
    let time = spec.time.column.as_ref().map(&mut get).transpose()?;
    let mut acc = [0; 3];
    for (k, r) in spec.acc.columns.iter().enumerate() {
        acc[k] = get(r)?;
    }
    let mut gyro = [0; 3];
    for (k, r) in spec.gyro.columns.iter().enumerate() {
        gyro[k] = get(r)?;
    }
    if !missing.is_empty() {
        return Err(Unresolved::Missing(missing));
    }
    Ok(Columns { time, acc, gyro })
}

/// Whether every column of `spec` is given by number (such a map can read files without a
/// header row).
pub(crate) fn all_by_index(spec: &FormatSpec) -> bool {
    spec.time
        .column
        .iter()
        .chain(spec.acc.columns.iter())
        .chain(spec.gyro.columns.iter())
        .all(|c| matches!(c, ColumnRef::Index(_)))
}

const ACC_SUFFIXES: [(&str, AccUnit); 3] = [
    ("_g", AccUnit::G),
    ("_mps2", AccUnit::Mps2),
    ("_m_s2", AccUnit::Mps2),
];
const GYRO_SUFFIXES: [(&str, GyroUnit); 4] = [
    ("_dps", GyroUnit::Dps),
    ("_deg_s", GyroUnit::Dps),
    ("_rads", GyroUnit::Rps),
    ("_rad_s", GyroUnit::Rps),
];

/// The `ldh` format adapted to a header whose names carry their units (`time_ms`,
/// `acc_x_mps2`, `gyro_x_rad_s`...): the same map with those columns and units, or `None` when
/// `spec` is not the default `ldh` map or the header has no complete unit-suffixed set.
pub(crate) fn unit_suffixed(spec: &FormatSpec, header: &[String]) -> Option<FormatSpec> {
    if spec.name != "ldh" || spec.acc.columns != ["acc_x", "acc_y", "acc_z"].map(ColumnRef::from) {
        return None;
    }
    let has = |n: &str| header.iter().any(|h| norm(h) == n);
    let mut out = spec.clone();
    let mut changed = false;
    if !has("time_s") && has("time_ms") {
        out.time.column = Some("time_ms".into());
        out.time.unit = TimeUnit::Milliseconds;
        changed = true;
    }
    let axes = ["x", "y", "z"];
    if !axes.iter().all(|a| has(&format!("acc_{a}"))) {
        let (suf, unit) = ACC_SUFFIXES
            .iter()
            .find(|(s, _)| axes.iter().all(|a| has(&format!("acc_{a}{s}"))))?;
        out.acc.columns = axes.map(|a| ColumnRef::Name(format!("acc_{a}{suf}")));
        out.acc.unit = *unit;
        changed = true;
    }
    if !axes.iter().all(|a| has(&format!("gyro_{a}"))) {
        let (suf, unit) = GYRO_SUFFIXES
            .iter()
            .find(|(s, _)| axes.iter().all(|a| has(&format!("gyro_{a}{s}"))))?;
        out.gyro.columns = axes.map(|a| ColumnRef::Name(format!("gyro_{a}{suf}")));
        out.gyro.unit = *unit;
        changed = true;
    }
    changed.then_some(out)
}
