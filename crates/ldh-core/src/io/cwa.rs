//! Axivity AX3 / AX6 `.cwa` files (Open Movement "continuous wave accelerometry"), the binary
//! format of multi-day wear studies (UK Biobank's wrist AX3; the AX6 with gyroscope in
//! Mobilise-D): read in streaming chunks ([`CwaReader`], an iterator of [`CwaChunk`]s) and
//! written ([`CwaWriter`], the simulator's `--format cwa`), so a week is never held whole.
//!
//! Format (Open Movement, `Docs/ax3/cwa.h` and `ax3-technical.md` in
//! github.com/digitalinteraction/openmovement): little-endian, a 1024-byte header block
//! (`MD`: hardware type 0x64 = AX6, device and session id, sensor configuration, rate code)
//! then 512-byte data blocks (`AX`: sequence number, the RTC timestamp packed as
//! `YYYYYYMM MMDDDDDh hhhhmmmm mmssssss` with the index of the sample it belongs to and an
//! optional 15-bit fraction of a second, rate code `3200 / 2^(15 − (code & 15))` Hz, range
//! `16 >> (code >> 6)` g, the axes and packing, the sample count and a checksum making the
//! 16-bit word sum of the block zero). Samples are 16-bit signed (`[gx gy gz] ax ay az`,
//! accelerometer 1/2^(8+n) g, gyroscope (4000/2^m)/32768 deg/s with n, m in the block's
//! `lightScale` bits) or, on the AX3, packed 10-bit with a 2-bit exponent (1/256 g).
//!
//! Written by hand: no maintained Rust reader is on crates.io (2026-12: `cwa_reader_rs`, the
//! Mobilise-D reader, is a Python extension only, not a crate), and the format is small and
//! documented. Time of a block's first sample: timestamp − (timestampOffset + fraction ·
//! rate) / rate, as Open Movement's readers compute it (they round the fraction down to whole
//! samples; kept exact here). Blocks with a bad checksum, or of another type, are skipped and
//! counted ([`CwaReader::skipped_blocks`]).

use std::fs::File;
use std::io::{BufReader, Read, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::start_time::days_from_civil;
use super::{AtomicFile, DateTime};
use crate::error::{LdhError, Result};

/// Bytes of a data block (and of a sector): 512.
pub const BLOCK_BYTES: usize = 512;
/// Bytes of the header: 1024.
pub const HEADER_BYTES: usize = 1024;
/// Samples of a full AX6 block with gyroscope (16-bit, 6 axes): 40.
pub const AX6_SAMPLES_PER_BLOCK: usize = 40;

/// The device that wrote the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum CwaDevice {
    /// AX3: accelerometer only.
    Ax3,
    /// AX6: accelerometer and gyroscope.
    Ax6,
}

/// What the header and the first data block say.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CwaInfo {
    /// The file.
    pub path: PathBuf,
    /// Device type (header byte 4).
    pub device: CwaDevice,
    /// Device identifier.
    pub device_id: u32,
    /// Session identifier.
    pub session_id: u32,
    /// Sampling rate of the first data block, Hz.
    pub fs_hz: f64,
    /// Accelerometer range (±), g.
    pub acc_range_g: f64,
    /// Gyroscope range (±), deg/s, when the blocks hold a gyroscope.
    pub gyro_range_dps: Option<f64>,
    /// Date and time of the first sample, to the second (the device clock, zone not stated).
    pub start: Option<DateTime>,
    /// The same in seconds since 1970 (with the fraction).
    pub start_unix_s: Option<f64>,
    /// Data blocks in the file (from its size).
    pub blocks: u64,
    /// The header's metadata text (URL-encoded name-value pairs), trailing padding removed.
    pub annotation: String,
}

