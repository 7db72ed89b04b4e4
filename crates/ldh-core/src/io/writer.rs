//! Writing a [`Recording`] in any [`FormatSpec`] — the inverse of the reader — and writing
//! files atomically (a temporary file in the same folder, then a rename), so an interrupted run
//! leaves the old file or the new one, never half of one.

use std::io::Write;
use std::path::Path;

use super::format::{AccUnit, Decimal, Delimiter, FormatSpec, GyroUnit, TimeUnit};
use crate::error::{LdhError, Result};
use crate::recording::{Recording, STANDARD_GRAVITY_MPS2};

/// The temporary name of a file being written: `.<name>.tmp-<pid>-<n>`, `n` counting every
/// temporary file of the process, so two threads writing the same target never share one.
fn temp_name(name: &str) -> String {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    format!(".{name}.tmp-{}-{n}", std::process::id())
}

/// Create a new file; an existing file or symbolic link of that name is an error, never
/// followed (`O_CREAT | O_EXCL`).
fn create_new(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
}

/// Write `bytes` to `path` atomically: a temporary file beside it, flushed and synced, then
/// renamed over `path`. Creates missing parent folders.
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    let werr = |e: std::io::Error| LdhError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    };
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(werr)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let tmp = dir.join(temp_name(&name));
    {
        let mut f = create_new(&tmp).map_err(werr)?;
        f.write_all(bytes).map_err(werr)?;
        f.sync_all().map_err(werr)?;
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        werr(e)
    })
}

/// A file written through a temporary file beside it and renamed into place by
/// [`AtomicFile::finish`] (after a flush and an fsync), for outputs streamed row by row. Dropped
/// without `finish` (an error, a panic, a kill), it leaves the old file untouched and removes
/// its temporary file where it still can.
#[derive(Debug)]
pub struct AtomicFile {
    path: std::path::PathBuf,
    tmp: std::path::PathBuf,
    file: Option<std::io::BufWriter<std::fs::File>>,
}

impl AtomicFile {
    /// Start writing `path` (its folder is created).
    pub fn create(path: impl AsRef<Path>) -> Result<AtomicFile> {
        let path = path.as_ref().to_path_buf();
        let werr = |e: std::io::Error| LdhError::Write {
            path: path.clone(),
            reason: e.to_string(),
        };
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
            .to_path_buf();
        std::fs::create_dir_all(&dir).map_err(werr)?;
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        let tmp = dir.join(temp_name(&name));
        let f = create_new(&tmp).map_err(werr)?;
        Ok(AtomicFile {
            path,
            tmp,
            file: Some(std::io::BufWriter::with_capacity(1 << 16, f)),
        })
    }

