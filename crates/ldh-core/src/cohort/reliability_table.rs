//! The test–retest reliability table: one row per gait parameter ([`ReliabilityRow`]), the file
//! `reliability.csv` that `ldh stats --reliability` writes and that marking changes between
//! visits reads back ([`ReliabilityTable::read`], [`ReliabilityTable::mdc95`]).
//!
//! Each row carries what [`crate::stats::agreement::test_retest`] computes for one parameter (ICC(2,1) and
//! ICC(3,1) with their intervals after Shrout & Fleiss 1979 / McGraw & Wong 1996, the SEM and
//! MDC95 after Weir 2005, the root-mean-square within-subject CV after Glüer et al. 1995, and
//! the one-way variance components), or, when it cannot be computed, the reason in plain words
//! in `withheld` and empty numeric cells. The columns, in this order, are [`COLUMNS`]; the
//! format is described column by column in `docs/agreement.md`, "Reliability table".

use std::collections::HashMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Location, Result};
use crate::io::table::{Row, Table, TableFormat};
use crate::output::Parameter;

/// The columns of `reliability.csv`, in order.
pub const COLUMNS: [&str; 19] = [
    "parameter",
    "code",
    "unit",
    "n_subjects",
    "k_trials",
    "icc_2_1",
    "icc_2_1_ci_low",
    "icc_2_1_ci_high",
    "icc_3_1",
    "icc_3_1_ci_low",
    "icc_3_1_ci_high",
    "sd_all",
    "sem",
    "sem_from_mse",
    "mdc95",
    "within_subject_cv",
    "between_subject_var",
    "within_subject_var",
    "withheld",
];

/// Test–retest reliability of one parameter (a row of `reliability.csv`). Values are in the
/// parameter's `unit` (variances in its square; the CV and the ICCs without unit). When
/// `withheld` is not empty every `Option` is `None` (an empty cell).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReliabilityRow {
    /// The parameter's column in `recordings.csv` (`stride_time_s`).
    pub parameter: String,
    /// Its code (`ST`).
    pub code: String,
    /// Its unit (`s`).
    pub unit: String,
    /// People with a value in each of the `k_trials` trials (those the statistics use).
    pub n_subjects: usize,
    /// Trials per person, k.
    pub k_trials: usize,
    /// ICC(2,1), two-way random, absolute agreement, single measurement.
    pub icc_2_1: Option<f64>,
    /// Lower end of its confidence interval.
    pub icc_2_1_ci_low: Option<f64>,
    /// Upper end of its confidence interval.
    pub icc_2_1_ci_high: Option<f64>,
    /// ICC(3,1), two-way mixed, consistency, single measurement.
    pub icc_3_1: Option<f64>,
    /// Lower end of its confidence interval.
    pub icc_3_1_ci_low: Option<f64>,
    /// Upper end of its confidence interval.
    pub icc_3_1_ci_high: Option<f64>,
    /// Sample SD (ddof = 1) of all n·k values.
    pub sd_all: Option<f64>,
    /// SEM = `sd_all`·√(1 − ICC(2,1)) (Weir 2005).
    pub sem: Option<f64>,
    /// √MSE, the SEM that does not depend on an ICC.
    pub sem_from_mse: Option<f64>,
    /// MDC95 = 1.96·√2·`sem`: the smallest change between two visits of one person that is
    /// real with 95 % confidence.
    pub mdc95: Option<f64>,
    /// Root-mean-square within-subject CV (a fraction); also `None` when a person's mean is
    /// not > 0 while the rest is computed.
    pub within_subject_cv: Option<f64>,
    /// Between-subject variance of the one-way model, (MSB − MSW)/k (not truncated at 0).
    pub between_subject_var: Option<f64>,
    /// Within-subject variance of the one-way model, MSW.
    pub within_subject_var: Option<f64>,
    /// Empty when computed; else why not, in plain words.
    pub withheld: String,
}

impl ReliabilityRow {
    /// A row for `p` that could not be computed, for `reason`.
    pub fn withheld(p: Parameter, n_subjects: usize, k_trials: usize, reason: String) -> Self {
        ReliabilityRow {
            parameter: p.column().to_string(),
            code: p.code().to_string(),
            unit: p.unit().to_string(),
            n_subjects,
            k_trials,
            icc_2_1: None,
            icc_2_1_ci_low: None,
            icc_2_1_ci_high: None,
            icc_3_1: None,
            icc_3_1_ci_low: None,
            icc_3_1_ci_high: None,
            sd_all: None,
            sem: None,
            sem_from_mse: None,
            mdc95: None,
            within_subject_cv: None,
            between_subject_var: None,
            within_subject_var: None,
            withheld: reason,
        }
    }

