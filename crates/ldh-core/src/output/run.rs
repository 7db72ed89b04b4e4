//! One output folder holds one run (issue 37: nothing mixed, nothing outside `--out`).
//!
//! An [`OutputRun`] owns an output folder of `ldh analyze` or `ldh report` while it writes:
//!
//! 1. **Lock**: `.ldh.lock` ([`OutputLock`]); a second run into the folder is refused.
//! 2. **Look**: every entry of the folder is classified, without following any link: a file an
//!    earlier run listed in its marker, or a name an ldh run writes ([`RunKind`]), is the
//!    earlier run's; a symbolic link anywhere in the folder, or any other file, refuses the run
//!    with the names (ldh never follows, writes through or removes a link under `--out`, and
//!    never deletes a file it did not write).
//! 3. **Clear**: the earlier marker is replaced first by an in-progress marker, in one rename
//!    (an interrupted clear leaves no complete marker, and never no marker), then the earlier
//!    run's files and folders removed.
//! 4. **Write**: every file goes through [`OutputRun::write`] / [`OutputRun::create`]: its folders
//!    are checked component by component with `symlink_metadata` (a link is refused), its
//!    temporary file is created with `O_CREAT | O_EXCL` (never through a link) and renamed into
//!    place; its size and FNV-1a 64 hash are recorded.
//! 5. **Mark**: [`OutputRun::finish`] writes the marker `ldh-run.json` last: the command, the ldh
//!    version, `complete: true`, every file with its size and hash, and the run id (a hash of
//!    that list). A folder whose marker is missing or not complete holds no finished run.
//!
//! Readers ([`crate::report::build`]) take a file of the folder only when the complete marker
//! lists it with the same hash, so a trace can never be paired with another run's tables.
//! The marker holds no time or process id, so the same run writes the same bytes.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use super::names::{fnv1a, fnv1a_from};
use crate::error::{LdhError, Result};
use crate::io::{write_atomic, AtomicFile, OutputLock};

/// The marker file of a run, in the output folder.
pub const MARKER: &str = "ldh-run.json";

/// Schema tag of the marker.
pub const MARKER_SCHEMA: &str = "ldh-run/1";

/// Which command's folder: what names its runs write.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RunKind {
    /// `ldh analyze`: `strides.csv/.json`, `events.csv`, `recordings.csv/.json`, `params.json`,
    /// `traces/*.json` and a report folder `reports/`.
    Analyze,
    /// `ldh report`: `index.html` and `subjects/*.html`.
    Report,
}

impl RunKind {
    /// Whether `rel` (a path inside the folder, `/`-separated) is a name runs of this kind write;
    /// for a folder, whether its entries are looked at (with the rules returned).
    fn known_file(self, rel: &str) -> bool {
        match self {
            RunKind::Analyze => {
                matches!(
                    rel,
                    "strides.csv"
                        | "strides.json"
                        | "events.csv"
                        | "events.json"
                        | "recordings.csv"
                        | "recordings.json"
                        | "params.json"
                        | MARKER
                ) || in_folder(rel, "traces", ".json")
                    || rel
                        .strip_prefix("reports/")
                        .is_some_and(|r| RunKind::Report.known_file(r))
            }
            RunKind::Report => {
                matches!(rel, "index.html" | MARKER) || in_folder(rel, "subjects", ".html")
            }
        }
    }

    fn known_dir(self, rel: &str) -> bool {
        match self {
            RunKind::Analyze => matches!(rel, "traces" | "reports" | "reports/subjects"),
            RunKind::Report => rel == "subjects",
        }
    }

    fn as_str(self) -> &'static str {
        match self {
            RunKind::Analyze => "analyze",
            RunKind::Report => "report",
        }
    }
}

/// `rel` is `<folder>/<name><ext>` with no further folder.
fn in_folder(rel: &str, folder: &str, ext: &str) -> bool {
    rel.strip_prefix(folder)
        .and_then(|r| r.strip_prefix('/'))
        .is_some_and(|n| !n.contains('/') && n.ends_with(ext))
}

/// A file a run wrote, as its marker lists it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RunFile {
    /// Path inside the output folder, `/`-separated.
    pub path: String,
    /// Size, bytes.
    pub bytes: u64,
    /// FNV-1a 64 of the content, 16 hex digits (to detect a change or a mix, not for security).
    pub fnv1a64: String,
}