/// A run of samples: each sample's time, acceleration and (AX6) angular velocity.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CwaChunk {
    /// Time of each sample, s from the file's first sample (gaps and clock jumps show here).
    pub time_s: Vec<f64>,
    /// Acceleration per axis, g.
    pub acc_g: [Vec<f64>; 3],
    /// Angular velocity per axis, deg/s (`None` for accelerometer-only files).
    pub gyro_dps: Option<[Vec<f64>; 3]>,
}

impl CwaChunk {
    /// Samples in the chunk.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }
    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }
}

fn le16(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}
fn le32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// Seconds since 1970 of a packed CWA timestamp (`None` for 0 or an impossible date).
fn unpack_time(v: u32) -> Option<(DateTime, f64)> {
    if v == 0 || v == u32::MAX {
        return None;
    }
    let f = |shift: u32, mask: u32| i64::from((v >> shift) & mask);
    let dt = DateTime::new(
        (f(26, 0x3f) + 2000, f(22, 0x0f), f(17, 0x1f)),
        (f(12, 0x1f), f(6, 0x3f), f(0, 0x3f)),
        false,
    )?;
    Some((dt, unix_s(&dt) as f64))
}

fn unix_s(dt: &DateTime) -> i64 {
    days_from_civil(i64::from(dt.year), i64::from(dt.month), i64::from(dt.day)) * 86_400
        + i64::from(dt.hour) * 3600
        + i64::from(dt.minute) * 60
        + i64::from(dt.second)
}

fn pack_time(dt: &DateTime) -> u32 {
    (u32::from(dt.year.saturating_sub(2000)) & 0x3f) << 26
        | u32::from(dt.month) << 22
        | u32::from(dt.day) << 17
        | u32::from(dt.hour) << 12
        | u32::from(dt.minute) << 6
        | u32::from(dt.second)
}

/// Rate of a rate code, Hz: 3200 / 2^(15 − (code & 15)).
fn rate_hz(code: u8) -> f64 {
    3200.0 / f64::from(1u32 << (15 - u32::from(code & 0x0f)))
}

/// One decoded data block.
struct Block {
    /// Seconds since 1970 of its first sample.
    t0_unix_s: f64,
    fs_hz: f64,
    acc_range_g: f64,
    gyro_range_dps: Option<f64>,
    /// Per sample: acc x, y, z (g), gyro x, y, z (deg/s, 0 without gyroscope).
    samples: Vec<[f64; 6]>,
    has_gyro: bool,
}

/// Decode a data block; `None` when it is not a valid `AX` block (type or checksum).
fn decode_block(b: &[u8], header_gyro_dps: Option<f64>) -> Option<Block> {
    if &b[0..2] != b"AX" {
        return None;
    }
    let sum = (0..BLOCK_BYTES / 2).fold(0u16, |s, i| s.wrapping_add(le16(b, 2 * i)));
    if sum != 0 {
        return None;
    }
    let fractional = le16(b, 4);
    let (_, t_unix) = unpack_time(le32(b, 14))?;
    let light_scale = le16(b, 18);
    let code = b[24];
    let fs = rate_hz(code);
    let axes = usize::from(b[25] >> 4);
    let packing = b[25] & 0x0f;
    let ts_offset = f64::from(le16(b, 26) as i16);
    let count = usize::from(le16(b, 28));
    let frac = if fractional & 0x8000 != 0 {
        f64::from(fractional & 0x7fff) / 32768.0
    } else {
        0.0
    };
    let acc_n = u32::from(light_scale >> 13);
    let acc_lsb = 1.0 / f64::from(1u32 << (8 + acc_n));
    let gyro_n = u32::from((light_scale >> 10) & 7);
    let gyro_range = if gyro_n > 0 {
        Some(4000.0 / f64::from(1u32 << gyro_n))
    } else {
        header_gyro_dps
    };
    let data = &b[30..510];
    let mut samples = Vec::with_capacity(count);
    let has_gyro = axes >= 6;
    match (packing, axes) {
        (0, 3) if count <= 120 => {
            for i in 0..count {
                let v = le32(data, 4 * i);
                let e = v >> 30;
                let ax = |s: u32| {
                    let raw = ((v >> s) & 0x3ff) as i32;
                    let signed = if raw & 0x200 != 0 { raw - 0x400 } else { raw };
                    f64::from(signed << e) / 256.0
                };
                samples.push([ax(0), ax(10), ax(20), 0.0, 0.0, 0.0]);
            }
        }
        (2, 3 | 6 | 9) if count * axes * 2 <= 480 => {
            let g = gyro_range.unwrap_or(2000.0) / 32768.0;
            for i in 0..count {
                let at = |k: usize| f64::from(le16(data, 2 * (i * axes + k)) as i16);
                samples.push(if has_gyro {
                    [
                        at(3) * acc_lsb,
                        at(4) * acc_lsb,
                        at(5) * acc_lsb,
                        at(0) * g,
                        at(1) * g,
                        at(2) * g,
                    ]
                } else {
                    [
                        at(0) * acc_lsb,
                        at(1) * acc_lsb,
                        at(2) * acc_lsb,
                        0.0,
                        0.0,
                        0.0,
                    ]
                });
            }
        }
        _ => return None,
    }
    Some(Block {
        t0_unix_s: t_unix - (ts_offset + frac * fs) / fs,
        fs_hz: fs,
        acc_range_g: f64::from(16u32 >> (code >> 6)),
        gyro_range_dps: if has_gyro { gyro_range } else { None },
        samples,
        has_gyro,
    })
}