    /// Flush, fsync and rename over the target.
    pub fn finish(mut self) -> Result<()> {
        let werr = |e: std::io::Error| LdhError::Write {
            path: self.path.clone(),
            reason: e.to_string(),
        };
        let f = self.file.take().expect("not finished");
        let f = f.into_inner().map_err(|e| werr(e.into_error()))?;
        f.sync_all().map_err(werr)?;
        drop(f);
        std::fs::rename(&self.tmp, &self.path).map_err(werr)
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.as_mut().expect("not finished").write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.as_mut().expect("not finished").flush()
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.file.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Remove the temporary files that killed runs left in `dir` and its sub-folders
/// (`.<name>.tmp-<pid>-<n>` of [`write_atomic`] and [`AtomicFile`] whose process no longer runs),
/// so a re-run into the same folder leaves only whole outputs. Files of a process that is still
/// running (per `/proc`) are kept; where `/proc` does not exist none is removed. Returns how
/// many were removed.
pub fn remove_stale_temp_files(dir: &Path) -> Result<usize> {
    let proc_fs = Path::new("/proc/self").exists();
    let me = std::process::id();
    let mut removed = 0;
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(0);
    };
    for e in entries.flatten() {
        let path = e.path();
        let Ok(ft) = e.file_type() else { continue };
        if ft.is_dir() {
            removed += remove_stale_temp_files(&path)?;
            continue;
        }
        let name = e.file_name().to_string_lossy().to_string();
        let Some(pid) = name
            .strip_prefix('.')
            .and_then(|n| n.rsplit_once(".tmp-"))
            .and_then(|(_, pid)| pid.split('-').next().unwrap_or("").parse::<u32>().ok())
        else {
            continue;
        };
        if !proc_fs || pid == me || Path::new("/proc").join(pid.to_string()).exists() {
            continue;
        }
        std::fs::remove_file(&path).map_err(|err| LdhError::Write {
            path: path.clone(),
            reason: err.to_string(),
        })?;
        removed += 1;
    }
    Ok(removed)
}

/// A lock on an output folder: the file `.ldh.lock` (holding the process id) exists while a run
/// writes into the folder, so a second concurrent run into the same folder is refused instead
/// of interleaving its files with the first's. The lock is removed on drop (every exit path,
/// errors included); a lock left by a killed run (its process no longer in `/proc`) is taken
/// over.
#[derive(Debug)]
pub struct OutputLock {
    path: std::path::PathBuf,
}

impl OutputLock {
    /// Lock `dir` (created if missing).
    pub fn acquire(dir: &Path) -> Result<OutputLock> {
        let write_err = |path: &Path, err: std::io::Error| LdhError::Write {
            path: path.to_path_buf(),
            reason: err.to_string(),
        };
        std::fs::create_dir_all(dir).map_err(|e| write_err(dir, e))?;
        let path = dir.join(".ldh.lock");
        for _ in 0..2 {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut f) => {
                    use std::io::Write;
                    write!(f, "{}", std::process::id()).map_err(|e| write_err(&path, e))?;
                    return Ok(OutputLock { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    if let Some(holder) = live_holder(&path) {
                        return Err(LdhError::Write {
                            path: dir.to_path_buf(),
                            reason: format!(
                                "another ldh run (process {holder}) is writing to this folder; wait for it, \
                                 or remove {} if no such run exists",
                                path.display()
                            ),
                        });
                    }
                    // A killed run's lock: take it over.
                    let _ = std::fs::remove_file(&path);
                }
                Err(e) => return Err(write_err(&path, e)),
            }
        }
        Err(LdhError::Write {
            path: path.clone(),
            reason: "could not take the lock".into(),
        })
    }
}

/// How long an empty lock file is read again before it is taken for a killed run's: a run
/// writes its id right after creating the file, so it is empty only for that instant, or for
/// good when the run was killed in between.
const EMPTY_LOCK_WAIT_MS: u64 = 1000;

/// The process id in the lock file `path` when that process may still run (per `/proc`; where
/// `/proc` does not exist, or the file holds something else than an id, it is taken to run);
/// `None` for a killed run's lock, including one still empty after [`EMPTY_LOCK_WAIT_MS`].
pub fn live_holder(path: &Path) -> Option<String> {
    let read = || {
        let holder = std::fs::read_to_string(path).unwrap_or_default();
        holder.trim().to_string()
    };
    let mut holder = read();
    let mut waited_ms = 0;
    while holder.is_empty() && waited_ms < EMPTY_LOCK_WAIT_MS && path.exists() {
        std::thread::sleep(std::time::Duration::from_millis(50));
        waited_ms += 50;
        holder = read();
    }
    if holder.is_empty() {
        return None;
    }
    let alive = match holder.parse::<u32>().ok() {
        Some(p) if Path::new("/proc/self").exists() => {
            Path::new("/proc").join(p.to_string()).exists()
        }
        _ => true,
    };
    alive.then_some(holder)
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Options of the writer.
#[derive(Debug, Clone, PartialEq)]
pub struct WriteOptions {
    /// Decimal places for acceleration (in the format's unit). Default 5.
    pub acc_decimals: usize,
    /// Decimal places for angular velocity (in the format's unit). Default 3.
    pub gyro_decimals: usize,
    /// Decimal places for time in s (ms and µs scale accordingly). Default 4.
    pub time_decimals: usize,
    /// Lines written before the header, each prefixed with the format's first comment prefix.
    pub preamble: Vec<String>,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            acc_decimals: 5,
            gyro_decimals: 3,
            time_decimals: 4,
            preamble: Vec::new(),
        }
    }
}