/// The marker `ldh-run.json` of an output folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunMarker {
    /// [`MARKER_SCHEMA`].
    pub schema: String,
    /// The command that wrote the folder.
    pub command: RunKind,
    /// Version of ldh that wrote it.
    pub ldh_version: String,
    /// Names the run: 16 hex digits of the FNV-1a 64 hash of the command, version and file
    /// list (empty while the run is writing).
    pub run_id: String,
    /// `true` only once every file is written; a folder without a complete marker holds no
    /// finished run (interrupted, or still being written).
    pub complete: bool,
    /// For a report: the run id of the `ldh analyze` folder it was built from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub results_run: Option<String>,
    /// Every file the run wrote, sorted by path.
    pub files: Vec<RunFile>,
}

impl RunMarker {
    /// The listed file at `rel`.
    pub fn file(&self, rel: &str) -> Option<&RunFile> {
        self.files
            .binary_search_by(|f| f.path.as_str().cmp(rel))
            .ok()
            .map(|i| &self.files[i])
    }

    /// Whether `bytes` are what the marker lists at `rel`.
    pub fn lists(&self, rel: &str, bytes: &[u8]) -> bool {
        self.file(rel).is_some_and(|f| {
            f.bytes == bytes.len() as u64 && f.fnv1a64 == format!("{:016x}", fnv1a(bytes))
        })
    }
}

/// The marker of `dir`: `None` when there is none; an error when it cannot be read or parsed,
/// or is a symbolic link.
pub fn read_marker(dir: &Path) -> Result<Option<RunMarker>> {
    let path = dir.join(MARKER);
    match std::fs::symlink_metadata(&path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => return Err(LdhError::Io { path, source }),
        Ok(m) if !m.is_file() => {
            return Err(LdhError::signal(
                path.display().to_string(),
                "not a regular file (a link or a folder): not an ldh run marker",
            ))
        }
        Ok(_) => {}
    }
    let text = std::fs::read_to_string(&path).map_err(|source| LdhError::Io {
        path: path.clone(),
        source,
    })?;
    let m: RunMarker = serde_json::from_str(&text).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not an ldh run marker: {e}"),
    })?;
    if m.schema != MARKER_SCHEMA {
        return Err(LdhError::Format {
            name: path.display().to_string(),
            reason: format!("marker schema '{}', expected '{MARKER_SCHEMA}'", m.schema),
        });
    }
    Ok(Some(m))
}

/// Refuse a symbolic link on the way from `root` down to `path` (components below `root`
/// only; `root` itself may be a link the user chose): a folder ldh writes into inside another
/// run's folder, such as the default `<results>/reports` of `ldh report`.
pub fn refuse_links_below(root: &Path, path: &Path) -> Result<()> {
    let Ok(rel) = path.strip_prefix(root) else {
        return Ok(());
    };
    let mut p = root.to_path_buf();
    for c in rel.components() {
        p.push(c);
        if std::fs::symlink_metadata(&p).is_ok_and(|m| m.file_type().is_symlink()) {
            return Err(LdhError::Write {
                path: p,
                reason: "is a symbolic link: ldh never writes through a link inside an output folder; remove it".into(),
            });
        }
    }
    Ok(())
}

/// An output folder while one run writes it; see the module documentation.
#[derive(Debug)]
pub struct OutputRun {
    dir: PathBuf,
    kind: RunKind,
    results_run: Option<String>,
    files: Mutex<Vec<RunFile>>,
    _lock: OutputLock,
}

/// What a look at the folder found.
#[derive(Default)]
struct Found {
    remove: Vec<PathBuf>,
    dirs: Vec<PathBuf>,
    links: Vec<String>,
    foreign: Vec<String>,
}

/// Name a few paths: the first five and how many more.
fn some(paths: &[String]) -> String {
    let mut s = paths
        .iter()
        .take(5)
        .map(|p| format!("'{p}'"))
        .collect::<Vec<_>>()
        .join(", ");
    if paths.len() > 5 {
        s += &format!(" and {} more", paths.len() - 5);
    }
    s
}

