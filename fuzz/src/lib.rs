//! The bodies of the `cargo fuzz` targets (`fuzz_targets/*.rs`, see docs/fuzzing.md): the
//! library of the `ldh-fuzz` package. They call the public API of `ldh-core` and `ldh-sim` only.
//!
//! The stable test `tests/tests/fuzz_replay.rs` compiles this same file (`#[path]`) and replays
//! the committed seeds and crash regressions through it, so a crash found once stays fixed where
//! nightly and libFuzzer are not available. Each body takes raw bytes, must never panic, and
//! checks what it can of the result: an error must carry a message, a recording must satisfy
//! [`Recording::validate`].

use std::path::Path;
use std::sync::OnceLock;

use ldh_core::attitude::AttitudeModel;
use ldh_core::error::{LdhError, Result};
use ldh_core::events::EventDetector;
use ldh_core::io::{read_recording_bytes, FormatSpec, GapPolicy, ReadParams, ReadReport};
use ldh_core::pipeline::{Analysis, AnalysisParams};
use ldh_core::recording::{Recording, Side};
use ldh_sim::CohortParams;

/// Formats the CSV target passes explicitly: the built-in ones (whose header checks differ from
/// detection) and three that reach what detection never picks: ISO 8601 time with decimal
/// commas, milliseconds with a sensor range and an axis map, microseconds with integer counts.
const EXTRA_FORMATS: [&str; 3] = [
    r##"
name = "fuzz-iso"
delimiter = ";"
decimal = ","
comment_prefixes = ["#", "//"]
[time]
column = "time"
unit = "iso8601"
[acc]
columns = ["acc_x", "acc_y", "acc_z"]
unit = "g"
[gyro]
columns = ["gyro_x", "gyro_y", "gyro_z"]
unit = "deg/s"
"##,
    r##"
name = "fuzz-ms"
delimiter = "\t"
skip_rows_after_header = 1
[time]
column = "t_ms"
unit = "ms"
[acc]
columns = ["ax", "ay", "az"]
unit = "m/s2"
range = 78.4
[gyro]
columns = ["gx", "gy", "gz"]
unit = "rad/s"
range = 17.4
[axes]
map = ["-y", "+x", "+z"]
"##,
    r##"
name = "fuzz-us"
delimiter = ","
[time]
column = "t_us"
unit = "us"
[acc]
columns = ["ax", "ay", "az"]
unit = "g"
scale = 0.00048828125
[gyro]
columns = ["gx", "gy", "gz"]
unit = "deg/s"
scale = 0.06103515625
range = 2000.0
"##,
];

struct ReadSetup {
    formats: Vec<FormatSpec>,
    default_params: ldh_core::io::ValidReadParams,
    variants: Vec<ldh_core::io::ValidReadParams>,
}

/// The built-in formats [`read_csv`] passes explicitly, in this order.
const FUZZ_BUILTINS: [&str; 4] = ["ldh", "xsens-mtmanager", "shimmer-consensys", "raw-counts"];

fn read_setup() -> &'static ReadSetup {
    static SETUP: OnceLock<ReadSetup> = OnceLock::new();
    SETUP.get_or_init(|| {
        // The built-ins the committed seeds and regressions were made for, by name: an input's
        // length picks its format, so adding a built-in must not move them (the HuGaDB maps
        // have their own tests).
        let mut formats: Vec<FormatSpec> = FormatSpec::builtins()
            .into_iter()
            .filter(|f| FUZZ_BUILTINS.contains(&f.name.as_str()))
            .collect();
        for (i, t) in EXTRA_FORMATS.iter().enumerate() {
            formats.push(
                FormatSpec::from_toml_str(t, &format!("fuzz format {i}"))
                    .expect("the fuzz formats are valid"),
            );
        }
        let p = ReadParams::default();
        let variants = [
            p.clone(),
            p.clone().gap_policy(GapPolicy::Reject),
            p.clone().check_units(false),
            p.clone().min_duration_s(0.0).max_gap_s(1e6),
        ]
        .iter()
        .map(|p| p.check().expect("the fuzz read parameters are valid"))
        .collect();
        ReadSetup {
            formats,
            default_params: p.check().expect("defaults are valid"),
            variants,
        }
    })
}

/// The formats [`read_csv`] may pass explicitly (built-ins, then the fuzz-only ones).
pub fn read_formats() -> &'static [FormatSpec] {
    &read_setup().formats
}

/// Target `read_csv`: arbitrary bytes through the CSV reader, once with format detection and
/// default parameters, once with an explicit format and reader parameters chosen by the
/// input's length (so every input length exercises one combination deterministically).
pub fn read_csv(data: &[u8]) {
    let s = read_setup();
    let path = Path::new("<fuzz>");
    check_read(read_recording_bytes(data, path, None, &s.default_params));
    let f = &s.formats[data.len() % s.formats.len()];
    let p = &s.variants[(data.len() / s.formats.len()) % s.variants.len()];
    check_read(read_recording_bytes(data, path, Some(f), p));
}