/// Render `rec` as CSV text in `spec` (units, scale, axis map, delimiter, time column).
///
/// Integer-count formats (`scale` ≠ 1) are written as rounded integers.
pub fn recording_to_csv(rec: &Recording, spec: &FormatSpec, opts: &WriteOptions) -> Result<String> {
    spec.validate()?;
    check_counter_rate(rec, spec)?;
    let delim = match spec.delimiter {
        Delimiter::Auto => ',',
        d => d.byte().expect("not auto") as char,
    };
    let inv = spec.axis_map()?.inverse();
    let n = rec.len();
    let mut out = String::with_capacity(n * 64 + 256);
    write_head(&mut out, spec, opts, delim)?;
    let cells = Cells::new(spec, opts);
    let mut fields: Vec<String> = Vec::with_capacity(7);
    for i in 0..n {
        fields.clear();
        let t = rec.t0_s + rec.time_s(i);
        fields.extend(cells.time(t));
        let a = [rec.acc_g[0][i], rec.acc_g[1][i], rec.acc_g[2][i]];
        let g = [rec.gyro_dps[0][i], rec.gyro_dps[1][i], rec.gyro_dps[2][i]];
        let a_in = inv.apply(a);
        let g_in = inv.apply(g);
        for v in a_in {
            fields.push(cells.num(v * cells.acc_from_g, cells.acc_dec, cells.acc_int));
        }
        for v in g_in {
            fields.push(cells.num(v * cells.gyro_from_dps, cells.gyro_dec, cells.gyro_int));
        }
        out.push_str(&fields.join(&delim.to_string()));
        out.push('\n');
    }
    Ok(out)
}

/// A format that numbers samples (a counter, or no time column) must state the recording's rate.
fn check_counter_rate(rec: &Recording, spec: &FormatSpec) -> Result<()> {
    if matches!(spec.time.unit, TimeUnit::Counter | TimeUnit::None) {
        let stated = spec.time.rate_hz.expect("validated");
        if (stated - rec.fs_hz).abs() > 1e-9 * rec.fs_hz {
            return Err(LdhError::Format {
                name: spec.name.clone(),
                reason: format!(
                    "states {stated} Hz for its sample counter but the recording is at {} Hz; use a copy of the format with time.rate_hz = {}",
                    rec.fs_hz, rec.fs_hz
                ),
            });
        }
    }
    Ok(())
}

/// The preamble (as comments), the header row and the rows of units the format skips.
fn write_head(out: &mut String, spec: &FormatSpec, opts: &WriteOptions, delim: char) -> Result<()> {
    if !opts.preamble.is_empty() {
        let prefix = spec
            .comment_prefixes
            .first()
            .map(String::as_str)
            .unwrap_or("#");
        for l in &opts.preamble {
            out.push_str(prefix);
            out.push(' ');
            out.push_str(l);
            out.push('\n');
        }
    }
    let header = spec.column_names_for_writing()?;
    out.push_str(&header.join(&delim.to_string()));
    out.push('\n');
    for _ in 0..spec.skip_rows_after_header {
        let mut units: Vec<String> = Vec::new();
        if spec.time.column.is_some() {
            units.push(format!("{:?}", spec.time.unit).to_lowercase());
        }
        let au = match spec.acc.unit {
            AccUnit::G => "g",
            AccUnit::Mps2 => "m/s^2",
        };
        let gu = match spec.gyro.unit {
            GyroUnit::Dps => "deg/s",
            GyroUnit::Rps => "rad/s",
        };
        units.extend([au, au, au, gu, gu, gu].map(String::from));
        out.push_str(&units.join(&delim.to_string()));
        out.push('\n');
    }
    Ok(())
}

/// How the cells of a row are written in a format: unit conversions, digits, integer counts
/// and the decimal separator.
struct Cells<'a> {
    spec: &'a FormatSpec,
    opts: &'a WriteOptions,
    /// Multiplier from g to the file's raw acceleration.
    acc_from_g: f64,
    /// Multiplier from deg/s to the file's raw angular velocity.
    gyro_from_dps: f64,
    /// Acceleration written as integer counts.
    acc_int: bool,
    /// Angular velocity written as integer counts.
    gyro_int: bool,
    /// Digits of the file's acceleration unit.
    acc_dec: usize,
    /// Digits of the file's angular-velocity unit.
    gyro_dec: usize,
}

