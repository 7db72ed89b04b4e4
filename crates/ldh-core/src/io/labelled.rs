//! Headers read without a map (docs/input.md, "Units in the header" and "Exports read without
//! a map"): vendor exports whose names `recognise.rs` recognises, with units in the names
//! (`time (ms), Acc_X [m/s^2], ..., Gyr_Z (°/s)`, `GyrX/deg/s`, `acc_x_mps2`), in a row under
//! the names (`time,acc_x,...` then `s,m/s^2,...` or `[s],[g],...`; Shimmer's `CAL` row
//! between is skipped), implied by the name (`gFx`: g) or not at all (then inferred from the
//! signal: `infer.rs`). Tried, when no format is given, on a header-like row that no built-in
//! format reads; the result is the `ldh` map with those columns and units, named after the
//! exporter the names suggest.

use std::path::Path;

use super::columns::{resolve, Columns, Unresolved};
use super::format::{ColumnRef, FormatSpec};
use super::infer::{Infer, TimeGuess};
use super::recognise::{exporter, recognise, Channel, Implied, Recognised};
use super::units::{is_unit, parse_for, split_label, Quantity, Unit, UnitError};
use crate::error::{LdhError, Location, Result};

/// The recognised column of each of the seven slots (time, acc x y z, gyro x y z), or `None`
/// when one is missing; two cells claiming a slot with the same rank are a
/// [`LdhError::DuplicateColumn`] (a lower rank gives way: Shimmer's wide-range accelerometer to
/// its low-noise one).
fn positions(
    fields: &[String],
    path: &Path,
    line: u64,
) -> Result<Option<Vec<(usize, Recognised)>>> {
    let mut at: Vec<Vec<(usize, Recognised)>> = vec![Vec::new(); 7];
    for (i, f) in fields.iter().enumerate() {
        if let Some(r) = recognise(f) {
            at[r.channel.slot()].push((i, r));
        }
    }
    let mut out = Vec::with_capacity(7);
    for mut cells in at {
        let Some(best) = cells.iter().map(|(_, r)| r.rank).max() else {
            return Ok(None);
        };
        cells.retain(|(_, r)| r.rank == best);
        if cells.len() > 1 {
            return Err(LdhError::DuplicateColumn {
                loc: Location::line(path, line),
                column: fields[cells[0].0].trim().to_string(),
                positions: cells.iter().map(|(i, _)| i + 1).collect(),
            });
        }
        out.push(cells.swap_remove(0));
    }
    Ok(Some(out))
}

const SLOTS: [Quantity; 7] = [
    Quantity::Time,
    Quantity::Acceleration,
    Quantity::Acceleration,
    Quantity::Acceleration,
    Quantity::AngularRate,
    Quantity::AngularRate,
    Quantity::AngularRate,
];

