//! One subject from plan to files, streamed: each segment is rendered in chunks of at most
//! [`CHUNK`] samples, turned into each device's frame, resampled onto the right sensor's
//! clock, measured (bias, noise, quantisation, clipping) and appended to the leg's file. Only
//! one chunk (and one gait bout) is held at a time.

use std::io::Write;
use std::path::Path;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::plan::{plan, Activity, Motion, Segment, GAIT_STANDING_S};
use super::render::{render_analytic, render_gait, LegSignal};
use super::truth::{write_truth_bouts, FreeLivingTruth, TruthBout};
use super::{FreeLivingParams, FreeLivingSubject};
use crate::draw::std_normal;
use crate::sensor::Mounting;
use crate::{SensorModel, SubjectParams};
use ldh_core::error::{LdhError, Result};
use ldh_core::io::AtomicFile;
use ldh_core::recording::Side;

/// Samples rendered at once: one minute at 100 Hz.
pub(super) const CHUNK: usize = 6000;

/// Simulate subject `i` of `params` into `out_dir/<subject>/`.
pub(super) fn simulate_subject_to(
    params: &FreeLivingParams,
    i: usize,
    out_dir: &Path,
) -> Result<FreeLivingSubject> {
    let (id, group) = params.subject(i);
    let dir = out_dir.join(&id);
    let stream = |k: u64| {
        let mut r = ChaCha8Rng::seed_from_u64(params.seed);
        r.set_stream((2u64 << 32) + 3 * i as u64 + k);
        r
    };
    let mut rng = stream(0);
    let fs = params.fs_hz;
    let mut base = draw_person(params, i, &id, &group, &mut rng);
    base.stride_time_s *= params.stride_time_factor;
    let drift_ppm = params.drift_ppm.unwrap_or_else(|| {
        let m = rng.gen_range(20.0..50.0);
        if rng.gen_bool(0.5) {
            m
        } else {
            -m
        }
    });
    let devices = [Side::Left, Side::Right].map(|side| {
        let m = Mounting::draw(&params.sensor, side, &mut rng);
        let noise = stream(if side == Side::Left { 1 } else { 2 });
        Device::new(&params.sensor, m.mount, noise)
    });
    let segments = plan(params, &base, &mut rng);
    let ext = params.format.extension();
    let mut sinks = [
        CsvSink::create(&dir.join(format!("left.{ext}")), params, 0.0)?,
        CsvSink::create(&dir.join(format!("right.{ext}")), params, 0.0)?,
    ];
    let mut run = Run {
        fs,
        devices,
        resampler: Resampler::new(fs, drift_ppm, params.right_clock_offset_s),
        buf: Default::default(),
        dev: Default::default(),
        right: LegSignal::default(),
        next_index: 0,
    };
    let mut bouts: Vec<TruthBout> = Vec::new();
    for seg in &segments {
        run.segment(seg, &mut sinks, &mut bouts, &mut rng)?;
    }
    let n_left = run.next_index;
    let [left, right] = sinks;
    let n_right = right.rows;
    left.finish()?;
    right.finish()?;
    for (k, b) in bouts.iter_mut().enumerate() {
        b.bout = k + 1;
    }
    write_truth_bouts(&dir.join("truth_bouts.csv"), &bouts)?;
    let _ = GAIT_STANDING_S;
    let truth = FreeLivingTruth::new(params, &id, &base, drift_ppm, [n_left, n_right], &bouts);
    truth.write(&dir.join("truth.json"))?;
    Ok(FreeLivingSubject {
        subject_id: id,
        dir,
        truth,
    })
}

/// The person's gait: drawn from `rng` (the subject's stream), or, for the same person on
/// another day (`subject_seed`), from the person's own stream while the day (drift, mounting,
/// plan, noise) keeps `rng`'s. `rng` is advanced by the same draw in both cases.
fn draw_person(
    params: &FreeLivingParams,
    i: usize,
    id: &str,
    group: &crate::Group,
    rng: &mut ChaCha8Rng,
) -> SubjectParams {
    let fs = params.fs_hz;
    let base = SubjectParams::draw(id.to_string(), group.clone(), fs, 25.0, rng);
    match params.subject_seed {
        Some(seed) => {
            let mut own = ChaCha8Rng::seed_from_u64(seed);
            own.set_stream((2u64 << 32) + 3 * i as u64);
            SubjectParams::draw(id.to_string(), group.clone(), fs, 25.0, &mut own)
        }
        None => base,
    }
}

