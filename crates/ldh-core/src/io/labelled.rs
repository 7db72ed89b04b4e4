//! Headers whose column names carry their units (docs/input.md, "Units in the header"):
//! `time (ms), Acc_X [m/s^2], ..., Gyr_Z (°/s)`, `GyrX/deg/s`, or names in one row and units in
//! the next (`time,acc_x,...` then `s,m/s^2,...` or `[s],[g],...`). Tried, when no format is
//! given, on a header-like row that no built-in format reads: the channel names are recognised
//! (`time`, `timestamp`; `acc`, `accel`, `accelerometer`, `acceleration` + axis; `gyr`, `gyro`,
//! `gyroscope`, `angular_velocity`, `angular_rate` + axis; case, `_`, `-`, `.` and spaces
//! ignored) and the units parsed by [`super::units`]; the result is the `ldh` map with those
//! columns and units.

use std::path::Path;

use super::columns::{resolve, Columns, Unresolved};
use super::format::{ColumnRef, FormatSpec};
use super::units::{is_unit, parse_for, split_label, Quantity, Unit, UnitError};
use crate::error::{LdhError, Location, Result};

/// A channel a recognised column name feeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Channel {
    /// Time.
    Time,
    /// Acceleration axis 0, 1, 2 (x, y, z).
    Acc(usize),
    /// Angular-rate axis 0, 1, 2.
    Gyro(usize),
}

impl Channel {
    fn quantity(self) -> Quantity {
        match self {
            Channel::Time => Quantity::Time,
            Channel::Acc(_) => Quantity::Acceleration,
            Channel::Gyro(_) => Quantity::AngularRate,
        }
    }
    /// Index in the order time, acc x y z, gyro x y z.
    fn slot(self) -> usize {
        match self {
            Channel::Time => 0,
            Channel::Acc(k) => 1 + k,
            Channel::Gyro(k) => 4 + k,
        }
    }
}

const ACC_NAMES: [&str; 5] = [
    "acc",
    "accel",
    "accelerometer",
    "acceleration",
    "accelerations",
];
const GYRO_NAMES: [&str; 6] = [
    "gyr",
    "gyro",
    "gyroscope",
    "angularvelocity",
    "angularrate",
    "angvel",
];

/// The channel a column name (without its unit) names, if any: `Acc_X`, `AccX`, `accel x`,
/// `GyrZ`, `gyro_z`, `time`, `Timestamp`.
fn channel_of(name: &str) -> Option<Channel> {
    let mut n = name.to_ascii_lowercase();
    n.retain(|c| !matches!(c, '_' | '-' | '.' | ' ' | '\t'));
    if matches!(n.as_str(), "time" | "timestamp" | "t") {
        return Some(Channel::Time);
    }
    let axis = match n.pop()? {
        'x' => 0,
        'y' => 1,
        'z' => 2,
        _ => return None,
    };
    if ACC_NAMES.contains(&n.as_str()) {
        Some(Channel::Acc(axis))
    } else if GYRO_NAMES.contains(&n.as_str()) {
        Some(Channel::Gyro(axis))
    } else {
        None
    }
}

/// What the labels of a header row say.
pub(super) enum Labelled {
    /// Not a header of recognised channel names (or some channel is missing).
    No,
    /// The names carry their units: the map and where its columns are.
    Found(Box<(FormatSpec, Columns)>),
    /// All seven channels named, none with a unit: the next row may be a units row.
    NeedsUnitsRow(Vec<usize>),
}

/// The seven columns (time, acc x y z, gyro x y z) of a header row, or `None` when one is
/// missing; a channel named twice is a [`LdhError::DuplicateColumn`].
fn positions(fields: &[String], path: &Path, line: u64) -> Result<Option<Vec<usize>>> {
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); 7];
    for (i, f) in fields.iter().enumerate() {
        if let Some(ch) = channel_of(split_label(f).0) {
            at[ch.slot()].push(i);
        }
    }
    if let Some(d) = at.iter().find(|p| p.len() > 1) {
        return Err(LdhError::DuplicateColumn {
            loc: Location::line(path, line),
            column: fields[d[0]].trim().to_string(),
            positions: d.iter().map(|i| i + 1).collect(),
        });
    }
    Ok(at.iter().map(|p| p.first().copied()).collect())
}

const SLOTS: [Channel; 7] = [
    Channel::Time,
    Channel::Acc(0),
    Channel::Acc(1),
    Channel::Acc(2),
    Channel::Gyro(0),
    Channel::Gyro(1),
    Channel::Gyro(2),
];

