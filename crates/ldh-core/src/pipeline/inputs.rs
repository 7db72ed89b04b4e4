//! Input discovery: a pair of files, a subject folder, a cohort folder, a manifest, or the
//! embedded demo.

use std::path::{Path, PathBuf};

use super::manifest::{is_manifest_text, parse_manifest, resolve_format_in};
pub use super::subject_input::{Clocks, Source, SubjectInput};
use crate::error::{LdhError, Result};
use crate::io::FormatSpec;
use crate::recording::Side;

/// People and trials among the inputs of a run: an input is one trial of a person, so a
/// person walking twice is 1 person and 2 trials (never "2 subjects").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PeopleTrials {
    /// Distinct `subject_id`s.
    pub people: usize,
    /// Inputs (one per trial of a person).
    pub trials: usize,
}

impl PeopleTrials {
    /// The counts of `inputs`.
    pub fn of(inputs: &[SubjectInput]) -> Self {
        let mut ids: Vec<&str> = inputs.iter().map(|s| s.subject_id.as_str()).collect();
        ids.sort_unstable();
        ids.dedup();
        PeopleTrials {
            people: ids.len(),
            trials: inputs.len(),
        }
    }

    /// "4 people", "1 person", or "16 people, 18 trials" when some walked more than once.
    pub fn describe(&self) -> String {
        let people = if self.people == 1 {
            "1 person".to_string()
        } else {
            format!("{} people", self.people)
        };
        if self.trials == self.people {
            people
        } else {
            format!("{people}, {} trials", self.trials)
        }
    }
}

/// Options for inputs given directly on a command line or in an API call.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct InputOptions {
    /// Subject id for files given directly (default: the common stem of their names).
    pub subject_id: Option<String>,
    /// Setting of every subject whose manifest row does not say.
    pub setting: Option<crate::recording::Setting>,
    /// The left sensor's height, m, for subjects that give no height for their left leg
    /// (`--left-sensor-height-m`; checked with [`SensorHeights::check`]).
    pub left_sensor_height_m: Option<f64>,
    /// The right sensor's height, m, for subjects that give none for their right leg.
    pub right_sensor_height_m: Option<f64>,
}

/// Parse a cohort manifest (SPEC §2; columns in [`super::manifest`]); paths and column maps
/// relative to the manifest's folder.
pub fn read_manifest(path: &Path) -> Result<Vec<SubjectInput>> {
    let text = crate::io::read_text_limited(path, crate::io::MAX_MANIFEST_MB, "a cohort manifest")?;
    let dir = path.parent().unwrap_or(Path::new("."));
    parse_manifest(&text, path, &|rel| Source::Path(dir.join(rel)), &|f| {
        resolve_format_in(dir, f)
    })
}

/// The embedded demo cohort as inputs.
pub fn demo_inputs() -> Result<Vec<SubjectInput>> {
    let text = crate::demo::file("manifest.csv").expect("embedded manifest");
    parse_manifest(
        text,
        Path::new("<demo>/manifest.csv"),
        &|rel| Source::Embedded(rel.to_string()),
        &FormatSpec::builtin,
    )
}

/// Turn command-line inputs into subjects: no input → the embedded demo; a manifest CSV; a
/// folder with `manifest.csv`; a subject folder with `left.csv` / `right.csv`; a cohort folder
/// of such subject folders; or files (two files are a left/right pair, by name or in order).
pub fn discover(inputs: &[PathBuf]) -> Result<Vec<SubjectInput>> {
    discover_with(inputs, &InputOptions::default())
}

/// Whether `p` is a manifest: a file whose header row holds `subject_id` and `left` and/or
/// `right` (only the first 64 kB are looked at).
pub fn is_manifest(p: &Path) -> bool {
    use std::io::Read;
    if !p.is_file() {
        return false;
    }
    let mut head = Vec::new();
    let ok = std::fs::File::open(p)
        .and_then(|f| f.take(1 << 16).read_to_end(&mut head))
        .is_ok();
    ok && is_manifest_text(&String::from_utf8_lossy(&head))
}

