//! The `.cwa` writer: AX6 files with gyroscope, 16-bit samples (the simulator's `--format cwa`
//! and the reader's round-trip tests); the format is in the parent module's docs.

use super::*;

/// How a [`CwaWriter`] writes: an AX6 file with gyroscope, 16-bit samples.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CwaWriterParams {
    /// Sampling rate, Hz: 3200 / 2^k (12.5, 25, 50, 100, 200, 400, 800, 1600).
    pub fs_hz: f64,
    /// Accelerometer range, g: 2, 4, 8 or 16.
    pub acc_range_g: f64,
    /// Gyroscope range, deg/s: 125, 250, 500, 1000 or 2000.
    pub gyro_range_dps: f64,
    /// Date and time of sample index 0 (the device clock).
    pub start: DateTime,
    /// Device identifier.
    pub device_id: u16,
    /// Session identifier.
    pub session_id: u32,
    /// Header metadata text (at most 448 bytes).
    pub annotation: String,
}

/// Writes an AX6 `.cwa` file sample by sample; sample k is at `start + k / fs_hz`.
#[derive(Debug)]
pub struct CwaWriter<W: Write> {
    out: W,
    start_unix_s: f64,
    fs_hz: f64,
    rate_code: u8,
    light_scale: u16,
    acc_lsb: f64,
    gyro_lsb: f64,
    session_id: u32,
    /// Index of the next sample.
    k: u64,
    seq: u32,
    buf: Vec<[i16; 6]>,
}

fn log2_exact(x: f64) -> Option<u32> {
    let l = x.log2().round();
    ((2f64.powf(l) - x).abs() < 1e-9 * x && l >= 0.0).then_some(l as u32)
}

impl CwaWriter<AtomicFile> {
    /// Create `path` (written through a temporary file, renamed by [`CwaWriter::finish`]).
    pub fn create(path: impl AsRef<Path>, p: &CwaWriterParams) -> Result<Self> {
        CwaWriter::new(AtomicFile::create(path)?, p)
    }
}

impl<W: Write> CwaWriter<W> {
    /// Check `p` and write the header to `out`.
    pub fn new(mut out: W, p: &CwaWriterParams) -> Result<Self> {
        let bad = |name: &'static str, v: f64, why: &str| LdhError::param(name, v, why.to_string());
        let k = log2_exact(3200.0 / p.fs_hz)
            .filter(|&k| (1..=8).contains(&k))
            .ok_or_else(|| {
                bad(
                    "fs_hz",
                    p.fs_hz,
                    "a .cwa rate is 3200 / 2^k Hz: 12.5, 25, 50, 100, 200, 400, 800 or 1600",
                )
            })?;
        let a = log2_exact(p.acc_range_g)
            .filter(|&a| (1..=4).contains(&a))
            .ok_or_else(|| {
                bad(
                    "acc_range_g",
                    p.acc_range_g,
                    "an AX6 accelerometer range is 2, 4, 8 or 16 g",
                )
            })?;
        let g = log2_exact(4000.0 / p.gyro_range_dps)
            .filter(|&g| (1..=5).contains(&g))
            .ok_or_else(|| {
                bad(
                    "gyro_range_dps",
                    p.gyro_range_dps,
                    "an AX6 gyroscope range is 125, 250, 500, 1000 or 2000 deg/s",
                )
            })?;
        let rate_code = (15 - k) as u8 | (((4 - a) as u8) << 6);
        let acc_n = 7 - a; // 1/2^(8+n) g per count: ±16 g → n = 3
        let mut head = vec![0u8; HEADER_BYTES];
        head[0..2].copy_from_slice(b"MD");
        head[2..4].copy_from_slice(&1020u16.to_le_bytes());
        head[4] = 0x64;
        head[5..7].copy_from_slice(&p.device_id.to_le_bytes());
        head[7..11].copy_from_slice(&p.session_id.to_le_bytes());
        head[13..17].copy_from_slice(&pack_time(&p.start).to_le_bytes());
        head[17..21].copy_from_slice(&u32::MAX.to_le_bytes());
        head[35] = (g + 1) as u8; // 8000 / 2^n deg/s
        head[36] = rate_code;
        head[37..41].copy_from_slice(&pack_time(&p.start).to_le_bytes());
        head[42..44].copy_from_slice(&(-1i16).to_le_bytes());
        head[64..512].fill(b' ');
        let text = p.annotation.as_bytes();
        head[64..64 + text.len().min(448)].copy_from_slice(&text[..text.len().min(448)]);
        head[512..].fill(0xff);
        out.write_all(&head).map_err(werr)?;
        Ok(CwaWriter {
            out,
            start_unix_s: unix_s(&p.start) as f64,
            fs_hz: p.fs_hz,
            rate_code,
            light_scale: ((acc_n as u16) << 13) | ((g as u16) << 10),
            acc_lsb: 1.0 / f64::from(1u32 << (8 + acc_n)),
            gyro_lsb: p.gyro_range_dps / 32768.0,
            session_id: p.session_id,
            k: 0,
            seq: 0,
            buf: Vec::with_capacity(AX6_SAMPLES_PER_BLOCK),
        })
    }