/// A `.cwa` file read block by block, yielding chunks of about `chunk_samples` samples.
#[derive(Debug)]
pub struct CwaReader<R: Read> {
    src: R,
    info: CwaInfo,
    header_gyro_dps: Option<f64>,
    chunk_samples: usize,
    /// Seconds since 1970 of the first sample (time 0 of the chunks).
    origin: f64,
    pending: Option<Vec<u8>>,
    skipped: u64,
    done: bool,
}

impl CwaReader<BufReader<File>> {
    /// Open `path`: read the header and the first valid data block (for the rate and the
    /// start). Errors: the file cannot be read, or it is not a `.cwa` file.
    pub fn open(path: impl AsRef<Path>, chunk_samples: usize) -> Result<Self> {
        let path = path.as_ref();
        let file = File::open(path).map_err(|source| LdhError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let len = file.metadata().map(|m| m.len()).unwrap_or(0);
        let mut r =
            CwaReader::from_reader(BufReader::with_capacity(1 << 16, file), path, chunk_samples)?;
        r.info.blocks = len.saturating_sub(HEADER_BYTES as u64) / BLOCK_BYTES as u64;
        Ok(r)
    }
}

impl<R: Read> CwaReader<R> {
    /// Read from `src` (named `path` in messages and in [`CwaInfo::path`]).
    pub fn from_reader(mut src: R, path: &Path, chunk_samples: usize) -> Result<Self> {
        let bad = |reason: String| LdhError::Format {
            name: path.display().to_string(),
            reason,
        };
        let mut head = vec![0u8; HEADER_BYTES];
        read_full(&mut src, &mut head, path)?
            .then_some(())
            .ok_or_else(|| bad("shorter than a .cwa header (1024 bytes)".into()))?;
        if &head[0..2] != b"MD" {
            return Err(bad(format!(
                "not an Axivity .cwa file: it begins {:?}, not \"MD\"",
                String::from_utf8_lossy(&head[0..2])
            )));
        }
        let device = if head[4] == 0x64 {
            CwaDevice::Ax6
        } else {
            CwaDevice::Ax3
        };
        let upper = le16(&head, 11);
        let device_id = u32::from(le16(&head, 5))
            | if upper == 0xffff {
                0
            } else {
                u32::from(upper) << 16
            };
        let cfg = head[35];
        let header_gyro_dps = (cfg != 0 && cfg != 0xff && (cfg & 0x0f) > 0)
            .then(|| 8000.0 / f64::from(1u32 << (cfg & 0x0f)));
        let annotation = String::from_utf8_lossy(&head[64..512])
            .trim_end_matches([' ', '\0', '\u{fffd}'])
            .to_string();
        let mut r = CwaReader {
            src,
            info: CwaInfo {
                path: path.to_path_buf(),
                device,
                device_id,
                session_id: le32(&head, 7),
                fs_hz: rate_hz(head[36]),
                acc_range_g: f64::from(16u32 >> (head[36] >> 6)),
                gyro_range_dps: header_gyro_dps,
                start: None,
                start_unix_s: None,
                blocks: 0,
                annotation,
            },
            header_gyro_dps,
            chunk_samples: chunk_samples.max(1),
            origin: 0.0,
            pending: None,
            skipped: 0,
            done: false,
        };
        let mut buf = vec![0u8; BLOCK_BYTES];
        while read_full(&mut r.src, &mut buf, path)? {
            if let Some(b) = decode_block(&buf, header_gyro_dps) {
                r.info.fs_hz = b.fs_hz;
                r.info.acc_range_g = b.acc_range_g;
                r.info.gyro_range_dps = b.gyro_range_dps;
                r.info.start_unix_s = Some(b.t0_unix_s);
                r.info.start =
                    DateTime::from_unix_s(b.t0_unix_s).map(|d| DateTime { utc: false, ..d });
                r.origin = b.t0_unix_s;
                r.pending = Some(buf);
                return Ok(r);
            }
            r.skipped += 1;
        }
        Err(bad("no valid data block: the recording is empty".into()))
    }

