//! Input discovery: a pair of files, a subject folder, a cohort folder, a manifest, or the
//! embedded demo.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

use crate::error::{LdhError, Result};
use crate::io::{read_recording, read_recording_bytes, FormatSpec, ReadReport, ValidReadParams};
use crate::recording::{Recording, Side};
use crate::simulate::Group;

/// Where a recording comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Source {
    /// A file.
    Path(PathBuf),
    /// A file of the embedded demo cohort (relative path).
    Embedded(String),
}

impl Source {
    /// A label for messages and tables.
    pub fn label(&self) -> String {
        match self {
            Source::Path(p) => p.display().to_string(),
            Source::Embedded(r) => format!("<demo>/{r}"),
        }
    }
    /// Read the recording.
    pub fn read(
        &self,
        format: Option<&FormatSpec>,
        params: &ValidReadParams,
    ) -> Result<(Recording, ReadReport)> {
        match self {
            Source::Path(p) => read_recording(p, format, params),
            Source::Embedded(rel) => {
                let text = crate::demo::file(rel)
                    .ok_or_else(|| LdhError::signal("demo", format!("no embedded file {rel}")))?;
                read_recording_bytes(text.as_bytes(), Path::new(&self.label()), format, params)
            }
        }
    }
}

/// One subject to analyse.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectInput {
    /// Identifier.
    pub subject_id: String,
    /// Group, when a manifest gives it.
    pub group: Option<Group>,
    /// Affected side, when a manifest gives it (`None` for healthy or unknown).
    pub affected_side: Option<Side>,
    /// Left recording.
    pub left: Option<Source>,
    /// Right recording.
    pub right: Option<Source>,
    /// Sensor height above the ankle, m (manifest column `sensor_height_m`).
    pub sensor_height_m: Option<f64>,
    /// Where the walk happened (`None`: not said, treated as overground).
    #[serde(default)]
    pub setting: Option<crate::recording::Setting>,
}