/// The subject id of files given directly: their names' common stem without side words and
/// separators (`P07_left.csv` + `P07_right.csv` → `P07`), else the first file's stem; names
/// that are only side words (`L02/left.csv` + `L02/right.csv`) take the folder's name (`L02`).
pub fn subject_id_from_files(files: &[&PathBuf]) -> String {
    let stems: Vec<String> = files
        .iter()
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().to_string()))
        .collect();
    let seps: &[char] = &['_', '-', '.', ' '];
    let trim = |s: &str| -> String {
        let mut t = s.trim_matches(seps);
        let lower = t.to_ascii_lowercase();
        for w in ["left", "right"] {
            let n = t.len();
            if lower.ends_with(w) && (n == w.len() || lower[..n - w.len()].ends_with(seps)) {
                t = &t[..n - w.len()];
                break;
            }
            if lower.starts_with(w) && (n == w.len() || lower[w.len()..].starts_with(seps)) {
                t = &t[w.len()..];
                break;
            }
        }
        t.trim_matches(seps).to_string()
    };
    let stems: Vec<String> = stems.iter().map(|s| trim(s)).collect();
    let id = match stems.as_slice() {
        [] => String::new(),
        [one] => one.clone(),
        [a, b, ..] if a == b => a.clone(),
        [a, b, ..] => {
            let pre: String = a
                .chars()
                .zip(b.chars())
                .take_while(|(x, y)| x == y)
                .map(|(x, _)| x)
                .collect();
            let mut suf: Vec<char> = a
                .chars()
                .rev()
                .zip(b.chars().rev())
                .take_while(|(x, y)| x == y)
                .map(|(x, _)| x)
                .collect();
            suf.reverse();
            let (pre, suf) = (trim(&pre), trim(&suf.into_iter().collect::<String>()));
            if !pre.is_empty() && pre.len() >= suf.len() {
                pre
            } else if !suf.is_empty() {
                suf
            } else {
                a.clone()
            }
        }
    };
    if !id.is_empty() {
        return id;
    }
    // Names that are only side words (`left.csv`, `right.csv`): the folder names the subject.
    files
        .first()
        .and_then(|p| p.canonicalize().ok().or_else(|| Some(p.to_path_buf())))
        .and_then(|p| {
            p.parent()
                .and_then(|d| d.file_name())
                .map(|n| n.to_string_lossy().to_string())
        })
        .filter(|n| !n.is_empty())
        .unwrap_or_else(|| "subject".into())
}

/// As [`discover`], with a subject id for files given directly, a setting for subjects whose
/// manifest row does not say, and per-side sensor heights for legs whose row gives none.
pub fn discover_with(inputs: &[PathBuf], opts: &InputOptions) -> Result<Vec<SubjectInput>> {
    let mut out = discover_inputs(inputs, opts)?;
    if let Some(st) = opts.setting {
        for s in &mut out {
            s.setting = s.setting.or(Some(st));
        }
    }
    // A leg the row gives no height for takes the run's height for that leg (the row wins).
    for s in &mut out {
        if s.sensor_height_m_of(Side::Left).is_none() {
            s.left_sensor_height_m = opts.left_sensor_height_m;
        }
        if s.sensor_height_m_of(Side::Right).is_none() {
            s.right_sensor_height_m = opts.right_sensor_height_m;
        }
    }
    Ok(out)
}

fn discover_inputs(inputs: &[PathBuf], opts: &InputOptions) -> Result<Vec<SubjectInput>> {
    if inputs.is_empty() {
        if opts.subject_id.is_some() {
            return Err(LdhError::signal(
                "inputs",
                "--subject names the subject of files given directly; no file was given",
            ));
        }
        return demo_inputs();
    }
    // A misspelt path is refused before any work (and before an output folder is made).
    if let Some(p) = inputs.iter().find(|p| !p.exists()) {
        return Err(LdhError::Io {
            path: p.clone(),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file or folder"),
        });
    }
    // An ldh output folder (or a table in one) is refused with the way to pass it.
    if let Some(e) = inputs.iter().find_map(|p| super::output_hint::refusal(p)) {
        return Err(e);
    }
    let files: Vec<&PathBuf> = inputs
        .iter()
        .filter(|p| !p.is_dir() && !is_manifest(p))
        .collect();
    if opts.subject_id.is_some() && files.is_empty() {
        return Err(LdhError::signal(
            "inputs",
            "--subject names the subject of files given directly; a manifest or a folder names its own subjects",
        ));
    }
    let mut out = Vec::new();
    for p in inputs {
        if p.is_dir() {
            out.extend(folder_inputs(p)?);
        } else if is_manifest(p) {
            out.extend(read_manifest(p)?);
        }
    }
    if !files.is_empty() {
        out.push(loose_files_input(&files, opts)?);
    }
    let mut seen = std::collections::BTreeSet::new();
    for s in &out {
        if !seen.insert((s.subject_id.as_str(), s.trial_id.as_deref())) {
            return Err(LdhError::signal(
                "inputs",
                format!("subject id '{}' appears twice (two folders or manifests with the same subject): rename one", s.subject_id),
            ));
        }
    }
    Ok(out)
}

