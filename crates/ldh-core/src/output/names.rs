//! File names for per-subject outputs (reports, traces): one file per subject (report) and per
//! subject and trial (trace), never two on one file (issues 19 and 37: `P 1`, `P_1` and `P/1`
//! must not share a report; subject `P1__trial_2` must not share a trace with subject `P1`,
//! trial `2`).
//!
//! The name is an injective function of the id (of the pair for traces), built so that no two
//! ids can reach the same file:
//!
//! * A **plain** id — ASCII letters, digits, `-`, `_` and `.` (not leading), at most
//!   [`MAX_STEM_CHARS`] bytes, not a Windows device name — is its own name (`H01` → `H01`).
//! * Any other id is **percent-encoded**: every byte other than an ASCII letter, digit, `-` or
//!   `_` becomes `%XX` (uppercase hex); `.` and `%` included, and the first letter of a Windows
//!   device name (`CON` → `%43ON`). An encoded id always holds a `%` or is longer than any plain
//!   id, so it never takes a plain id's name, and decoding gives the id back. The empty id is
//!   `%`.
//! * A trial's trace is `<subject>~trial-<trial>`, both parts named as above. `~` is never in
//!   a named id (it is encoded as `%7E`), so the first `~` tells subject and trial apart.
//! * A name longer than [`MAX_NAME_BYTES`] is cut to [`CUT_BYTES`] (never inside a `%XX`) and
//!   ends in `=` and 16 hex digits of the FNV-1a 64 hash of the ids; `=` is never in an uncut
//!   name. Only these names can meet (a hash collision), and [`check_unique_keys`] refuses them.
//!
//! Names are ASCII, never empty, never start with `.`, and hold no `/`, `\` or `..` component.
//! [`check_unique_keys`] is run on the whole cohort before any work: two ids whose names are
//! equal ignoring case (the same file on macOS and Windows) are refused with both ids named.

use crate::error::{LdhError, Result};
use std::fmt::Write;

/// The longest subject id that is its own file name (bytes, ASCII).
pub const MAX_STEM_CHARS: usize = 100;

/// The longest name kept whole (bytes); longer names are cut and hashed (a file name stays
/// below the 255 bytes every file system allows, extension included).
pub const MAX_NAME_BYTES: usize = 160;

/// Where a name longer than [`MAX_NAME_BYTES`] is cut (bytes) before its hash suffix.
pub const CUT_BYTES: usize = 128;

/// What joins a subject's name and a trial's name in a trace file name.
pub const TRIAL_SEPARATOR: &str = "~trial-";

/// FNV-1a, 64 bit: a small, fixed, platform-independent hash (not for security).
pub(crate) fn fnv1a(bytes: &[u8]) -> u64 {
    fnv1a_from(0xcbf2_9ce4_8422_2325, bytes)
}

/// FNV-1a, 64 bit, continued from `h` (a running hash over pieces).
pub(crate) fn fnv1a_from(mut h: u64, bytes: &[u8]) -> u64 {
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

/// Whether an id is its own file name (see the module documentation).
fn plain(id: &str) -> bool {
    !id.is_empty()
        && id.len() <= MAX_STEM_CHARS
        && !id.starts_with('.')
        && id
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_' || b == b'.')
        && !reserved(id)
}

/// The name of one id: itself when plain, else percent-encoded.
fn encode(id: &str) -> String {
    if plain(id) {
        return id.to_string();
    }
    if id.is_empty() {
        return "%".into();
    }
    let device = reserved(id);
    let mut out = String::with_capacity(id.len() * 3);
    for (i, b) in id.bytes().enumerate() {
        let keep = b.is_ascii_alphanumeric() || b == b'-' || b == b'_';
        if keep && !(i == 0 && device) {
            out.push(b as char);
        } else {
            let _ = write!(out, "%{b:02X}");
        }
    }
    out
}

/// A name cut to [`CUT_BYTES`] (never inside a `%XX`) with the hash of the ids.
fn cut(name: &str, subject_id: &str, trial_id: Option<&str>) -> String {
    let mut at = CUT_BYTES.min(name.len());
    // `name` is ASCII; back off when a `%` sits in the last two bytes kept.
    if let Some(p) = name[at.saturating_sub(2)..at].find('%') {
        at = at - 2 + p;
    }
    let mut h = fnv1a(subject_id.as_bytes());
    if let Some(t) = trial_id {
        // 0xFF never occurs in UTF-8: (a, bc) and (ab, c) hash different texts.
        h = fnv1a_from(fnv1a_from(h, &[0xFF]), t.as_bytes());
    }
    format!("{}={h:016x}", &name[..at])
}

/// The file stem (name without extension) of a subject's report; see the module
/// documentation. Plain ids (`H01`) are their own name.
pub fn file_stem(subject_id: &str) -> String {
    key_stem(subject_id, None)
}

/// The file stem of a subject's trace: [`file_stem`] of the subject, and for one of a person's
/// several trials `<subject>~trial-<trial>` (both parts named as in [`file_stem`]).
pub fn key_stem(subject_id: &str, trial_id: Option<&str>) -> String {
    let mut name = encode(subject_id);
    if let Some(t) = trial_id {
        name.push_str(TRIAL_SEPARATOR);
        name.push_str(&encode(t));
    }
    if name.len() > MAX_NAME_BYTES {
        cut(&name, subject_id, trial_id)
    } else {
        name
    }
}

/// Refuse a cohort in which two subject ids would share a report file (equal ignoring case).
/// Run before any work, so nothing is overwritten and nothing is half-written.
pub fn check_unique<'a>(ids: impl IntoIterator<Item = &'a str>) -> Result<()> {
    check_unique_keys(ids.into_iter().map(|id| (id, None)))
}