    /// A computed row for `p`.
    pub fn computed(p: Parameter, r: &crate::stats::agreement::Reliability) -> Self {
        ReliabilityRow {
            icc_2_1: Some(r.icc.icc_2_1.value),
            icc_2_1_ci_low: Some(r.icc.icc_2_1.ci_low),
            icc_2_1_ci_high: Some(r.icc.icc_2_1.ci_high),
            icc_3_1: Some(r.icc.icc_3_1.value),
            icc_3_1_ci_low: Some(r.icc.icc_3_1.ci_low),
            icc_3_1_ci_high: Some(r.icc.icc_3_1.ci_high),
            sd_all: Some(r.sd_all),
            sem: Some(r.sem),
            sem_from_mse: Some(r.sem_from_mse),
            mdc95: Some(r.mdc95),
            within_subject_cv: r.within_subject_cv,
            between_subject_var: Some(r.variance.between_subject),
            within_subject_var: Some(r.variance.within_subject),
            ..ReliabilityRow::withheld(p, r.n_subjects, r.k_trials, String::new())
        }
    }

    /// The numeric cells in the order of [`COLUMNS`] (from `icc_2_1` to `within_subject_var`).
    fn numbers_mut(&mut self) -> [&mut Option<f64>; 13] {
        [
            &mut self.icc_2_1,
            &mut self.icc_2_1_ci_low,
            &mut self.icc_2_1_ci_high,
            &mut self.icc_3_1,
            &mut self.icc_3_1_ci_low,
            &mut self.icc_3_1_ci_high,
            &mut self.sd_all,
            &mut self.sem,
            &mut self.sem_from_mse,
            &mut self.mdc95,
            &mut self.within_subject_cv,
            &mut self.between_subject_var,
            &mut self.within_subject_var,
        ]
    }
}

/// The reliability of every parameter (`reliability.csv`), one row per parameter.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ReliabilityTable {
    /// The rows, in the order of [`Parameter::ALL`] when ldh wrote them.
    pub rows: Vec<ReliabilityRow>,
}

impl ReliabilityTable {
    /// The row of `p`, if the table has one.
    pub fn row(&self, p: Parameter) -> Option<&ReliabilityRow> {
        self.rows.iter().find(|r| r.parameter == p.column())
    }

    /// The MDC95 of `p` in its unit; `None` when the table has no row for it or it was withheld.
    pub fn mdc95(&self, p: Parameter) -> Option<f64> {
        self.row(p).and_then(|r| r.mdc95)
    }

    /// The table as CSV text (header [`COLUMNS`], numbers in shortest round-trip form, `None`
    /// as an empty cell).
    pub fn to_csv(&self) -> Result<String> {
        let mut w = csv::Writer::from_writer(Vec::new());
        for r in &self.rows {
            w.serialize(r)?;
        }
        if self.rows.is_empty() {
            w.write_record(COLUMNS)?;
        }
        let bytes = w.into_inner().map_err(|e| LdhError::Write {
            path: "reliability.csv".into(),
            reason: e.to_string(),
        })?;
        Ok(String::from_utf8(bytes).expect("csv of UTF-8 strings is UTF-8"))
    }

    /// Read `reliability.csv`. Errors name the file, line and column: a missing or unknown
    /// column, an unknown parameter or one listed twice, a code or unit that is not the
    /// parameter's, a cell that is not a number (or not finite), a negative `mdc95`, SEM or
    /// variance of the one-way model's within part, numbers beside a `withheld` reason, and a
    /// file without rows.
    pub fn read(path: &Path) -> Result<ReliabilityTable> {
        let text = crate::io::read_text_limited(path, crate::io::MAX_TABLE_MB, "a table")?;
        if text.trim().is_empty() {
            return Err(LdhError::EmptyFile {
                path: path.to_path_buf(),
            });
        }
        let table =
            Table::parse(&text, path, &TableFormat::default()).map_err(|f| f.into_error(""))?;
        check_header(&table)?;
        let mut rows = Vec::new();
        let mut seen: HashMap<Parameter, u64> = HashMap::new();
        for cell in table.rows() {
            let cell = cell.map_err(|f| f.into_error(""))?;
            let row = row_of(&cell)?;
            let p = Parameter::from_column(&row.parameter).expect("checked by row_of");
            if let Some(first) = seen.insert(p, cell.line) {
                return Err(cell.invalid(
                    "parameter",
                    format!("a parameter not listed before (it is on line {first})"),
                ));
            }
            rows.push(row);
        }
        if rows.is_empty() {
            return Err(LdhError::InvalidValue {
                loc: Location::line(path, 2),
                column: "parameter".into(),
                value: String::new(),
                expected: "one row per parameter under the header (the table has none)".into(),
            });
        }
        Ok(ReliabilityTable { rows })
    }
}