/// Read the header row `fields` (at `line`) as names with units. `base` is the `ldh` map the
/// result is made from (its delimiter, comments and axis map).
pub(super) fn labelled(
    base: &FormatSpec,
    fields: &[String],
    path: &Path,
    line: u64,
) -> Result<Labelled> {
    let Some(pos) = positions(fields, path, line)? else {
        return Ok(Labelled::No);
    };
    let texts: Vec<Option<&str>> = pos.iter().map(|&i| split_label(&fields[i]).1).collect();
    if texts.iter().all(Option::is_none) {
        return Ok(Labelled::NeedsUnitsRow(pos));
    }
    let mut units = Vec::with_capacity(7);
    for (k, (&i, text)) in pos.iter().zip(&texts).enumerate() {
        let ch = SLOTS[k];
        let loc = Location::cell(path, line, i + 1);
        let Some(text) = text else {
            return Err(unit_err(UnitError::Missing {
                loc,
                column: fields[i].trim().to_string(),
                quantity: ch.quantity(),
            }));
        };
        units.push(parse_for(text, ch.quantity(), fields[i].trim(), loc).map_err(unit_err)?);
    }
    build(base, fields, &pos, &units, path, line)
}

/// The header `fields` (at `line`) with its units in the next row, `units_row` (at
/// `units_line`): `Ok(None)` when that row is not a units row (it holds no unit ldh knows in
/// the columns read, or a number), else the map, or the [`UnitError`] of a cell that is not a
/// unit of its column.
pub(super) fn with_units_row(
    base: &FormatSpec,
    fields: &[String],
    pos: &[usize],
    units_row: &[String],
    lines: (u64, u64),
    path: &Path,
) -> Result<Option<(FormatSpec, Columns)>> {
    let (line, units_line) = lines;
    let cells: Vec<&str> = pos
        .iter()
        .map(|&i| units_row.get(i).map_or("", |c| c.trim()))
        .collect();
    let numeric = |c: &str| c.parse::<f64>().is_ok() || c.replace(',', ".").parse::<f64>().is_ok();
    if cells.iter().any(|c| numeric(c)) || !cells.iter().any(|c| is_unit(c)) {
        return Ok(None);
    }
    let mut units = Vec::with_capacity(7);
    for (k, (&i, cell)) in pos.iter().zip(&cells).enumerate() {
        let loc = Location::cell(path, units_line, i + 1);
        let q = SLOTS[k].quantity();
        if cell.is_empty() {
            return Err(unit_err(UnitError::Missing {
                loc,
                column: fields[i].trim().to_string(),
                quantity: q,
            }));
        }
        units.push(parse_for(cell, q, fields[i].trim(), loc).map_err(unit_err)?);
    }
    match build(base, fields, pos, &units, path, line)? {
        Labelled::Found(b) => Ok(Some(*b)),
        _ => Ok(None),
    }
}

fn unit_err(e: UnitError) -> LdhError {
    LdhError::Unit(Box::new(e))
}

/// The `ldh` map reading the columns at `pos` (time, acc x y z, gyro x y z) in `units`; the
/// three axes of a sensor must share a unit.
fn build(
    base: &FormatSpec,
    fields: &[String],
    pos: &[usize],
    units: &[Unit],
    path: &Path,
    line: u64,
) -> Result<Labelled> {
    for first in [1, 4] {
        for k in first + 1..first + 3 {
            if units[k] != units[first] {
                return Err(unit_err(UnitError::Mixed {
                    loc: Location::cell(path, line, pos[k] + 1),
                    column: fields[pos[k]].trim().to_string(),
                    unit: units[k],
                    first: fields[pos[first]].trim().to_string(),
                    first_unit: units[first],
                }));
            }
        }
    }
    let mut spec = base.clone();
    let name = |k: usize| ColumnRef::Name(fields[pos[k]].trim().to_string());
    spec.time.column = Some(name(0));
    spec.acc.columns = [name(1), name(2), name(3)];
    spec.gyro.columns = [name(4), name(5), name(6)];
    // Each unit's quantity was checked by `parse_for`.
    let (Some(t), Some(a), Some(g)) = (units[0].time(), units[1].acc(), units[4].gyro()) else {
        return Ok(Labelled::No);
    };
    spec.time.unit = t;
    spec.acc.unit = a;
    spec.gyro.unit = g;
    match resolve(&spec, fields) {
        Ok(cols) => Ok(Labelled::Found(Box::new((spec, cols)))),
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