/// Append a truth row, merged with the previous one when both are the same non-gait activity.
fn push_bout(
    bouts: &mut Vec<TruthBout>,
    activity: Activity,
    start_s: f64,
    end_s: f64,
    steps: [usize; 2],
) {
    if end_s - start_s <= 1e-9 {
        return;
    }
    let gait = matches!(
        activity,
        Activity::Walking | Activity::Stairs | Activity::Running
    );
    if let Some(prev) = bouts.last_mut() {
        if prev.activity == activity && !gait && (prev.end_s - start_s).abs() < 1e-6 {
            prev.end_s = end_s;
            return;
        }
    }
    bouts.push(TruthBout {
        bout: 0,
        start_s,
        end_s,
        activity,
        steps_left: steps[0],
        steps_right: steps[1],
    });
}

/// The chunk pipeline's state.
struct Run {
    fs: f64,
    devices: [Device; 2],
    resampler: Resampler,
    /// Rendered samples in F, both legs, true clock.
    buf: [LegSignal; 2],
    /// The same in device frames.
    dev: [LegSignal; 2],
    /// The right leg resampled onto its clock.
    right: LegSignal,
    /// Global true-clock index of `buf`'s first sample.
    next_index: u64,
}

impl Run {
    /// Render one planned segment in chunks, write it to both files, and append its truth
    /// rows (a gait bout: the standing before its first and after its last heel strike, and
    /// the steps inside the segment).
    fn segment(
        &mut self,
        seg: &Segment,
        sinks: &mut [CsvSink; 2],
        bouts: &mut Vec<TruthBout>,
        rng: &mut ChaCha8Rng,
    ) -> Result<()> {
        let fs = self.fs;
        let i0 = (seg.start_s * fs).round() as usize;
        let i1 = ((seg.start_s + seg.duration_s) * fs).round() as usize;
        if i1 <= i0 {
            return Ok(());
        }
        let t0 = i0 as f64 / fs;
        let t1 = i1 as f64 / fs;
        if let Motion::Gait {
            params: p,
            impact_g,
        } = &seg.motion
        {
            let bout = render_gait(p, *impact_g, rng)?;
            let first = bout
                .hs_s
                .iter()
                .filter_map(|h| h.first())
                .fold(f64::INFINITY, |a, &b| a.min(b));
            let last = bout
                .hs_s
                .iter()
                .filter_map(|h| h.last())
                .fold(0.0, |a: f64, &b| a.max(b));
            let (ws, we) = ((t0 + first).min(t1), (t0 + last).min(t1));
            push_bout(bouts, Activity::Standing, t0, ws, [0, 0]);
            let steps = bout
                .hs_s
                .clone()
                .map(|h| h.iter().filter(|&&x| t0 + x <= t1).count());
            push_bout(bouts, seg.activity, ws, we, steps);
            push_bout(bouts, Activity::Standing, we, t1, [0, 0]);
            let mut j = 0;
            while j < i1 - i0 {
                let n = CHUNK.min(i1 - i0 - j);
                for (leg, sig) in self.buf.iter_mut().enumerate() {
                    sig.extend_from(&bout.legs[leg], j, j + n);
                }
                self.flush(sinks)?;
                j += n;
            }
        } else {
            push_bout(bouts, seg.activity, t0, t1, [0, 0]);
            let mounts = [self.devices[0].mount, self.devices[1].mount];
            let mut j = 0;
            while j < i1 - i0 {
                let n = CHUNK.min(i1 - i0 - j);
                let tj = j as f64 / fs;
                render_analytic(&seg.motion, tj, t1 - t0, n, fs, &mounts, &mut self.buf);
                self.flush(sinks)?;
                j += n;
            }
        }
        Ok(())
    }