impl OutputRun {
    /// Take `dir` (created if missing) for a run of `kind`: lock it, refuse links and files no
    /// ldh run wrote, and remove an earlier run's outputs (its marker first).
    pub fn begin(dir: &Path, kind: RunKind) -> Result<OutputRun> {
        let lock = OutputLock::acquire(dir)?;
        let werr = |path: &Path, e: std::io::Error| LdhError::Write {
            path: path.to_path_buf(),
            reason: e.to_string(),
        };
        let previous = read_marker(dir).ok().flatten();
        let mut found = Found::default();
        look(dir, dir, kind, previous.as_ref(), &mut found)?;
        if !found.links.is_empty() {
            return Err(LdhError::Write {
                path: dir.to_path_buf(),
                reason: format!(
                    "{} in the output folder is a symbolic link: ldh never writes through, follows or removes a link inside --out; remove the link or choose another --out",
                    some(&found.links)
                ),
            });
        }
        if !found.foreign.is_empty() {
            return Err(LdhError::Write {
                path: dir.to_path_buf(),
                reason: format!(
                    "the output folder holds {} that no ldh {} run wrote; ldh replaces an earlier run's outputs but never removes other files: move them, or choose an empty or new --out",
                    some(&found.foreign),
                    kind.as_str()
                ),
            });
        }
        // The earlier marker is replaced first, in one rename, by the in-progress one: from
        // here on the folder holds no complete run, and never no marker at all (a run killed
        // between a removal and the new marker's write left a folder that read as an older
        // ldh's, issue 51's CI).
        let marker = dir.join(MARKER);
        let run = OutputRun {
            dir: dir.to_path_buf(),
            kind,
            results_run: None,
            files: Mutex::new(Vec::new()),
            _lock: lock,
        };
        write_atomic(&marker, &run.marker(false).to_json()?)?;
        for f in &found.remove {
            match std::fs::remove_file(f) {
                Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(werr(f, e)),
                _ => {}
            }
        }
        // Deepest first; a folder left non-empty (a file appeared meanwhile) stays.
        for d in found.dirs.iter().rev() {
            let _ = std::fs::remove_dir(d);
        }
        Ok(run)
    }

    /// The output folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Record, for a report, the run id of the analysis it was built from.
    pub fn set_results_run(&mut self, id: Option<String>) {
        self.results_run = id;
    }

    /// `rel` (`/`-separated, inside the folder) as a path whose folders exist and none of
    /// whose components is a link (refused, naming it).
    fn path_for(&self, rel: &str) -> Result<PathBuf> {
        let parts: Vec<&str> = rel.split('/').collect();
        let bad = parts
            .iter()
            .any(|p| p.is_empty() || *p == "." || *p == ".." || p.contains('\\'));
        if bad {
            return Err(LdhError::Write {
                path: self.dir.join(rel),
                reason: "not a plain path inside the output folder".into(),
            });
        }
        let mut path = self.dir.clone();
        for (i, p) in parts.iter().enumerate() {
            path.push(p);
            let last = i + 1 == parts.len();
            match std::fs::symlink_metadata(&path) {
                Ok(m) if m.file_type().is_symlink() => {
                    return Err(LdhError::Write {
                        path: path.clone(),
                        reason: "is a symbolic link: ldh never writes through a link inside --out; remove it".into(),
                    })
                }
                Ok(m) if !last && !m.is_dir() => {
                    return Err(LdhError::Write {
                        path: path.clone(),
                        reason: "is not a folder".into(),
                    })
                }
                Ok(_) => {}
                Err(e) if e.kind() == std::io::ErrorKind::NotFound && !last => {
                    match std::fs::create_dir(&path) {
                        Err(e) if e.kind() != std::io::ErrorKind::AlreadyExists => {
                            return Err(LdhError::Write {
                                path: path.clone(),
                                reason: e.to_string(),
                            })
                        }
                        _ => {}
                    }
                    // Made by someone else meanwhile: checked again.
                    if std::fs::symlink_metadata(&path).map_or(true, |m| !m.is_dir()) {
                        return Err(LdhError::Write {
                            path: path.clone(),
                            reason: "is not a folder (replaced while writing?)".into(),
                        });
                    }
                }
                Err(_) => {}
            }
        }
        Ok(path)
    }

    fn record(&self, rel: &str, bytes: u64, hash: u64) {
        self.files.lock().expect("no panic holds it").push(RunFile {
            path: rel.to_string(),
            bytes,
            fnv1a64: format!("{hash:016x}"),
        });
    }

    /// Write `bytes` to `rel` in the folder atomically, never through a link, and record it.
    pub fn write(&self, rel: &str, bytes: &[u8]) -> Result<()> {
        write_atomic(self.path_for(rel)?, bytes)?;
        self.record(rel, bytes.len() as u64, fnv1a(bytes));
        Ok(())
    }