/// A subject folder: one whose file names say a side (`left.csv` / `right.csv`, or a side
/// word at the start or end of the name; [`super::pairing`]), named after the folder.
fn subject_dir(d: &Path) -> Option<SubjectInput> {
    let f = super::pairing::pair_folder(d);
    f.is_subject().then(|| SubjectInput {
        subject_id: d
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_else(|| "subject".into()),
        left: f.left.map(Source::Path),
        right: f.right.map(Source::Path),
        unpaired: f.unpaired,
        ..SubjectInput::default()
    })
}

/// The subjects of a folder: its `manifest.csv`, else the folder as one subject, else its
/// subject folders in name order.
fn folder_inputs(p: &Path) -> Result<Vec<SubjectInput>> {
    if p.join("manifest.csv").is_file() {
        return read_manifest(&p.join("manifest.csv"));
    }
    if let Some(s) = subject_dir(p) {
        return Ok(vec![s]);
    }
    let mut subs: Vec<PathBuf> = std::fs::read_dir(p)
        .map_err(|source| LdhError::Io {
            path: p.to_path_buf(),
            source,
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|e| e.is_dir())
        .collect();
    subs.sort();
    let found: Vec<SubjectInput> = subs.iter().filter_map(|d| subject_dir(d)).collect();
    if found.is_empty() {
        let ignored = super::pairing::pair_folder(p).unpaired;
        return Err(LdhError::signal(
            p.display().to_string(),
            format!(
                "no manifest.csv, no left.csv/right.csv (or files named by their side) and no subject folders with them{}",
                if ignored.is_empty() {
                    String::new()
                } else {
                    format!("; {}", ignored.join("; "))
                }
            ),
        ));
    }
    Ok(found)
}

/// One subject from one or two files given directly: a file whose name says its side
/// ([`super::pairing::side_of_name`]: `P07_left.csv`, `right-P07.csv`; not `Albright.csv`) is
/// that leg, the other file the other leg; names that say nothing pair in order (left, right).
/// Two names of one side are refused, naming both.
fn loose_files_input(files: &[&PathBuf], opts: &InputOptions) -> Result<SubjectInput> {
    use super::pairing::{side_of_name, NameSide};
    if files.len() > 2 {
        return Err(LdhError::signal(
            "inputs",
            format!(
                "{} loose files: give one subject's left and right files, or a folder or manifest",
                files.len()
            ),
        ));
    }
    let says: Vec<Option<Side>> = files
        .iter()
        .map(|f| {
            match side_of_name(
                &f.file_name()
                    .map(|n| n.to_string_lossy())
                    .unwrap_or_default(),
            ) {
                NameSide::Leg(s) => Some(s),
                _ => None,
            }
        })
        .collect();
    let src = |i: usize| Some(Source::Path(files[i].clone()));
    let (left, right) = match says.as_slice() {
        [Some(a), Some(b)] if a == b => {
            return Err(LdhError::signal(
                "inputs",
                format!(
                    "two files look like the {a} leg: {}, {} (name one of them by the other side, or give a manifest)",
                    files[0].display(),
                    files[1].display()
                ),
            ))
        }
        [Some(Side::Right)] => (None, src(0)),
        [_] => (src(0), None),
        [Some(Side::Right), _] | [None, Some(Side::Left)] => (src(1), src(0)),
        _ => (src(0), src(1)),
    };
    Ok(SubjectInput {
        subject_id: opts
            .subject_id
            .clone()
            .unwrap_or_else(|| subject_id_from_files(files)),
        left,
        right,
        ..SubjectInput::default()
    })
}