    /// The header's and first block's description.
    pub fn info(&self) -> &CwaInfo {
        &self.info
    }

    /// Blocks skipped so far (another type or a bad checksum).
    pub fn skipped_blocks(&self) -> u64 {
        self.skipped
    }

    fn next_chunk(&mut self) -> Result<Option<CwaChunk>> {
        let mut c = CwaChunk::default();
        let path = self.info.path.clone();
        while c.len() < self.chunk_samples {
            let buf = match self.pending.take() {
                Some(b) => b,
                None => {
                    let mut b = vec![0u8; BLOCK_BYTES];
                    if !read_full(&mut self.src, &mut b, &path)? {
                        self.done = true;
                        break;
                    }
                    b
                }
            };
            let Some(b) = decode_block(&buf, self.header_gyro_dps) else {
                self.skipped += 1;
                continue;
            };
            if b.has_gyro && c.gyro_dps.is_none() {
                c.gyro_dps = Some(Default::default());
            }
            for (i, s) in b.samples.iter().enumerate() {
                c.time_s
                    .push(b.t0_unix_s - self.origin + i as f64 / b.fs_hz);
                for k in 0..3 {
                    c.acc_g[k].push(s[k]);
                    if let Some(g) = c.gyro_dps.as_mut() {
                        g[k].push(s[k + 3]);
                    }
                }
            }
        }
        Ok((!c.is_empty()).then_some(c))
    }
}

impl<R: Read> Iterator for CwaReader<R> {
    type Item = Result<CwaChunk>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.done && self.pending.is_none() {
            return None;
        }
        self.next_chunk().transpose()
    }
}

/// Fill `buf` from `src`: `Ok(true)` when full, `Ok(false)` at the end of the file (a
/// truncated last block is dropped).
fn read_full<R: Read>(src: &mut R, buf: &mut [u8], path: &Path) -> Result<bool> {
    let mut got = 0;
    while got < buf.len() {
        match src.read(&mut buf[got..]) {
            Ok(0) => return Ok(false),
            Ok(n) => got += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(source) => {
                return Err(LdhError::Io {
                    path: path.to_path_buf(),
                    source,
                })
            }
        }
    }
    Ok(true)
}

mod writer;
pub use writer::{CwaWriter, CwaWriterParams};

#[cfg(test)]
mod tests;