fn check_read(r: Result<(Recording, ReadReport)>) {
    match r {
        Ok((rec, report)) => {
            if let Err(e) = rec.validate() {
                panic!("the reader returned a recording that breaks its invariants: {e}");
            }
            assert_eq!(report.samples, rec.len(), "report and recording disagree");
            assert!(report.fs_hz == rec.fs_hz, "report and recording disagree");
        }
        Err(e) => check_error(&e),
    }
}

fn check_error(e: &LdhError) {
    let msg = e.to_string();
    assert!(!msg.trim().is_empty(), "an error without a message: {e:?}");
    let _ = e.kind();
}

/// Reads the fuzzer's bytes as a stream of numbers; past the end it yields zeros.
struct Stream<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Stream<'a> {
    fn u8(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }
    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    fn f64(&mut self) -> f64 {
        let mut b = [0u8; 8];
        for x in &mut b {
            *x = self.u8();
        }
        f64::from_le_bytes(b)
    }
    /// The bytes not read yet.
    fn rest(&self) -> &'a [u8] {
        self.data.get(self.pos..).unwrap_or(&[])
    }
}

/// Gait-like bases for the pipeline target: simulated legs (100 Hz, walk, turn, walk back).
fn bases() -> &'static [Recording] {
    static BASES: OnceLock<Vec<Recording>> = OnceLock::new();
    BASES.get_or_init(|| {
        let c = CohortParams {
            healthy: 1,
            ldh: 1,
            duration_s: 40.0,
            ..CohortParams::default()
        };
        (0..c.len())
            .flat_map(|i| {
                let s = c.simulate(i).expect("the simulator works");
                [s.left.recording, s.right.recording]
            })
            .collect()
    })
}

/// Values the pipeline target injects at chosen samples.
const SPECIALS: [f64; 12] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
    -1e300,
    0.0,
    -0.0,
    f64::MIN_POSITIVE,
    f64::EPSILON,
    16.0,
    -2000.0,
    1e9,
];

/// Rates the pipeline target picks from (most inputs); a selector ≥ 240 reads any f64 instead.
const RATES: [f64; 14] = [
    100.0, 50.0, 200.0, 20.0, 64.0, 128.0, 1000.0, 25.0, 10.0, 2000.0, 1.0, 333.3, 30.0, 0.5,
];

/// Longest recording the pipeline target builds, samples.
pub const PIPELINE_MAX_SAMPLES: usize = 4000;

/// What [`pipeline`] decoded from its bytes (for the replay test's messages).
#[derive(Debug, Clone)]
pub struct PipelineCase {
    /// The recording as built (possibly breaking its invariants when `hand_built`).
    pub recording: Recording,
    /// Built with a struct literal instead of [`Recording::new`].
    pub hand_built: bool,
    /// The analysis parameters.
    pub params: AnalysisParams,
    /// The leg.
    pub side: Side,
    /// The sensor height passed to [`Analysis::leg`].
    pub sensor_height_m: Option<f64>,
}

/// Decode the pipeline target's bytes into a case (`None` when [`Recording::new`] refuses the
/// channels, which is a correct outcome).
///
/// Layout: a flags byte (STA on, side, attitude model, two bits of event detector, hand-built,
/// sensor height given, raw f64 samples), a rate selector (a table, or any f64 when ≥ 240),
/// a `u16` length (2 + value mod [`PIPELINE_MAX_SAMPLES`]), then either raw little-endian f64
/// samples read cyclically (raw mode) or a gait-like mode: a simulated leg chosen and offset by
/// the next bytes, per-channel gains, up to 7 injected special values and an i8 perturbation
/// per value read cyclically from the rest. Hand-built cases also take `t0_s` and a length
/// change of one channel or of the saturation mask.
pub fn decode_pipeline(data: &[u8]) -> Option<PipelineCase> {
    let mut s = Stream { data, pos: 0 };
    let f = Flags::from_byte(s.u8());
    let sel = s.u8();
    let fs_hz = if sel >= 240 {
        s.f64()
    } else {
        RATES[usize::from(sel) % RATES.len()]
    };
    let n = 2 + usize::from(s.u16()) % PIPELINE_MAX_SAMPLES;
    let sensor_height_m = if f.height_given {
        Some(match s.u8() {
            0 => s.f64(),
            b => f64::from(b) / 1000.0,
        })
    } else {
        None
    };
    let (t0_s, tweak) = if f.hand_built {
        (s.f64(), (s.u8(), s.u8() as i8))
    } else {
        (0.0, (0, 0))
    };
    let signals = if f.raw_mode {
        raw_signals(&mut s, n)
    } else {
        gait_like_signals(&mut s, n)
    };
    let recording = if f.hand_built {
        hand_built_recording(signals, tweak, f.side, fs_hz, t0_s)
    } else {
        let Signals {
            acc,
            gyro,
            saturated,
        } = signals;
        match Recording::new(fs_hz, acc, gyro, saturated) {
            Ok(r) => r,
            Err(e) => {
                check_error(&e);
                return None;
            }
        }
    };
    let mut params = AnalysisParams {
        compute_sta: f.compute_sta,
        ..AnalysisParams::default()
    };
    params.attitude.model = f.model;
    params.events.detector = f.detector;
    Some(PipelineCase {
        recording,
        hand_built: f.hand_built,
        params,
        side: f.side,
        sensor_height_m,
    })
}

