//! Streaming reader tests (issue 19): a stream read in tiny chunks gives what bytes in memory
//! give; faults past the first 64 KiB are found with their line; the sample and size limits.

use super::super::format::FormatSpec;
use super::super::reader::*;
use super::super::text::Lines;
use crate::error::LdhError;
use std::path::Path;

const HEADER: &str = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n";

/// `n` rows of a constant recording at 100 Hz (the text layer's faults come first).
fn rows(n: usize) -> String {
    let mut t = String::from(HEADER);
    for i in 0..n {
        t.push_str(&format!(
            "{}.{:02},1.000,0.010,0.020,0.5,0.6,0.7\n",
            i / 100,
            i % 100
        ));
    }
    t
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
fn a_nul_byte_past_the_first_64_kib_is_refused_with_its_line() {
    let mut text = rows(2500);
    let line = 2001;
    let start = text.match_indices('\n').nth(line - 2).unwrap().0 + 1;
    text.replace_range(start + 7..start + 8, "\0");
    assert!(start > 1 << 16);
    let e = read_recording_bytes(text.as_bytes(), Path::new("x.csv"), None, &params())
        .unwrap_err()
        .to_string();
    let want = format!(
        "x.csv:{line}: this is not a text file (byte 0x00 at offset {})",
        start + 7
    );
    assert!(e.starts_with(&want), "{e}");
}

#[test]
fn invalid_utf8_past_the_head_is_refused_with_its_line_and_offset() {
    let mut bytes = rows(2500).into_bytes();
    let start = bytes
        .iter()
        .enumerate()
        .filter(|(_, &b)| b == b'\n')
        .nth(2198)
        .unwrap()
        .0
        + 1;
    bytes[start + 2] = 0xFF;
    let e = read_recording_bytes(&bytes, Path::new("x.csv"), None, &params())
        .unwrap_err()
        .to_string();
    let want = format!(
        "x.csv:2200: the text is not valid UTF-8 (offset {})",
        start + 2
    );
    assert!(e.starts_with(&want), "{e}");
}

#[test]
fn the_size_limit_holds_for_content_longer_than_its_stated_size() {
    let text = rows(100);
    let mut lines = Lines::new(text.as_bytes(), Path::new("x.csv"), Some(0.001)).unwrap();
    let e = loop {
        match lines.next_line() {
            Ok(Some(_)) => {}
            Ok(None) => panic!("read past the limit"),
            Err(e) => break e,
        }
    };
    assert!(matches!(e, LdhError::FileTooLarge { .. }), "{e}");
}

#[test]
fn lines_after_comment_lines_keep_their_numbers_in_messages() {
    // Rows on lines 2–4, comments on 5–6, rows from line 7: row lines are stored as runs.
    let mut text = rows(3);
    text.push_str("# a\n# b\n0.03,1,0,0,0,0,0\n0.02,1,0,0,0,0,0\n");
    let f = hash_comments();
    let e = read_recording_bytes(text.as_bytes(), Path::new("x.csv"), Some(&f), &params())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("x.csv:8:1:"), "{e}");
}

#[test]
fn a_line_longer_than_the_bound_is_refused_with_its_line_without_holding_it() {
    use super::super::MAX_LINE_BYTES;
    // A row of exactly the bound (newline included) is read; one byte more is refused.
    for (extra, refused) in [(0usize, false), (1, true), (5_000_000, true)] {
        let mut text = rows(2);
        let cell = "7".repeat(MAX_LINE_BYTES - 1 + extra - "0.02,,0,0,0,0,0".len());
        text.push_str(&format!("0.02,{cell},0,0,0,0,0\n"));
        let mut lines = Lines::new(text.as_bytes(), Path::new("x.csv"), None).unwrap();
        let got = loop {
            match lines.next_line() {
                Ok(Some((4, l))) => break Ok(l.len()),
                Ok(Some(_)) => {}
                Ok(None) => panic!("line 4 not read"),
                Err(e) => break Err(e),
            }
        };
        match got {
            Ok(len) => assert!(!refused && len == MAX_LINE_BYTES - 1, "{len}"),
            Err(e) => {
                assert!(refused, "{e}");
                assert!(matches!(e, LdhError::LineTooLong { .. }), "{e}");
                assert!(e
                    .to_string()
                    .starts_with("x.csv:4: the line is longer than 65536 bytes"));
            }
        }
    }
    // Through the reader too, with a line past the first 64 KiB and without any line end.
    let text = "x".repeat(3 * MAX_LINE_BYTES);
    let e = read_recording_bytes(text.as_bytes(), Path::new("x.csv"), None, &params()).unwrap_err();
    assert!(
        e.to_string().starts_with("x.csv:1: the line is longer"),
        "{e}"
    );
}

#[test]
fn a_long_bad_cell_is_echoed_cut_with_its_length() {
    let mut text = rows(2);
    let cell = "q".repeat(50_000);
    text.push_str(&format!("0.02,{cell},0,0,0,0,0\n"));
    let e = read_recording_bytes(text.as_bytes(), Path::new("x.csv"), None, &params())
        .unwrap_err()
        .to_string();
    assert!(e.len() < 300, "{}", e.len());
    assert!(e.contains("… (50000 characters)' is not a number"), "{e}");
}

#[test]
fn files_read_whole_must_be_regular_files_within_their_limit() {
    use super::super::{read_text_limited, MAX_PARAMS_MB};
    let d = tempfile::tempdir().unwrap();
    let ok = d.path().join("p.toml");
    std::fs::write(&ok, "a = 1\n").unwrap();
    assert_eq!(
        read_text_limited(&ok, MAX_PARAMS_MB, "a parameter file").unwrap(),
        "a = 1\n"
    );
    // Larger than the limit: refused by its size, naming the kind of file.
    let e = read_text_limited(&ok, 0.000_002, "a parameter file").unwrap_err();
    assert!(matches!(e, LdhError::TextTooLarge { .. }), "{e}");
    assert!(
        e.to_string()
            .contains("a parameter file of 0.0 MB, above the limit of 0.000002 MB"),
        "{e}"
    );
    // A device and a folder: refused at once.
    for (p, what) in [(Path::new("/dev/zero"), "a device"), (d.path(), "a folder")] {
        let e = read_text_limited(p, MAX_PARAMS_MB, "a model file").unwrap_err();
        assert_eq!(e.kind(), crate::ErrorKind::Io, "{e}");
        let msg = e.to_string();
        assert!(
            msg.contains(&format!(
                "not a regular file but {what}; a model file must be a regular file"
            )),
            "{msg}"
        );
    }
    // A FIFO without a writer: refused without blocking (a blocking open would hang the test).
    let fifo = d.path().join("f.toml");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let e = read_text_limited(&fifo, MAX_PARAMS_MB, "a parameter file").unwrap_err();
        assert!(
            e.to_string()
                .contains("not a regular file but a FIFO (named pipe)"),
            "{e}"
        );
        let e = read_recording(&fifo, None, &params()).unwrap_err();
        assert!(
            e.to_string().contains("not a regular file but a FIFO"),
            "{e}"
        );
    }
}
