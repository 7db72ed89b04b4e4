//! Streaming reader tests (issue 19): a stream read in tiny chunks gives what bytes in memory
//! give; faults past the first 64 KiB are found with their line; the sample and size limits.

use ldh_core::error::LdhError;
use ldh_core::io::format::FormatSpec;
use ldh_core::io::reader::*;
use ldh_core::io::writer::{recording_to_csv, WriteOptions};
use ldh_sim::CohortParams;
use std::io::BufReader;
use std::path::Path;

/// A simulated 12 s walk at 100 Hz as the `ldh` format's CSV (1201 rows).
fn walking_csv() -> String {
    let c = CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 12.0,
        fs_hz: 100.0,
        turn: false,
        ..CohortParams::default()
    };
    let rec = c.simulate(0).unwrap().left.recording;
    recording_to_csv(&rec, &FormatSpec::default(), &WriteOptions::default()).unwrap()
}

fn params() -> ValidReadParams {
    ReadParams::default().check().unwrap()
}

fn hash_comments() -> FormatSpec {
    FormatSpec {
        comment_prefixes: vec!["#".into()],
        ..FormatSpec::default()
    }
}

#[test]
fn a_stream_read_in_tiny_chunks_equals_the_bytes_in_memory() {
    // A comment line between rows, CRLF line ends and a BOM exercise the line layer.
    let text = walking_csv().replacen("\n1.00", "\n# a note\n1.00", 1);
    let text = format!("\u{feff}{}", text.replace('\n', "\r\n"));
    let f = hash_comments();
    let path = Path::new("x.csv");
    let (a, ra) = read_recording_bytes(text.as_bytes(), path, Some(&f), &params()).unwrap();
    let chunks = BufReader::with_capacity(7, text.as_bytes());
    let (b, rb) = read_recording_from(chunks, path, Some(&f), &params()).unwrap();
    assert_eq!(a.acc_g, b.acc_g);
    assert_eq!(a.gyro_dps, b.gyro_dps);
    assert_eq!(ra, rb);
    assert!(ra.bom && ra.rows == 1201 && ra.samples == 1201, "{ra:?}");
}

#[test]
fn a_character_cut_by_the_end_of_the_first_64_kib_is_read() {
    // 'é' (2 bytes) at offsets 65535–65536: the head check ends inside it (two comment
    // lines: one line may not hold 64 KiB).
    let text = format!(
        "#{}\n#{}é\n{}",
        "a".repeat(30000),
        "a".repeat(65534 - 30002),
        walking_csv()
    );
    assert_eq!(text.find('é'), Some(65535));
    let f = hash_comments();
    let (_, r) =
        read_recording_bytes(text.as_bytes(), Path::new("x.csv"), Some(&f), &params()).unwrap();
    assert_eq!((r.header_line, r.samples), (3, 1201));
}

#[test]
fn more_rows_than_max_samples_are_refused_with_the_row_count() {
    let text = walking_csv() + "# the end\n\n";
    let p = ReadParams {
        max_samples: 500,
        ..ReadParams::default()
    }
    .check()
    .unwrap();
    let f = hash_comments();
    let e = read_recording_bytes(text.as_bytes(), Path::new("x.csv"), Some(&f), &p).unwrap_err();
    assert!(
        matches!(
            e,
            LdhError::TooManySamples {
                rows: 1201,
                limit: 500,
                ..
            }
        ),
        "{e}"
    );
    assert!(e
        .to_string()
        .starts_with("x.csv: 1201 data rows, above the limit of 500 samples per recording"));
    let p = ReadParams {
        max_samples: 1201,
        ..ReadParams::default()
    };
    assert!(read_recording_bytes(
        text.as_bytes(),
        Path::new("x.csv"),
        Some(&f),
        &p.check().unwrap()
    )
    .is_ok());
    let zero = ReadParams {
        max_samples: 0,
        ..ReadParams::default()
    };
    assert!(zero.check().is_err());
}