/// The flags byte of the pipeline target.
struct Flags {
    compute_sta: bool,
    side: Side,
    model: AttitudeModel,
    detector: EventDetector,
    hand_built: bool,
    height_given: bool,
    raw_mode: bool,
}

impl Flags {
    fn from_byte(flags: u8) -> Flags {
        Flags {
            compute_sta: flags & 1 != 0,
            side: if flags & 2 != 0 {
                Side::Right
            } else {
                Side::Left
            },
            model: if flags & 4 != 0 {
                AttitudeModel::Acc
            } else {
                AttitudeModel::Fusion
            },
            detector: [
                EventDetector::GyroBracket,
                EventDetector::GyroZeroCrossing,
                EventDetector::Salarian,
                EventDetector::PitchPeaks,
            ][usize::from((flags >> 3) & 3)],
            hand_built: flags & 0x20 != 0,
            height_given: flags & 0x40 != 0,
            raw_mode: flags & 0x80 != 0,
        }
    }
}

/// Decoded channels: acceleration, angular velocity and the saturation mask (empty: none).
struct Signals {
    acc: [Vec<f64>; 3],
    gyro: [Vec<f64>; 3],
    saturated: Vec<bool>,
}

/// Raw mode: `n` samples of little-endian f64 values read cyclically from the rest.
fn raw_signals(s: &mut Stream, n: usize) -> Signals {
    let mut acc: [Vec<f64>; 3] = Default::default();
    let mut gyro: [Vec<f64>; 3] = Default::default();
    let rest = s.rest();
    let values: Vec<f64> = rest
        .chunks(8)
        .map(|c| {
            let mut b = [0u8; 8];
            b[..c.len()].copy_from_slice(c);
            f64::from_le_bytes(b)
        })
        .collect();
    let value = |k: usize| {
        if values.is_empty() {
            0.0
        } else {
            values[k % values.len()]
        }
    };
    for i in 0..n {
        for c in 0..3 {
            acc[c].push(value(6 * i + c));
            gyro[c].push(value(6 * i + 3 + c));
        }
    }
    Signals {
        acc,
        gyro,
        saturated: Vec::new(),
    }
}

/// Gait-like mode: a simulated leg chosen and offset by the next bytes, per-channel gains, up to
/// 7 injected special values, an i8 perturbation per value and maybe a saturation mask.
fn gait_like_signals(s: &mut Stream, n: usize) -> Signals {
    let mut acc: [Vec<f64>; 3] = Default::default();
    let mut gyro: [Vec<f64>; 3] = Default::default();
    let mut saturated = Vec::new();
    let bases = bases();
    let base = &bases[usize::from(s.u8()) % bases.len()];
    let offset = usize::from(s.u16()) % base.len();
    let gains: [f64; 6] = std::array::from_fn(|_| match s.u8() {
        0 => 0.0,
        255 => -1.0,
        b => f64::from(b) / 128.0,
    });
    let n_special = usize::from(s.u8() & 7);
    let specials: Vec<(usize, usize, f64)> = (0..n_special)
        .map(|_| {
            let at = usize::from(s.u16()) % n;
            let ch = usize::from(s.u8()) % 6;
            (at, ch, SPECIALS[usize::from(s.u8()) % SPECIALS.len()])
        })
        .collect();
    let sat_byte = s.u8();
    let rest = s.rest();
    let noise = |k: usize| -> f64 {
        if rest.is_empty() {
            0.0
        } else {
            f64::from(rest[k % rest.len()] as i8)
        }
    };
    for i in 0..n {
        let j = (offset + i) % base.len();
        for c in 0..3 {
            acc[c].push(base.acc_g[c][j] * gains[c] + 0.01 * noise(6 * i + c));
            gyro[c].push(base.gyro_dps[c][j] * gains[3 + c] + 2.0 * noise(6 * i + 3 + c));
        }
    }
    for (at, ch, v) in specials {
        if ch < 3 {
            acc[ch][at] = v;
        } else {
            gyro[ch - 3][at] = v;
        }
    }
    if sat_byte != 0 {
        saturated = (0..n)
            .map(|i| !rest.is_empty() && rest[(6 * i + 4) % rest.len()] == sat_byte)
            .collect();
    }
    Signals {
        acc,
        gyro,
        saturated,
    }
}