/// Refuse an unknown, repeated or missing column of [`COLUMNS`].
fn check_header(table: &Table) -> Result<()> {
    let (path, line) = (&table.path, table.header_line);
    for (i, name) in table.header.iter().enumerate() {
        if !COLUMNS.contains(&name.as_str()) {
            return Err(LdhError::UnknownColumn {
                loc: table.header_cell(i),
                column: name.to_string(),
                what: "a reliability table".into(),
                accepted: COLUMNS.join(", "),
            });
        };
        if let Some(first) = table.column(name).filter(|&first| first < i) {
            return Err(LdhError::DuplicateColumn {
                loc: Location::line(path, line),
                column: name.to_string(),
                positions: vec![first + 1, i + 1],
            });
        }
    }
    let missing: Vec<String> = COLUMNS
        .iter()
        .filter(|c| table.column(c).is_none())
        .map(|c| c.to_string())
        .collect();
    if !missing.is_empty() {
        return Err(LdhError::MissingColumn {
            loc: Location::line(path, line),
            missing,
            by: "a reliability table (ldh stats --reliability)".into(),
        });
    }
    Ok(())
}

/// One row of the table, checked.
fn row_of(cell: &Row) -> Result<ReliabilityRow> {
    let p = Parameter::from_column(cell.get("parameter")).map_err(|_| {
        cell.invalid(
            "parameter",
            format!(
                "a parameter column, one of {}",
                Parameter::columns().join(", ")
            ),
        )
    })?;
    for (name, want) in [("code", p.code()), ("unit", p.unit())] {
        if cell.get(name) != want {
            return Err(cell.invalid(name, format!("'{want}', the {name} of {}", p.column())));
        }
    }
    let count = |name: &str| {
        cell.get(name)
            .parse::<usize>()
            .map_err(|_| cell.invalid(name, "a whole number ≥ 0"))
    };
    let mut row = ReliabilityRow::withheld(
        p,
        count("n_subjects")?,
        count("k_trials")?,
        cell.get("withheld").to_string(),
    );
    for (slot, name) in row.numbers_mut().into_iter().zip(&COLUMNS[5..18]) {
        *slot = cell.number(name)?;
    }
    for name in [
        "sd_all",
        "sem",
        "sem_from_mse",
        "mdc95",
        "within_subject_cv",
        "within_subject_var",
    ] {
        if cell.number(name)?.is_some_and(|v| v < 0.0) {
            return Err(cell.invalid(name, "a number ≥ 0"));
        }
    }
    if !row.withheld.is_empty() {
        if let Some(name) = COLUMNS[5..18].iter().find(|n| !cell.get(n).is_empty()) {
            return Err(cell.invalid(
                name,
                "an empty cell: the row is withheld (its withheld column gives a reason)",
            ));
        }
    }
    Ok(row)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> ReliabilityTable {
        let mut st = ReliabilityRow::withheld(Parameter::StrideTime, 10, 3, String::new());
        for (i, slot) in st.numbers_mut().into_iter().enumerate() {
            *slot = Some(0.1 + i as f64 / 3.0);
        }
        st.within_subject_cv = None;
        let sta = ReliabilityRow::withheld(
            Parameter::Sta,
            1,
            3,
            "fewer than 2 people with a value in each trial, \"quoted\"".into(),
        );
        ReliabilityTable {
            rows: vec![st, sta],
        }
    }

    fn write(dir: &Path, text: &str) -> std::path::PathBuf {
        let p = dir.join("reliability.csv");
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn a_table_reads_back_as_written() {
        let dir = tempfile::tempdir().unwrap();
        let t = table();
        let csv = t.to_csv().unwrap();
        assert_eq!(csv.lines().next().unwrap(), COLUMNS.join(","));
        assert!(
            csv.lines()
                .nth(2)
                .unwrap()
                .starts_with("sta_per_s,STA,1/s,1,3,,,"),
            "{csv}"
        );
        let back = ReliabilityTable::read(&write(dir.path(), &csv)).unwrap();
        assert_eq!(back, t, "exact round trip of every f64");
        assert_eq!(back.mdc95(Parameter::StrideTime), Some(0.1 + 9.0 / 3.0));
        assert_eq!(back.mdc95(Parameter::Sta), None, "withheld");
        assert_eq!(back.mdc95(Parameter::Speed), None, "no row");
        assert_eq!(back.row(Parameter::StrideTime).unwrap().code, "ST");
        assert_eq!(
            ReliabilityTable::default().to_csv().unwrap().trim(),
            COLUMNS.join(",")
        );
    }

    /// `table()`'s CSV with `from` replaced by `to` in its text, read back: the error message.
    fn error(from: &str, to: &str) -> String {
        let dir = tempfile::tempdir().unwrap();
        let csv = table().to_csv().unwrap();
        assert!(csv.contains(from), "{from}");
        let p = write(dir.path(), &csv.replacen(from, to, 1));
        ReliabilityTable::read(&p).unwrap_err().to_string()
    }

    #[test]
    fn each_error_names_the_file_line_and_column() {
        let m = error("stride_time_s,ST", "stride_time_ms,ST");
        assert!(
            m.contains("reliability.csv:2:1: column 'parameter': 'stride_time_ms' is not valid"),
            "{m}"
        );
        assert!(m.contains("stride_time_s"), "lists the known ones: {m}");
        let m = error("sta_per_s,STA,1/s", "stride_time_s,ST,s");
        assert!(
            m.contains("reliability.csv:3:1: ") && m.contains("on line 2"),
            "{m}"
        );
        let m = error("sta_per_s,STA", "sta_per_s,ST");
        assert!(
            m.contains("reliability.csv:3:2: column 'code': 'ST'") && m.contains("'STA'"),
            "{m}"
        );
        let m = error(",0.1,", ",zero,");
        assert!(
            m.contains("reliability.csv:2:6: column 'icc_2_1': 'zero' is not a number"),
            "{m}"
        );
        let m = error(",0.1,", ",NaN,");
        assert!(
            m.contains("reliability.csv:2:6: column 'icc_2_1': non-finite"),
            "{m}"
        );
        let m = error(",3.1,", ",-3.1,");
        assert!(
            m.contains(
                "reliability.csv:2:15: column 'mdc95': '-3.1' is not valid; expected a number ≥ 0"
            ),
            "{m}"
        );
        let m = error("1,3,,,", "1,3,0.5,,");
        assert!(
            m.contains("reliability.csv:3:6: column 'icc_2_1'") && m.contains("withheld"),
            "{m}"
        );
        let m = error(",10,3,", ",ten,3,");
        assert!(
            m.contains("reliability.csv:2:4: column 'n_subjects': 'ten'"),
            "{m}"
        );
        let m = error("mdc95,", "mdc_95,");
        assert!(
            m.contains("reliability.csv:1:15: unknown column 'mdc_95'"),
            "{m}"
        );
        let m = error(",withheld", "");
        assert!(
            m.contains("reliability.csv:1: missing column(s) [\"withheld\"]"),
            "{m}"
        );
        let m = error("sta_per_s,STA,1/s,1,3,", "sta_per_s,STA,1/s,1,");
        assert!(
            m.contains("reliability.csv:3: row has 18 fields, the header has 19"),
            "{m}"
        );
    }

    #[test]
    fn an_empty_file_or_one_without_rows_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let m = ReliabilityTable::read(&write(dir.path(), " \n"))
            .unwrap_err()
            .to_string();
        assert!(m.ends_with("reliability.csv: the file is empty"), "{m}");
        let header = format!("{}\n", COLUMNS.join(","));
        let m = ReliabilityTable::read(&write(dir.path(), &header))
            .unwrap_err()
            .to_string();
        assert!(
            m.contains("reliability.csv:2: column 'parameter'") && m.contains("has none"),
            "{m}"
        );
    }
}