/// What the recogniser finds in a header row that lacks a channel, for the message when no
/// format fits: `time (timestamp), acceleration (ax, ay, az); no angular rate`; `None` when it
/// finds nothing.
pub(super) fn partial(fields: &[String]) -> Option<String> {
    let mut found: [Vec<&str>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    for f in fields {
        if let Some(r) = recognise(f) {
            let k = match r.channel {
                Channel::Time => 0,
                Channel::Acc(_) => 1,
                Channel::Gyro(_) => 2,
            };
            found[k].push(f.trim());
        }
    }
    if found.iter().all(Vec::is_empty) {
        return None;
    }
    let names = ["time", "acceleration", "angular rate"];
    let (mut has, mut lacks) = (Vec::new(), Vec::new());
    for (k, v) in found.iter().enumerate() {
        let want = if k == 0 { 1 } else { 3 };
        if v.len() >= want {
            has.push(format!("{} ({})", names[k], v.join(", ")));
        } else if v.is_empty() {
            lacks.push(format!("no {}", names[k]));
        } else {
            lacks.push(format!("{} only ({})", names[k], v.join(", ")));
        }
    }
    let has = if has.is_empty() {
        "nothing complete".to_string()
    } else {
        has.join(", ")
    };
    Some(if lacks.is_empty() {
        format!("the names read as {has}, but the row under them is neither units nor numbers split at the same delimiter")
    } else {
        format!("the names read as {has}; {}", lacks.join(", "))
    })
}

/// A recognised header: the map, where its columns are and which units are to be inferred.
pub(super) struct Found {
    /// The map (the `ldh` map with the header's columns and units).
    pub spec: FormatSpec,
    /// Where its columns are.
    pub cols: Columns,
    /// The units the header does not state.
    pub infer: Infer,
}

/// What the labels of a header row say.
pub(super) enum Labelled {
    /// Not a header of recognised channel names (or some channel is missing).
    No,
    /// The names recognised, with the units they state or imply (the others to infer).
    Found(Box<Found>),
    /// All seven channels named, none with a unit: the next row may be a units row.
    NeedsUnitsRow(Vec<(usize, Recognised)>),
}

/// Read the header row `fields` (at `line`) as recognised names, with units where they carry
/// them. `base` is the `ldh` map the result is made from (its delimiter and comments).
pub(super) fn labelled(
    base: &FormatSpec,
    fields: &[String],
    path: &Path,
    line: u64,
) -> Result<Labelled> {
    let Some(pos) = positions(fields, path, line)? else {
        return Ok(Labelled::No);
    };
    if pos
        .iter()
        .all(|(_, r)| r.unit_text.is_none() && r.implied.is_none())
    {
        return Ok(Labelled::NeedsUnitsRow(pos));
    }
    let mut units = Vec::with_capacity(7);
    for (k, (i, r)) in pos.iter().enumerate() {
        let loc = Location::cell(path, line, i + 1);
        units.push(match (&r.unit_text, r.implied) {
            (Some(t), _) => Some(parse_for(t, SLOTS[k], fields[*i].trim(), loc).map_err(unit_err)?),
            (None, Some(Implied::Unit(u))) => Some(u),
            _ => None,
        });
    }
    build(base, fields, &pos, &units, path, line)
}

/// Whether a row is a vendor's row of data kinds under the names (Shimmer's `CAL`), to be
/// skipped on the way to a units row.
pub(super) fn kinds_row(pos: &[(usize, Recognised)], row: &[String]) -> bool {
    pos.iter().all(|(i, _)| {
        row.get(*i).is_some_and(|c| {
            matches!(
                c.trim().to_ascii_uppercase().as_str(),
                "CAL" | "UNCAL" | "RAW"
            )
        })
    })
}

/// The header `fields` (at `line`) with its units in the next row, `units_row` (at
/// `units_line`): `Ok(None)` when that row is not a units row (it holds no unit ldh knows in
/// the columns read, or a number), else the map, or the [`UnitError`] of a cell that is not a
/// unit of its column. An empty cell leaves its unit to be inferred.
pub(super) fn with_units_row(
    base: &FormatSpec,
    fields: &[String],
    pos: &[(usize, Recognised)],
    units_row: &[String],
    lines: (u64, u64),
    path: &Path,
) -> Result<Option<Found>> {
    let (line, units_line) = lines;
    let cells: Vec<&str> = pos
        .iter()
        .map(|(i, _)| units_row.get(*i).map_or("", |c| c.trim()))
        .collect();
    let numeric = |c: &str| c.parse::<f64>().is_ok() || c.replace(',', ".").parse::<f64>().is_ok();
    if cells.iter().any(|c| numeric(c)) || !cells.iter().any(|c| is_unit(c)) {
        return Ok(None);
    }
    let mut units = Vec::with_capacity(7);
    for (k, ((i, _), cell)) in pos.iter().zip(&cells).enumerate() {
        let loc = Location::cell(path, units_line, i + 1);
        units.push(if cell.is_empty() {
            None
        } else {
            Some(parse_for(cell, SLOTS[k], fields[*i].trim(), loc).map_err(unit_err)?)
        });
    }
    match build(base, fields, pos, &units, path, line)? {
        Labelled::Found(b) => Ok(Some(*b)),
        _ => Ok(None),
    }
}

/// The header recognised with every unit left to infer (no unit in the names, no units row).
pub(super) fn all_inferred(
    base: &FormatSpec,
    fields: &[String],
    pos: &[(usize, Recognised)],
    path: &Path,
    line: u64,
) -> Result<Option<Found>> {
    match build(base, fields, pos, &[None; 7], path, line)? {
        Labelled::Found(b) => Ok(Some(*b)),
        _ => Ok(None),
    }
}

fn unit_err(e: UnitError) -> LdhError {
    LdhError::Unit(Box::new(e))
}

/// The unit the axes of one sensor (`slots`) state: the first stated, which the others must
/// share ([`UnitError::Mixed`]); `None` when none states one.
fn sensor_unit(
    slots: std::ops::Range<usize>,
    units: &[Option<Unit>],
    pos: &[(usize, Recognised)],
    fields: &[String],
    at: (&Path, u64),
) -> Result<Option<Unit>> {
    let mut first: Option<(usize, Unit)> = None;
    for k in slots {
        let Some(u) = units[k] else { continue };
        match first {
            None => first = Some((k, u)),
            Some((f, fu)) if fu != u => {
                return Err(unit_err(UnitError::Mixed {
                    loc: Location::cell(at.0, at.1, pos[k].0 + 1),
                    column: fields[pos[k].0].trim().to_string(),
                    unit: u,
                    first: fields[pos[f].0].trim().to_string(),
                    first_unit: fu,
                }))
            }
            _ => {}
        }
    }
    Ok(first.map(|(_, u)| u))
}

/// The `ldh` map reading the columns at `pos` (time, acc x y z, gyro x y z) in `units` (`None`:
/// to infer); the three axes of a sensor must share a unit. Named after the exporter the
/// names suggest; a Shimmer export takes the `shimmer-consensys` map's axes.
fn build(
    base: &FormatSpec,
    fields: &[String],
    pos: &[(usize, Recognised)],
    units: &[Option<Unit>],
    path: &Path,
    line: u64,
) -> Result<Labelled> {
    let acc = sensor_unit(1..4, units, pos, fields, (path, line))?;
    let gyro = sensor_unit(4..7, units, pos, fields, (path, line))?;
    let mut spec = base.clone();
    spec.name = exporter(fields).to_string();
    spec.description = "recognised from the column names".to_string();
    if spec.name == "shimmer" {
        if let Ok(sh) = FormatSpec::builtin("shimmer-consensys") {
            spec.axes = sh.axes;
        }
    }
    let name = |k: usize| ColumnRef::Name(fields[pos[k].0].trim().to_string());
    spec.time.column = Some(name(0));
    spec.acc.columns = [name(1), name(2), name(3)];
    spec.gyro.columns = [name(4), name(5), name(6)];
    let mut infer = Infer::default();
    // Each unit's quantity was checked by `parse_for`.
    match units[0].and_then(Unit::time) {
        Some(t) => spec.time.unit = t,
        None if pos[0].1.implied == Some(Implied::SampleTimeFine) => {
            infer.time = Some(TimeGuess::SampleTimeFine)
        }
        None => infer.time = Some(TimeGuess::Clock),
    }
    match acc.and_then(Unit::acc) {
        Some(a) => spec.acc.unit = a,
        None => infer.acc = true,
    }
    match gyro.and_then(Unit::gyro) {
        Some(g) => spec.gyro.unit = g,
        None => infer.gyro = true,
    }
    match resolve(&spec, fields) {
        Ok(cols) => Ok(Labelled::Found(Box::new(Found { spec, cols, infer }))),
        Err(Unresolved::Duplicate { column, positions }) => Err(LdhError::DuplicateColumn {
            loc: Location::line(path, line),
            column,
            positions,
        }),
        Err(Unresolved::Missing(_)) => Ok(Labelled::No),
    }
}

/// The header `fields` with the units cut off their names (`Acc_X [g]` → `Acc_X`), for a
/// given map whose names are written without units; `None` when no cell carries a unit.
pub(super) fn without_units(fields: &[String]) -> Option<Vec<String>> {
    let cut: Vec<String> = fields
        .iter()
        .map(|f| split_label(f).0.to_string())
        .collect();
    (cut.iter().zip(fields).any(|(c, f)| c != f.trim())).then_some(cut)
}

/// The unit a header cell states, if it carries one ldh knows.
pub(super) fn stated_unit(cell: &str) -> Option<Unit> {
    split_label(cell).1.and_then(|u| u.parse().ok())
}