    /// Measure and write the samples in `buf`, then clear it.
    fn flush(&mut self, sinks: &mut [CsvSink; 2]) -> Result<()> {
        let n = self.buf[0].len();
        for leg in 0..2 {
            self.dev[leg].clear();
            self.devices[leg].rotate(&self.buf[leg], &mut self.dev[leg]);
        }
        self.devices[0].measure(&mut self.dev[0]);
        sinks[0].write(self.next_index, &self.dev[0], self.fs)?;
        self.right.clear();
        let k0 = self
            .resampler
            .run(self.next_index, &self.dev[1], &mut self.right);
        self.devices[1].measure(&mut self.right);
        sinks[1].write(k0, &self.right, self.fs)?;
        self.next_index += n as u64;
        for b in self.buf.iter_mut() {
            b.clear();
        }
        Ok(())
    }
}

/// One device: its mounting on the leg, its constant biases and its noise stream.
struct Device {
    /// Device axes (columns) in F.
    mount: [[f64; 3]; 3],
    sensor: SensorModel,
    acc_bias: [f64; 3],
    gyro_bias: [f64; 3],
    rng: ChaCha8Rng,
}

impl Device {
    fn new(sensor: &SensorModel, mount: [[f64; 3]; 3], mut rng: ChaCha8Rng) -> Device {
        let gyro_bias = std::array::from_fn(|_| sensor.gyro_bias_dps_sd * std_normal(&mut rng));
        let acc_bias = std::array::from_fn(|_| sensor.acc_bias_g_sd * std_normal(&mut rng));
        Device {
            mount,
            sensor: sensor.clone(),
            acc_bias,
            gyro_bias,
            rng,
        }
    }

    /// F-frame samples in the device's axes: v_d[c] = Σ_r mount[r][c]·v_F[r].
    fn rotate(&self, f: &LegSignal, out: &mut LegSignal) {
        let m = &self.mount;
        for i in 0..f.len() {
            for c in 0..3 {
                let a = (0..3).map(|r| m[r][c] * f.acc_g[r][i]).sum();
                let w = (0..3).map(|r| m[r][c] * f.gyro_dps[r][i]).sum();
                out.acc_g[c].push(a);
                out.gyro_dps[c].push(w);
            }
        }
    }

    /// Bias, white noise and quantisation (when the model has noise), clipping at the range.
    fn measure(&mut self, sig: &mut LegSignal) {
        let s = &self.sensor;
        let acc_lsb = s.acc_range_g / 2f64.powi(s.bits as i32 - 1);
        let gyro_lsb = s.gyro_range_dps / 2f64.powi(s.bits as i32 - 1);
        for i in 0..sig.len() {
            for k in 0..3 {
                let a = &mut sig.acc_g[k][i];
                let w = &mut sig.gyro_dps[k][i];
                if s.noise {
                    *a = ((*a + self.acc_bias[k] + s.acc_noise_g * std_normal(&mut self.rng))
                        / acc_lsb)
                        .round()
                        * acc_lsb;
                    *w = ((*w + self.gyro_bias[k] + s.gyro_noise_dps * std_normal(&mut self.rng))
                        / gyro_lsb)
                        .round()
                        * gyro_lsb;
                }
                *a = a.clamp(-s.acc_range_g, s.acc_range_g);
                *w = w.clamp(-s.gyro_range_dps, s.gyro_range_dps);
            }
        }
    }
}

/// The right sensor's clock: its sample k is at right-clock time k/fs, i.e. true time
/// (k/fs − offset)/(1 + drift), linearly interpolated between the true-clock samples.
struct Resampler {
    fs: f64,
    scale: f64,
    offset_s: f64,
    /// Next right sample to emit.
    k: u64,
    /// The last true-clock sample of the previous chunk (6 channels).
    prev: Option<[f64; 6]>,
}

impl Resampler {
    fn new(fs: f64, drift_ppm: f64, offset_s: f64) -> Resampler {
        Resampler {
            fs,
            scale: 1.0 + drift_ppm * 1e-6,
            offset_s,
            k: (offset_s * fs).max(0.0).ceil() as u64,
            prev: None,
        }
    }

