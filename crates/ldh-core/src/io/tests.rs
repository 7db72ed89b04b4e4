//! Reader tests: every supported variation reads back what was written, and every bad input
//! gives an error that names the file and the problem (and line and column where there is one).

mod columns;
mod start;
mod stream;
mod units;

use super::format::*;
use super::reader::*;
use super::writer::*;
use crate::error::{ErrorKind, LdhError};
use crate::recording::Recording;
use std::path::{Path, PathBuf};

struct Tmp {
    dir: tempfile::TempDir,
}

impl Tmp {
    fn new() -> Tmp {
        Tmp {
            dir: tempfile::tempdir().unwrap(),
        }
    }
    fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let p = self.dir.path().join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }
}

fn params() -> ValidReadParams {
    ReadParams::default().check().unwrap()
}

fn read(path: &Path, spec: Option<&FormatSpec>) -> crate::Result<(Recording, ReadReport)> {
    read_recording(path, spec, &params())
}

fn err_of(path: &Path, spec: Option<&FormatSpec>) -> String {
    let e = read(path, spec).expect_err("should fail");
    let msg = e.to_string();
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    assert!(msg.contains(&name), "message does not name the file: {msg}");
    msg
}

#[test]
fn shipped_format_files_parse_and_describe_their_units() {
    for name in BUILTIN_FORMATS {
        let spec = FormatSpec::builtin(name).unwrap();
        assert_eq!(spec.name, name);
        assert!(!spec.description.is_empty());
        let round = FormatSpec::from_toml_str(&spec.to_toml(), name).unwrap();
        assert_eq!(round, spec);
    }
}

#[test]
fn files_that_cannot_be_opened() {
    let t = Tmp::new();
    let missing = t.dir.path().join("nope.csv");
    let e = read(&missing, None).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::NotFound);
    assert!(e.to_string().contains("nope.csv"));
    let e = read(t.dir.path(), None).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Io);
    assert!(matches!(e, LdhError::Io { .. }));
}

#[test]
fn format_files_with_mistakes_are_refused() {
    let e = FormatSpec::from_toml_str(
        "name = \"x\"\n[acc]\ncolumns=[\"a\",\"b\",\"c\"]\nunit=\"g\"\n",
        "x.toml",
    )
    .unwrap_err();
    assert!(e.to_string().contains("x.toml"), "{e}");
    let mut s = FormatSpec::default();
    s.time = TimeSpec {
        column: None,
        unit: TimeUnit::None,
        rate_hz: None,
        counter_wrap: None,
    };
    assert!(s.validate().unwrap_err().to_string().contains("rate_hz"));
    let text = FormatSpec::default()
        .to_toml()
        .replace("unit = \"g\"", "unit = \"furlongs\"");
    assert!(FormatSpec::from_toml_str(&text, "f.toml").is_err());
}

#[test]
fn iso8601_parser_and_formatter_agree() {
    for t in [
        0.0,
        1_709_288_102.25,
        951_782_400.5, /* 2000-02-29 */
        4_102_444_799.999,
    ] {
        let s = format_iso8601(t);
        let back = parse_iso8601(&s).unwrap();
        assert!((back - t).abs() < 1e-3, "{s}: {back} vs {t}");
    }
    assert_eq!(
        parse_iso8601("2024-03-01 10:15:02.250Z"),
        Some(1_709_288_102.25)
    );
    assert!(parse_iso8601("2024-13-01T00:00:00").is_none());
    assert!(parse_iso8601("yesterday").is_none());
    // A year of more than four digits overflowed the day count (a panic with overflow checks).
    assert!(parse_iso8601("99999999999999999-01-01T00:00:00").is_none());
    assert!(parse_iso8601("10000-01-01T00:00:00").is_none());
    assert!(parse_iso8601("9999-12-31T23:59:59").is_some());
}

#[test]
fn utf16_is_named_with_or_without_a_byte_order_mark() {
    let t = Tmp::new();
    let text = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n0.00,1,0,0,0,0,0\n";
    let le: Vec<u8> = text.encode_utf16().flat_map(|u| u.to_le_bytes()).collect();
    let be: Vec<u8> = text.encode_utf16().flat_map(|u| u.to_be_bytes()).collect();
    for (name, bytes, order) in [
        ("le.csv", le.clone(), "little-endian"),
        ("be.csv", be.clone(), "big-endian"),
        (
            "bom.csv",
            [&[0xFF, 0xFE][..], &le].concat(),
            "little-endian",
        ),
    ] {
        let p = t.write(name, bytes);
        let m = err_of(&p, None);
        assert!(
            m.contains(&format!(
                "the text is UTF-16 ({order}), not valid UTF-8; re-export the file as UTF-8"
            )),
            "{m}"
        );
    }
    // A binary file with zero bytes is still a binary file.
    let p = t.write("bin.csv", [0x89, b'P', b'N', b'G', 0, 0, 0, 13, 1, 2]);
    assert!(err_of(&p, None).contains("not a text file"));
}

#[test]
fn a_buffer_that_cannot_be_had_is_the_files_error() {
    let mut v: Vec<f64> = Vec::new();
    let e = reserve(&mut v, usize::MAX / 16, Path::new("huge.csv")).unwrap_err();
    assert!(matches!(e, LdhError::OutOfMemory { .. }), "{e:?}");
    assert!(
        e.to_string()
            .starts_with("huge.csv: not enough memory to read it"),
        "{e}"
    );
    assert!(reserve(&mut v, 1000, Path::new("small.csv")).is_ok());
    assert!(v.capacity() >= 1000);
}
