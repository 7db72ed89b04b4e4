//! File names for per-subject outputs (reports, traces): one file per subject id, never two ids
//! on one file (issue 19: `P 1`, `P_1` and `P/1` must not share a report).
//!
//! A subject id made only of ASCII letters, digits, `-`, `_` and `.` (not leading) and at most
//! [`MAX_STEM_CHARS`] long is its own file name. Any other id is *sanitised* (each other
//! character becomes `_`, the text cut to [`MAX_STEM_CHARS`]) and then *disambiguated* with a
//! stable suffix `~` + 8 hex digits of the FNV-1a hash of the id's UTF-8 bytes. The suffix
//! depends only on the id (the same id gets the same file in every run and cohort), and `~`
//! never appears in an unchanged id, so a sanitised name can never take an unchanged id's file.
//! Windows device names (`CON`, `NUL`, `COM1` …) get the suffix too.
//!
//! [`check_unique`] is run on the whole cohort before any work: two ids whose names are equal
//! ignoring case (the same file on macOS and Windows) are refused with both ids in the message.

use crate::error::{LdhError, Result};

/// The longest file stem kept from a subject id (bytes, ASCII); longer ids are cut and suffixed.
pub const MAX_STEM_CHARS: usize = 100;

/// FNV-1a, 64 bit: a small, fixed, platform-independent hash (not for security).
fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

fn reserved(stem: &str) -> bool {
    let base = stem.split('.').next().unwrap_or("").to_ascii_uppercase();
    matches!(base.as_str(), "CON" | "PRN" | "AUX" | "NUL")
        || ((base.starts_with("COM") || base.starts_with("LPT"))
            && base.len() == 4
            && base.as_bytes()[3].is_ascii_digit())
}

/// The file stem (name without extension) of a subject's report and trace files; see the
/// module documentation for the rule. Never empty, never starts with `.`, at most
/// [`MAX_STEM_CHARS`] + 9 bytes.
pub fn file_stem(subject_id: &str) -> String {
    let mut s: String = subject_id
        .chars()
        .enumerate()
        .map(|(i, c)| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' || (c == '.' && i > 0) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        s.push('_');
    }
    if s == subject_id && s.len() <= MAX_STEM_CHARS && !reserved(&s) {
        return s;
    }
    s.truncate(MAX_STEM_CHARS); // ASCII only here, so any byte index is a char boundary
    format!(
        "{s}~{:08x}",
        (fnv1a(subject_id.as_bytes()) & 0xffff_ffff) as u32
    )
}

/// Refuse a cohort in which two subject ids would share a file name (equal ignoring case).
/// Run before any work, so nothing is overwritten and nothing is half-written.
pub fn check_unique<'a>(ids: impl IntoIterator<Item = &'a str>) -> Result<()> {
    let mut seen: std::collections::HashMap<String, &str> = std::collections::HashMap::new();
    for id in ids {
        let key = file_stem(id).to_ascii_lowercase();
        if let Some(other) = seen.insert(key, id) {
            if other == id {
                return Err(LdhError::signal(
                    "inputs",
                    format!("subject id {id:?} appears twice: rename one"),
                ));
            }
            return Err(LdhError::signal(
                "inputs",
                format!(
                    "subject ids {other:?} and {id:?} would share the report file '{}' (file names ignore case on some systems): rename one",
                    file_stem(id)
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_ids_are_their_own_names() {
        for id in ["S01", "P_1", "a-b.c", "HC_003"] {
            assert_eq!(file_stem(id), id);
        }
    }

    #[test]
    fn changed_ids_get_a_stable_distinct_suffix() {
        let a = file_stem("P 1");
        let b = file_stem("P/1");
        assert!(a.starts_with("P_1~") && b.starts_with("P_1~"), "{a} {b}");
        assert_ne!(a, b);
        assert_ne!(a, "P_1");
        // Stable: a fixed function of the id (FNV-1a of "P 1").
        assert_eq!(a, file_stem("P 1"));
        assert_eq!(a, format!("P_1~{:08x}", fnv1a(b"P 1") as u32));
        assert!(check_unique(["P 1", "P_1", "P/1"]).is_ok());
        assert!(file_stem(".hidden").starts_with("_hidden~"));
        assert!(file_stem("").starts_with("_~"));
        assert!(file_stem("S 01/../x").starts_with("S_01_.._x~"));
        assert!(file_stem("con").starts_with("con~"));
        assert!(file_stem("LPT1.txt").starts_with("LPT1.txt~"));
        assert_eq!(file_stem("CONTROL"), "CONTROL");
        let long = "x".repeat(300);
        assert_eq!(file_stem(&long).len(), MAX_STEM_CHARS + 9);
        assert_ne!(file_stem(&long), file_stem(&"x".repeat(301)));
        assert!(file_stem("Пациент 1").is_ascii());
    }

    #[test]
    fn case_and_exact_duplicates_are_refused() {
        let e = check_unique(["p1", "P1"]).unwrap_err().to_string();
        assert!(e.contains("\"p1\" and \"P1\""), "{e}");
        let e = check_unique(["S1", "S1"]).unwrap_err().to_string();
        assert!(e.contains("appears twice"), "{e}");
    }
}