/// Refuse a cohort in which two (subject, trial) keys would share a trace file, or two subjects
/// a report file (names equal ignoring case, or a repeated key). A person's several trials
/// share one report, so a subject id may come with several trials.
pub fn check_unique_keys<'a>(
    keys: impl IntoIterator<Item = (&'a str, Option<&'a str>)>,
) -> Result<()> {
    type Key<'a> = (&'a str, Option<&'a str>);
    let mut traces: std::collections::HashMap<String, Key<'a>> = Default::default();
    let mut reports: std::collections::HashMap<String, &'a str> = Default::default();
    let show = |(s, t): Key<'_>| match t {
        None => format!("{s:?}"),
        Some(t) => format!("{s:?} trial {t:?}"),
    };
    for key in keys {
        let stem = key_stem(key.0, key.1);
        if let Some(other) = traces.insert(stem.to_ascii_lowercase(), key) {
            if other == key {
                return Err(LdhError::signal(
                    "inputs",
                    format!("subject {} appears twice: rename one", show(key)),
                ));
            }
            let what = if key.1.is_none() && other.1.is_none() {
                "subject ids"
            } else {
                "subjects"
            };
            return Err(LdhError::signal(
                "inputs",
                format!(
                    "{what} {} and {} would share the output file '{stem}' (file names ignore case on some systems): rename one",
                    show(other),
                    show(key)
                ),
            ));
        }
        let stem = file_stem(key.0);
        if let Some(other) = reports.insert(stem.to_ascii_lowercase(), key.0) {
            if other != key.0 {
                return Err(LdhError::signal(
                    "inputs",
                    format!(
                        "subject ids {other:?} and {:?} would share the report file '{stem}' (file names ignore case on some systems): rename one",
                        key.0
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn plain_ids_are_their_own_names() {
        for id in ["S01", "P_1", "a-b.c", "HC_003", "P1__trial_2", "CONTROL"] {
            assert_eq!(file_stem(id), id);
        }
        assert_eq!(key_stem("P1", Some("a")), "P1~trial-a");
    }

    #[test]
    fn other_ids_are_percent_encoded() {
        assert_eq!(file_stem("P 1"), "P%201");
        assert_eq!(file_stem("P/1"), "P%2F1");
        assert_eq!(file_stem(".hidden"), "%2Ehidden");
        assert_eq!(file_stem(""), "%");
        assert_eq!(file_stem("S 01/../x"), "S%2001%2F%2E%2E%2Fx");
        assert_eq!(file_stem("con"), "%63on");
        assert_eq!(file_stem("LPT1.txt"), "%4CPT1%2Etxt");
        assert_eq!(file_stem("a~b"), "a%7Eb");
        assert_eq!(file_stem("é"), "%C3%A9");
        assert!(file_stem("Пациент 1").is_ascii());
        // The trace of subject `P1__trial_2` and that of subject `P1`, trial `2` differ.
        assert_ne!(key_stem("P1__trial_2", None), key_stem("P1", Some("2")));
        let long = "x".repeat(300);
        let s = file_stem(&long);
        assert_eq!(s.len(), CUT_BYTES + 17);
        assert_ne!(s, file_stem(&"x".repeat(301)));
        // Never cut inside an escape.
        let s = file_stem(&"é".repeat(100));
        assert!(s.split('=').next().unwrap().len().is_multiple_of(3), "{s}");
    }

    #[test]
    fn case_and_exact_duplicates_are_refused() {
        assert!(check_unique(["P 1", "P_1", "P/1"]).is_ok());
        let e = check_unique(["p1", "P1"]).unwrap_err().to_string();
        assert!(e.contains("\"p1\" and \"P1\""), "{e}");
        let e = check_unique(["S1", "S1"]).unwrap_err().to_string();
        assert!(e.contains("appears twice"), "{e}");
        let e = check_unique_keys([("P1", Some("a")), ("P1", Some("A"))])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("\"P1\" trial \"a\" and \"P1\" trial \"A\""),
            "{e}"
        );
        assert!(
            check_unique_keys([("P1", Some("a")), ("P1", Some("b")), ("P1__trial_a", None)])
                .is_ok()
        );
    }

    /// Ids made of the pieces that used to collide: `__`, `_trial_`, `/`, `..`, `.`, `~`, `%`,
    /// `=`, spaces, case and Unicode variants (NFC/NFD é, Turkish dotless ı, ß), device names.
    fn id() -> impl Strategy<Value = String> {
        let piece = prop::sample::select(vec![
            "P", "p", "1", "_", "__", "__trial_", "~trial-", "/", "..", ".", "~", "%", "%41", "=",
            " ", "-", "é", "e\u{301}", "É", "ı", "I", "ß", "SS", "CON", "nul", "x",
        ]);
        prop::collection::vec(piece, 0..8).prop_map(|v| v.concat())
    }

    fn key() -> impl Strategy<Value = (String, Option<String>)> {
        (id(), prop::option::of(id()))
    }

    proptest! {
        /// Names are safe file names; distinct keys get distinct names (also ignoring case,
        /// unless the keys are equal ignoring case, which `check_unique_keys` refuses); and the
        /// check refuses exactly the cohorts in which two keys would share a file.
        #[test]
        fn keys_name_distinct_safe_files(keys in prop::collection::vec(key(), 1..12), long in 0usize..3) {
            let keys: Vec<(String, Option<String>)> = keys
                .into_iter()
                .map(|(s, t)| (s.repeat(1 + long * 40), t))
                .collect();
            let mut by_name: std::collections::HashMap<String, &(String, Option<String>)> = Default::default();
            let mut clash = false;
            for k in &keys {
                let name = key_stem(&k.0, k.1.as_deref());
                prop_assert!(!name.is_empty() && name.is_ascii() && name.len() <= MAX_NAME_BYTES);
                prop_assert!(!name.starts_with('.') && !name.contains('/') && !name.contains('\\'));
                prop_assert!(!reserved(&name), "{name}");
                if !name.contains('=') {
                    prop_assert_eq!(name.contains('~'), k.1.is_some());
                }
                if let Some(other) = by_name.insert(name.to_ascii_lowercase(), k) {
                    let cut = name.contains('=');
                    // Uncut names meet only for keys equal ignoring ASCII case.
                    prop_assert!(cut || (other.0.eq_ignore_ascii_case(&k.0)
                        && other.1.as_deref().map(str::to_ascii_lowercase) == k.1.as_deref().map(str::to_ascii_lowercase)),
                        "{other:?} and {k:?} share {name}");
                    clash = true;
                }
                if let Some(t) = &k.1 {
                    prop_assert_ne!(&name, &key_stem(&format!("{}__trial_{t}", k.0), None));
                }
            }
            let mut subjects: std::collections::HashMap<String, &str> = Default::default();
            for k in &keys {
                if let Some(o) = subjects.insert(file_stem(&k.0).to_ascii_lowercase(), &k.0) {
                    clash |= o != k.0;
                }
            }
            let checked = check_unique_keys(keys.iter().map(|(s, t)| (s.as_str(), t.as_deref())));
            prop_assert_eq!(checked.is_err(), clash, "{:?}", checked);
        }

        /// A plain id is its own name; two different ids never share a name.
        #[test]
        fn the_name_of_an_id_is_injective(a in id(), b in id()) {
            if plain(&a) {
                prop_assert_eq!(file_stem(&a), a.clone());
            }
            if a != b {
                prop_assert_ne!(file_stem(&a), file_stem(&b));
                prop_assert_ne!(key_stem("S", Some(&a)), key_stem("S", Some(&b)));
                prop_assert_ne!(key_stem(&a, Some("1")), key_stem(&b, Some("1")));
            }
        }
    }
}