impl<'a> Cells<'a> {
    fn new(spec: &'a FormatSpec, opts: &'a WriteOptions) -> Self {
        let acc_from_g = match spec.acc.unit {
            AccUnit::G => 1.0,
            AccUnit::Mps2 => STANDARD_GRAVITY_MPS2,
        } / spec.acc.scale;
        let gyro_from_dps = match spec.gyro.unit {
            GyroUnit::Dps => 1.0,
            GyroUnit::Rps => std::f64::consts::PI / 180.0,
        } / spec.gyro.scale;
        // Digits needed for the file's native acc unit.
        let acc_dec = if spec.acc.unit == AccUnit::Mps2 {
            opts.acc_decimals.saturating_sub(1).max(3)
        } else {
            opts.acc_decimals
        };
        let gyro_dec = if spec.gyro.unit == GyroUnit::Rps {
            opts.gyro_decimals + 2
        } else {
            opts.gyro_decimals
        };
        Cells {
            spec,
            opts,
            acc_from_g,
            gyro_from_dps,
            acc_int: spec.acc.scale != 1.0,
            gyro_int: spec.gyro.scale != 1.0,
            acc_dec,
            gyro_dec,
        }
    }

    /// A number with `decimals` digits, or rounded to an integer count.
    fn num(&self, v: f64, decimals: usize, integer: bool) -> String {
        let s = if integer {
            format!("{}", v.round() as i64)
        } else {
            format!("{v:.decimals$}")
        };
        if self.spec.decimal == Decimal::Comma {
            s.replace('.', ",")
        } else {
            s
        }
    }

    /// The time cell at `t` s in the format's time unit (none without a time column).
    fn time(&self, t: f64) -> Option<String> {
        let (spec, opts) = (self.spec, self.opts);
        Some(match spec.time.unit {
            TimeUnit::Seconds => self.num(t, opts.time_decimals, false),
            TimeUnit::Milliseconds => {
                self.num(t * 1e3, opts.time_decimals.saturating_sub(3), false)
            }
            TimeUnit::Microseconds => self.num(t * 1e6, 0, false),
            TimeUnit::HundredMicroseconds => self.num(t * 1e4, 0, false),
            TimeUnit::Nanoseconds => self.num(t * 1e9, 0, false),
            TimeUnit::Counter => {
                let rate = spec.time.rate_hz.expect("validated");
                let mut c = (t * rate).round() as u64;
                if let Some(w) = spec.time.counter_wrap {
                    c %= w;
                }
                c.to_string()
            }
            TimeUnit::Iso8601 => format_iso8601(t),
            TimeUnit::None => return None,
        })
    }
}

/// Write `rec` to `path` in `spec`, atomically.
pub fn write_recording(
    path: impl AsRef<Path>,
    rec: &Recording,
    spec: &FormatSpec,
    opts: &WriteOptions,
) -> Result<()> {
    let text = recording_to_csv(rec, spec, opts)?;
    write_atomic(path, text.as_bytes())
}

/// Seconds since 1970-01-01 as `YYYY-MM-DDTHH:MM:SS.mmm` (UTC).
pub fn format_iso8601(t: f64) -> String {
    let ms_total = (t * 1000.0).round() as i64;
    let days = ms_total.div_euclid(86_400_000);
    let ms_day = ms_total.rem_euclid(86_400_000);
    // Civil from days (Howard Hinnant's algorithm).
    let z = days + 719468;
    let era = if z >= 0 { z } else { z - 146096 } / 146097;
    let doe = z - era * 146097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = if m <= 2 { y + 1 } else { y };
    let (h, rem) = (ms_day / 3_600_000, ms_day % 3_600_000);
    let (mi, rem) = (rem / 60_000, rem % 60_000);
    let (s, ms) = (rem / 1000, rem % 1000);
    format!("{y:04}-{m:02}-{d:02}T{h:02}:{mi:02}:{s:02}.{ms:03}")
}