/// A recording built with a struct literal, one channel's (or the mask's) length changed by
/// `tweak` = (which, delta), so that the pipeline meets broken invariants.
fn hand_built_recording(
    signals: Signals,
    tweak: (u8, i8),
    side: Side,
    fs_hz: f64,
    t0_s: f64,
) -> Recording {
    let Signals {
        mut acc,
        mut gyro,
        mut saturated,
    } = signals;
    if saturated.is_empty() {
        saturated = vec![false; acc[0].len()];
    }
    let (which, delta) = tweak;
    if delta != 0 {
        let resize = |v: &mut Vec<f64>| {
            let len = v.len().saturating_add_signed(isize::from(delta));
            v.resize(len, 0.5);
        };
        match which % 7 {
            c @ 0..=2 => resize(&mut acc[usize::from(c)]),
            c @ 3..=5 => resize(&mut gyro[usize::from(c) - 3]),
            _ => {
                let len = saturated.len().saturating_add_signed(isize::from(delta));
                saturated.resize(len, true);
            }
        }
    }
    Recording {
        source: None,
        side: Some(side),
        fs_hz,
        t0_s,
        acc_g: acc,
        gyro_dps: gyro,
        saturated,
        acc_saturated: Vec::new(),
        gyro_saturated: Vec::new(),
        recorded_at: None,
    }
}

/// Target `pipeline`: a recording decoded from arbitrary bytes ([`decode_pipeline`]) through
/// [`Analysis::leg`] (parameters the guard refuses are an error too). A hand-built recording
/// that breaks the invariants must be refused.
pub fn pipeline(data: &[u8]) {
    let Some(case) = decode_pipeline(data) else {
        return;
    };
    let valid = case.recording.validate().is_ok();
    let analysed = case
        .params
        .check()
        .and_then(|v| Analysis::new(v).leg(&case.recording, case.side, case.sensor_height_m));
    match analysed {
        Ok(a) => {
            let (leg, hs) = (a.leg, a.lent.hs_s);
            assert!(valid, "Analysis::leg accepted an invalid recording");
            assert_eq!(hs, leg.events.hs_s, "lent heel strikes differ");
            let _ = serde_json::to_string(&leg).expect("a leg result serialises");
        }
        Err(e) => check_error(&e),
    }
}

/// Target `model_file`: arbitrary bytes as a model file (`ldh predict --model`), twice: as they
/// are, and re-signed (the bytes parsed as JSON, the correct checksum written in) so that
/// mutations get past the checksum to the schema and shape checks of
/// [`ldh_core::ml::model_check::validate`]. A refusal must carry a message; an accepted model must
/// predict (or refuse with a message) three rows of its features without panicking, and its
/// labels must be classes it has.
pub fn model_file(data: &[u8]) {
    use ldh_core::ml::ModelFile;
    let text = String::from_utf8_lossy(data);
    check_model(ModelFile::from_json(&text, "fuzz"));
    let Ok(mut v) = serde_json::from_str::<serde_json::Value>(&text) else {
        return;
    };
    let sum = ldh_core::ml::model_check::checksum(&v);
    if let serde_json::Value::Object(m) = &mut v {
        m.insert("checksum".into(), serde_json::Value::String(sum));
    }
    let signed = serde_json::to_string(&v).expect("a JSON value serialises");
    check_model(ModelFile::from_json(&signed, "fuzz"));
}

/// The checks of [`model_file`] on one parse.
fn check_model(m: std::result::Result<ldh_core::ml::ModelFile, ldh_core::ml::ModelError>) {
    let m = match m {
        Ok(m) => m,
        Err(e) => {
            assert!(!e.to_string().trim().is_empty(), "empty model error");
            return;
        }
    };
    let n = m.feature_names.len();
    let x = ndarray::Array2::from_shape_fn((3, n), |(i, j)| [0.0, 1.0, 1e3][i] * (j + 1) as f64);
    match m.predict(&x) {
        Ok((labels, proba)) => {
            assert_eq!(labels.len(), 3, "one label per row");
            assert!(
                labels.iter().all(|&l| l < m.class_names.len()),
                "a label outside the model's classes"
            );
            if let Some(p) = proba {
                assert_eq!(p.dim(), (3, m.class_names.len()), "probability shape");
            }
        }
        Err(e) => check_error(&e),
    }
}