    /// Start writing `rel` row by row ([`RunWriter::finish`] puts it in place and records it).
    pub fn create(&self, rel: &str) -> Result<RunWriter<'_>> {
        Ok(RunWriter {
            run: self,
            rel: rel.to_string(),
            file: AtomicFile::create(self.path_for(rel)?)?,
            bytes: 0,
            hash: fnv1a(b""),
        })
    }

    fn marker(&self, complete: bool) -> RunMarker {
        let mut files = self.files.lock().expect("no panic holds it").clone();
        files.sort_by(|a, b| a.path.cmp(&b.path));
        let version = env!("CARGO_PKG_VERSION");
        let mut h = fnv1a(format!("{}\n{version}\n", self.kind.as_str()).as_bytes());
        for f in &files {
            h = fnv1a_from(
                h,
                format!("{}\0{}\0{}\n", f.path, f.bytes, f.fnv1a64).as_bytes(),
            );
        }
        RunMarker {
            schema: MARKER_SCHEMA.into(),
            command: self.kind,
            ldh_version: version.into(),
            run_id: if complete {
                format!("{h:016x}")
            } else {
                String::new()
            },
            complete,
            results_run: self.results_run.clone(),
            files: if complete { files } else { Vec::new() },
        }
    }

    /// Write the complete marker (last) and release the folder.
    pub fn finish(self) -> Result<RunMarker> {
        let m = self.marker(true);
        let path = self.path_for(MARKER)?;
        write_atomic(path, &m.to_json()?)?;
        Ok(m)
    }
}

impl RunMarker {
    fn to_json(&self) -> Result<Vec<u8>> {
        let mut s = serde_json::to_string_pretty(self)?;
        s.push('\n');
        Ok(s.into_bytes())
    }
}

/// Look at `d` (inside `root`), sorting its entries into `found`.
fn look(
    root: &Path,
    d: &Path,
    kind: RunKind,
    previous: Option<&RunMarker>,
    found: &mut Found,
) -> Result<()> {
    let entries = std::fs::read_dir(d).map_err(|source| LdhError::Io {
        path: d.to_path_buf(),
        source,
    })?;
    let mut entries: Vec<_> = entries.flatten().collect();
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let path = e.path();
        let rel = path
            .strip_prefix(root)
            .map(|r| r.to_string_lossy().replace('\\', "/"))
            .unwrap_or_default();
        let name = e.file_name().to_string_lossy().to_string();
        let Ok(ft) = e.file_type() else { continue };
        if ft.is_symlink() {
            found.links.push(rel);
        } else if d == root && (name == ".ldh.lock" || name == MARKER) {
            // The lock of this run; the marker, replaced first by `begin`.
        } else if name == ".ldh.lock" {
            if let Some(holder) = crate::io::writer::live_holder(&path) {
                return Err(LdhError::Write {
                    path: path.parent().unwrap_or(root).to_path_buf(),
                    reason: format!(
                        "another ldh run (process {holder}) is writing to this folder; wait for it"
                    ),
                });
            }
            found.remove.push(path);
        } else if name.starts_with('.') && name.contains(".tmp-") && ft.is_file() {
            found.remove.push(path); // a temporary file of an interrupted run
        } else if ft.is_dir() && kind.known_dir(&rel) {
            found.dirs.push(path.clone());
            look(root, &path, kind, previous, found)?;
        } else if ft.is_file()
            && (kind.known_file(&rel) || previous.is_some_and(|m| m.file(&rel).is_some()))
        {
            found.remove.push(path);
        } else {
            found
                .foreign
                .push(if ft.is_dir() { rel + "/" } else { rel });
        }
    }
    Ok(())
}

/// A file of an [`OutputRun`] written row by row: an [`AtomicFile`] whose size and hash are
/// recorded by [`RunWriter::finish`].
pub struct RunWriter<'a> {
    run: &'a OutputRun,
    rel: String,
    file: AtomicFile,
    bytes: u64,
    hash: u64,
}

impl RunWriter<'_> {
    /// Flush, fsync, rename into place, and record the file in the run.
    pub fn finish(self) -> Result<()> {
        let (run, rel, bytes, hash) = (self.run, self.rel, self.bytes, self.hash);
        self.file.finish()?;
        run.record(&rel, bytes, hash);
        Ok(())
    }
}

impl Write for RunWriter<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.file.write(buf)?;
        self.hash = fnv1a_from(self.hash, &buf[..n]);
        self.bytes += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

#[cfg(test)]
mod tests;