    /// True-clock position (in samples) of right sample k.
    fn u(&self, k: u64) -> f64 {
        (k as f64 / self.fs - self.offset_s) / self.scale * self.fs
    }

    /// Emit every right sample that falls inside `chunk` (true indices `base..base + n`, and
    /// the gap from the previous chunk); returns the index of the first sample emitted.
    fn run(&mut self, base: u64, chunk: &LegSignal, out: &mut LegSignal) -> u64 {
        let first_k = self.k;
        let n = chunk.len();
        if n == 0 {
            return first_k;
        }
        let at = |j: i64| -> [f64; 6] {
            if j < 0 {
                return self.prev.expect("a previous chunk");
            }
            let j = j as usize;
            std::array::from_fn(|c| {
                if c < 3 {
                    chunk.acc_g[c][j]
                } else {
                    chunk.gyro_dps[c - 3][j]
                }
            })
        };
        let last = (base + n as u64 - 1) as f64;
        let lo = if self.prev.is_some() {
            base as f64 - 1.0
        } else {
            base as f64
        };
        loop {
            let u = self.u(self.k);
            if u >= last {
                break;
            }
            if u < lo {
                self.k += 1;
                continue;
            }
            let j = u.floor();
            let fr = u - j;
            let jl = (j - base as f64) as i64;
            let (a, b) = (at(jl), at(jl + 1));
            for c in 0..3 {
                out.acc_g[c].push(a[c] + fr * (b[c] - a[c]));
                out.gyro_dps[c].push(a[c + 3] + fr * (b[c + 3] - a[c + 3]));
            }
            self.k += 1;
        }
        self.prev = Some(at(n as i64 - 1));
        first_k
    }
}

/// ldh's CSV (`time_s,acc_x,…,gyro_z`, `# start:` comment), written row by row with fixed
/// decimals (time 4, or 6 when the rate does not divide 10 000; acc 5; gyro 3).
struct CsvSink {
    file: AtomicFile,
    line: Vec<u8>,
    time_dec: u32,
    rows: u64,
}

impl CsvSink {
    fn create(path: &Path, params: &FreeLivingParams, _offset: f64) -> Result<CsvSink> {
        let mut file = AtomicFile::create(path)?;
        let head = format!(
            "# start: {}\n# simulated free-living recording (ldh simulate --free-living, seed {})\ntime_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n",
            params.start.iso(),
            params.seed
        );
        file.write_all(head.as_bytes()).map_err(|e| werr(path, e))?;
        let exact = (10_000.0 / params.fs_hz).fract() == 0.0;
        Ok(CsvSink {
            file,
            line: Vec::with_capacity(1 << 16),
            time_dec: if exact { 4 } else { 6 },
            rows: 0,
        })
    }

    fn write(&mut self, k0: u64, sig: &LegSignal, fs: f64) -> Result<()> {
        self.line.clear();
        for i in 0..sig.len() {
            let t = (k0 + i as u64) as f64 / fs;
            push_fixed(&mut self.line, t, self.time_dec);
            for k in 0..3 {
                self.line.push(b',');
                push_fixed(&mut self.line, sig.acc_g[k][i], 5);
            }
            for k in 0..3 {
                self.line.push(b',');
                push_fixed(&mut self.line, sig.gyro_dps[k][i], 3);
            }
            self.line.push(b'\n');
        }
        self.rows += sig.len() as u64;
        self.file
            .write_all(&self.line)
            .map_err(|e| LdhError::Write {
                path: Default::default(),
                reason: e.to_string(),
            })
    }

    fn finish(self) -> Result<()> {
        self.file.finish()
    }
}

fn werr(path: &Path, e: std::io::Error) -> LdhError {
    LdhError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    }
}

/// Append `v` with `dec` decimals (fixed point, rounded half away from zero).
pub(super) fn push_fixed(buf: &mut Vec<u8>, v: f64, dec: u32) {
    let scale = 10u64.pow(dec);
    let x = (v * scale as f64).round();
    if x < 0.0 {
        buf.push(b'-');
    }
    let a = x.abs() as u64;
    let (int, frac) = (a / scale, a % scale);
    let _ = write!(buf, "{int}.{frac:0width$}", width = dec as usize);
}