    /// The first sample written is sample `k0` (at `start + k0 / fs_hz`). Call before any
    /// sample.
    pub fn first_index(mut self, k0: u64) -> Self {
        self.k = k0;
        self
    }

    /// Append one sample (g, deg/s), clipped to the ranges.
    pub fn push(&mut self, acc_g: [f64; 3], gyro_dps: [f64; 3]) -> Result<()> {
        let q = |v: f64, lsb: f64| (v / lsb).round().clamp(-32768.0, 32767.0) as i16;
        self.buf.push([
            q(gyro_dps[0], self.gyro_lsb),
            q(gyro_dps[1], self.gyro_lsb),
            q(gyro_dps[2], self.gyro_lsb),
            q(acc_g[0], self.acc_lsb),
            q(acc_g[1], self.acc_lsb),
            q(acc_g[2], self.acc_lsb),
        ]);
        if self.buf.len() == AX6_SAMPLES_PER_BLOCK {
            self.write_block()?;
        }
        Ok(())
    }

    fn write_block(&mut self) -> Result<()> {
        let n = self.buf.len();
        if n == 0 {
            return Ok(());
        }
        let first = self.k;
        // Whole second T at or before the block's first sample, the sample index where it
        // falls (−k0) and the remaining fraction, so that T − (offset + frac·fs)/fs is exact.
        let s = self.start_unix_s + first as f64 / self.fs_hz;
        let t = s.floor();
        let k0 = ((s - t) * self.fs_hz - 1e-9).ceil().max(0.0);
        let frac = (k0 - (s - t) * self.fs_hz) / self.fs_hz;
        let dt = DateTime::from_unix_s(t)
            .ok_or_else(|| LdhError::param("start", t, "outside 1970–9999"))?;
        let mut b = [0u8; BLOCK_BYTES];
        b[0..2].copy_from_slice(b"AX");
        b[2..4].copy_from_slice(&508u16.to_le_bytes());
        let f = 0x8000u16 | ((frac * 32768.0).round() as u16).min(0x7fff);
        b[4..6].copy_from_slice(&f.to_le_bytes());
        b[6..10].copy_from_slice(&self.session_id.to_le_bytes());
        b[10..14].copy_from_slice(&self.seq.to_le_bytes());
        b[14..18].copy_from_slice(&pack_time(&dt).to_le_bytes());
        b[18..20].copy_from_slice(&self.light_scale.to_le_bytes());
        b[24] = self.rate_code;
        b[25] = 0x62;
        b[26..28].copy_from_slice(&(-(k0 as i16)).to_le_bytes());
        b[28..30].copy_from_slice(&(n as u16).to_le_bytes());
        for (i, s) in self.buf.iter().enumerate() {
            for (j, v) in s.iter().enumerate() {
                let at = 30 + 2 * (6 * i + j);
                b[at..at + 2].copy_from_slice(&v.to_le_bytes());
            }
        }
        let sum = (0..255).fold(0u16, |s, i| s.wrapping_add(le16(&b, 2 * i)));
        b[510..512].copy_from_slice(&0u16.wrapping_sub(sum).to_le_bytes());
        self.out.write_all(&b).map_err(werr)?;
        self.k += n as u64;
        self.seq += 1;
        self.buf.clear();
        Ok(())
    }

    /// Samples written (including any not yet in a full block).
    pub fn samples(&self) -> u64 {
        self.k + self.buf.len() as u64
    }

    /// Write the last (partial) block and return the output.
    pub fn finish(mut self) -> Result<W> {
        self.write_block()?;
        Ok(self.out)
    }
}

fn werr(e: std::io::Error) -> LdhError {
    LdhError::Write {
        path: PathBuf::from("(.cwa)"),
        reason: e.to_string(),
    }
}
