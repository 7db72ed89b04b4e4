//! Replays the fuzz seeds and every committed crash reproducer through the bodies of the
//! `cargo fuzz` targets (`fuzz/src/lib.rs`, compiled here as a module), on the stable toolchain: a crash found once
//! stays fixed even where nightly and libFuzzer are not available (docs/fuzzing.md).

use std::path::{Path, PathBuf};

// The fuzz crate's library, compiled here as a module; fields only the fuzz targets read are
// unread here.
#[path = "../../fuzz/src/lib.rs"]
#[allow(dead_code)]
mod fuzz_targets;
use ldh_core::io::read_recording_bytes;

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The files of `fuzz/<kind>/<target>`, sorted (none when the folder does not exist).
fn inputs(kind: &str, target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = fuzz_dir().join(kind).join(target);
    let mut files: Vec<PathBuf> = match std::fs::read_dir(&dir) {
        Ok(rd) => rd
            .map(|e| e.expect("readable folder").path())
            .filter(|p| p.is_file() && p.file_name().is_some_and(|n| n != ".gitkeep"))
            .collect(),
        Err(_) => Vec::new(),
    };
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let b = std::fs::read(&p).expect("readable file");
            (p, b)
        })
        .collect()
}

/// Run `f` on each input, naming the file of any panic.
fn replay(kind: &str, target: &str, f: fn(&[u8])) -> usize {
    let files = inputs(kind, target);
    for (path, bytes) in &files {
        if std::panic::catch_unwind(|| f(bytes)).is_err() {
            panic!("fuzz input {} panics", path.display());
        }
    }
    files.len()
}

#[test]
fn read_csv_seeds_and_regressions() {
    assert!(replay("seeds", "read_csv", fuzz_targets::read_csv) >= 5);
    replay("regressions", "read_csv", fuzz_targets::read_csv);
}

#[test]
fn model_file_seeds_and_regressions() {
    assert!(replay("seeds", "model_file", fuzz_targets::model_file) >= 5);
    replay("regressions", "model_file", fuzz_targets::model_file);
}

/// The model seeds are models `ldh train` wrote (rf, svm, mlp): they load and predict, so the
/// fuzzer starts from inputs that reach the shape checks and the classifiers.
#[test]
fn model_seeds_load() {
    let mut n = 0;
    for (path, bytes) in inputs("seeds", "model_file") {
        if path.extension().is_some_and(|e| e == "json") && bytes.len() > 1000 {
            let text = String::from_utf8(bytes).unwrap();
            let m = ldh_core::ml::ModelFile::from_json(&text, "seed");
            assert!(m.is_ok(), "{}: {}", path.display(), m.unwrap_err());
            n += 1;
        }
    }
    assert_eq!(n, 3, "one trained model per classifier");
}

#[test]
fn pipeline_seeds_and_regressions() {
    assert!(replay("seeds", "pipeline", fuzz_targets::pipeline) >= 5);
    replay("regressions", "pipeline", fuzz_targets::pipeline);
}

/// The realistic CSV seeds are read by the format their length selects, so the fuzzer starts
/// from inputs that reach the whole reader.
#[test]
fn csv_seeds_are_readable_recordings() {
    let formats = fuzz_targets::read_formats();
    let params = ldh_core::io::ReadParams::default().check().unwrap();
    let mut n = 0;
    for (path, bytes) in inputs("seeds", "read_csv") {
        if bytes.len() < 1000 {
            continue;
        }
        let f = &formats[bytes.len() % formats.len()];
        let r = read_recording_bytes(&bytes, &path, Some(f), &params);
        assert!(r.is_ok(), "{}: {}", path.display(), r.unwrap_err());
        n += 1;
    }
    assert!(n >= formats.len(), "one realistic seed per format");
}

/// The gait-like pipeline seeds reach strides.
#[test]
fn pipeline_seeds_reach_strides() {
    for (path, bytes) in inputs("seeds", "pipeline") {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name.contains("hand-built") || name.starts_with("raw") {
            continue;
        }
        let case = fuzz_targets::decode_pipeline(&bytes).expect("a valid recording");
        let r = ldh_core::pipeline::Analysis::new(case.params.check().unwrap()).leg(
            &case.recording,
            case.side,
            case.sensor_height_m,
        );
        match r {
            Ok(a) => {
                let leg = a.leg;
                assert!(!leg.strides.is_empty(), "{name}: no strides");
            }
            Err(e) => panic!("{name}: {e}"),
        }
    }
}

/// Crash 1 (pipeline target): a recording claiming ~1e74 Hz or ~1e257 Hz made sci-rs's
/// Butterworth design panic (`assertion failed: p.len() == z.len()` in zpk2sos). Now the
/// preprocessing parameters are refused with a message naming the cut-off and the rate.
#[test]
fn regression_butterworth_huge_rate() {
    for name in ["butterworth-huge-rate-raw", "butterworth-huge-rate-gait"] {
        let bytes = std::fs::read(fuzz_dir().join("regressions/pipeline").join(name)).unwrap();
        let case = fuzz_targets::decode_pipeline(&bytes).expect("decodes");
        assert!(
            case.recording.fs_hz > 1e70,
            "{name}: {}",
            case.recording.fs_hz
        );
        let e = case
            .params
            .check()
            .and_then(|v| {
                ldh_core::pipeline::Analysis::new(v).leg(
                    &case.recording,
                    case.side,
                    case.sensor_height_m,
                )
            })
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("cutoff_hz") && e.contains("Nyquist"),
            "{name}: {e}"
        );
    }
}

/// Crash 2 (read_csv target, found by review of what the fuzzer had not reached): an ISO 8601
/// timestamp with a 17-digit year overflowed the day count (a panic with overflow checks,
/// a silently wrong time without). Now the cell is refused as not a timestamp.
#[test]
fn regression_iso_huge_year() {
    let bytes = std::fs::read(fuzz_dir().join("regressions/read_csv/iso-huge-year")).unwrap();
    let formats = fuzz_targets::read_formats();
    let f = &formats[bytes.len() % formats.len()];
    assert_eq!(f.name, "fuzz-iso");
    let params = ldh_core::io::ReadParams::default().check().unwrap();
    let e = read_recording_bytes(&bytes, Path::new("iso-huge-year"), Some(f), &params)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("iso-huge-year:2:1") && e.contains("ISO 8601"),
        "{e}"
    );
}