/// Parse a cohort manifest (SPEC §2): `subject_id, group, affected_side, left, right` and the
/// optional `sensor_height_m`; paths relative to the manifest's folder.
pub fn read_manifest(path: &Path) -> Result<Vec<SubjectInput>> {
    let text = std::fs::read_to_string(path).map_err(|source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_manifest(&text, path, &|rel| {
        Source::Path(path.parent().unwrap_or(Path::new(".")).join(rel))
    })
}

fn parse_manifest(
    text: &str,
    path: &Path,
    resolve: &dyn Fn(&str) -> Source,
) -> Result<Vec<SubjectInput>> {
    use crate::error::Location;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((hl, header)) = lines.next() else {
        return Err(LdhError::EmptyFile {
            path: path.to_path_buf(),
        });
    };
    let header = header.trim_start_matches('\u{feff}');
    let cols: Vec<String> = header
        .split(',')
        .map(|c| c.trim().to_ascii_lowercase())
        .collect();
    let col = |name: &str| cols.iter().position(|c| c == name);
    let need = ["subject_id", "group", "affected_side", "left", "right"];
    for n in need {
        if col(n).is_none() {
            return Err(LdhError::MissingColumn {
                loc: Location::line(path, hl as u64 + 1),
                column: n.into(),
                format: "cohort manifest".into(),
                header: cols.clone(),
            });
        }
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        let f: Vec<&str> = line.split(',').map(|x| x.trim()).collect();
        let get = |n: &str| col(n).and_then(|c| f.get(c).copied()).unwrap_or("");
        let lineno = i as u64 + 1;
        let group = match get("group").to_ascii_lowercase().as_str() {
            "healthy" | "h" | "control" => Group::Healthy,
            "ldh" => Group::Ldh,
            other => {
                return Err(LdhError::InvalidValue {
                    loc: Location::cell(path, lineno, col("group").unwrap() + 1),
                    column: "group".into(),
                    value: other.into(),
                    expected: "'healthy' or 'ldh'".into(),
                })
            }
        };
        let affected_side = match get("affected_side").to_ascii_lowercase().as_str() {
            "left" => Some(Side::Left),
            "right" => Some(Side::Right),
            "none" | "" => None,
            other => {
                return Err(LdhError::InvalidValue {
                    loc: Location::cell(path, lineno, col("affected_side").unwrap() + 1),
                    column: "affected_side".into(),
                    value: other.into(),
                    expected: "'left', 'right' or 'none'".into(),
                })
            }
        };
        let h = get("sensor_height_m");
        let sensor_height_m = if h.is_empty() {
            None
        } else {
            Some(h.parse::<f64>().map_err(|_| LdhError::NotANumber {
                loc: Location::cell(path, lineno, col("sensor_height_m").unwrap() + 1),
                column: "sensor_height_m".into(),
                value: h.into(),
                hint: String::new(),
            })?)
        };
        let side = |n: &str| {
            let v = get(n);
            (!v.is_empty()).then(|| resolve(v))
        };
        let id = get("subject_id");
        if id.is_empty() {
            return Err(LdhError::InvalidValue {
                loc: Location::cell(path, lineno, col("subject_id").unwrap() + 1),
                column: "subject_id".into(),
                value: String::new(),
                expected: "a non-empty subject id".into(),
            });
        }
        if out.iter().any(|s: &SubjectInput| s.subject_id == id) {
            return Err(LdhError::InvalidValue {
                loc: Location::cell(path, lineno, col("subject_id").unwrap() + 1),
                column: "subject_id".into(),
                value: id.into(),
                expected: "a subject id not used on an earlier line".into(),
            });
        }
        out.push(SubjectInput {
            setting: None,
            subject_id: id.to_string(),
            group: Some(group),
            affected_side,
            left: side("left"),
            right: side("right"),
            sensor_height_m,
        });
    }
    Ok(out)
}

/// The embedded demo cohort as inputs.
pub fn demo_inputs() -> Result<Vec<SubjectInput>> {
    let text = crate::demo::file("manifest.csv").expect("embedded manifest");
    parse_manifest(text, Path::new("<demo>/manifest.csv"), &|rel| {
        Source::Embedded(rel.to_string())
    })
}

/// Turn command-line inputs into subjects: no input → the embedded demo; a manifest CSV; a
/// folder with `manifest.csv`; a subject folder with `left.csv` / `right.csv`; a cohort folder
/// of such subject folders; or files (two files are a left/right pair, by name or in order).
pub fn discover(inputs: &[PathBuf]) -> Result<Vec<SubjectInput>> {
    if inputs.is_empty() {
        return demo_inputs();
    }
    // A misspelt path is refused before any work (and before an output folder is made).
    if let Some(p) = inputs.iter().find(|p| !p.exists()) {
        return Err(LdhError::Io {
            path: p.clone(),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file or folder"),
        });
    }
    let is_manifest = |p: &Path| {
        p.is_file()
            && std::fs::read_to_string(p)
                .map(|t| {
                    t.lines()
                        .next()
                        .unwrap_or("")
                        .trim_start_matches('\u{feff}')
                        .to_ascii_lowercase()
                        .starts_with("subject_id,")
                })
                .unwrap_or(false)
    };
    let subject_dir = |d: &Path| -> Option<SubjectInput> {
        let (l, r) = (d.join("left.csv"), d.join("right.csv"));
        (l.exists() || r.exists()).then(|| SubjectInput {
            setting: None,
            subject_id: d
                .file_name()
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_else(|| "subject".into()),
            group: None,
            affected_side: None,
            left: l.exists().then_some(Source::Path(l)),
            right: r.exists().then_some(Source::Path(r)),
            sensor_height_m: None,
        })
    };
    let files: Vec<&PathBuf> = inputs
        .iter()
        .filter(|p| !p.is_dir() && !is_manifest(p))
        .collect();
    let mut out = Vec::new();
    for p in inputs {
        if p.is_dir() {
            if p.join("manifest.csv").is_file() {
                out.extend(read_manifest(&p.join("manifest.csv"))?);
            } else if let Some(s) = subject_dir(p) {
                out.push(s);
            } else {
                let mut subs: Vec<PathBuf> = std::fs::read_dir(p)
                    .map_err(|source| LdhError::Io {
                        path: p.clone(),
                        source,
                    })?
                    .filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|e| e.is_dir())
                    .collect();
                subs.sort();
                let found: Vec<SubjectInput> = subs.iter().filter_map(|d| subject_dir(d)).collect();
                if found.is_empty() {
                    return Err(LdhError::signal(
                        p.display().to_string(),
                        "no manifest.csv, no left.csv/right.csv and no subject folders with them",
                    ));
                }
                out.extend(found);
            }
        } else if is_manifest(p) {
            out.extend(read_manifest(p)?);
        }
    }
    if !files.is_empty() {
        if files.len() > 2 {
            return Err(LdhError::signal(
                "inputs",
                format!("{} loose files: give one subject's left and right files, or a folder or manifest", files.len()),
            ));
        }
        let name = |p: &Path| {
            p.file_name()
                .map(|n| n.to_string_lossy().to_ascii_lowercase())
                .unwrap_or_default()
        };
        let (mut left, mut right) = (None, None);
        for (i, f) in files.iter().enumerate() {
            let n = name(f);
            if n.contains("right") || (i == 1 && !n.contains("left")) {
                right = Some(Source::Path((*f).clone()));
            } else {
                left = Some(Source::Path((*f).clone()));
            }
        }
        let id = files[0]
            .parent()
            .and_then(|d| d.file_name())
            .map(|n| n.to_string_lossy().to_string())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "subject".into());
        out.push(SubjectInput {
            setting: None,
            subject_id: id,
            group: None,
            affected_side: None,
            left,
            right,
            sensor_height_m: None,
        });
    }
    let mut seen = std::collections::BTreeSet::new();
    for s in &out {
        if !seen.insert(s.subject_id.as_str()) {
            return Err(LdhError::signal(
                "inputs",
                format!("subject id '{}' appears twice (two folders or manifests with the same subject): rename one", s.subject_id),
            ));
        }
    }
    Ok(out)
}
