//! Which files are a subject's left and right legs, by their names (docs/input.md "Subject
//! folders and file names"; issue 37): a folder's files and two files given directly.
//!
//! A name says its side when `left` or `right` is a separate word (split at anything that is
//! not a letter or digit, case ignored) at the **start or the end** of its stem: `left.csv`,
//! `P07_left.csv`, `Albright_left.csv`, `left-P07.csv`. A side word inside a word
//! (`Albright.csv`: "right" in "albright") or in the middle of a name (`P07_left_old.csv`) says
//! nothing, and such a file is never taken for a leg; in a subject folder it is named with
//! that reason. In a folder `left.csv` / `right.csv` win over other names of their side (which
//! are named as ignored); two other files of one side are ambiguous: neither is taken, and the
//! leg's error names both. A dangling symlink is named as such.

use std::path::{Path, PathBuf};

use crate::recording::Side;

/// Extensions of the files of a folder that can be recordings (case ignored); other files
/// (format maps, notes, truth files) are not looked at.
pub const DATA_EXTENSIONS: [&str; 4] = ["csv", "tsv", "txt", "dat"];

/// What a file name says about its leg.
#[derive(Debug, Clone, PartialEq)]
pub enum NameSide {
    /// A side word at the start or the end of the name.
    Leg(Side),
    /// A side word elsewhere (inside a word, or in the middle): why it says nothing.
    Unclear(String),
    /// No side word.
    Silent,
}

/// The side a file name says ([`NameSide`]).
pub fn side_of_name(name: &str) -> NameSide {
    let stem = Path::new(name)
        .file_stem()
        .map(|s| s.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let words: Vec<&str> = stem
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect();
    let side = |w: &str| match w {
        "left" => Some(Side::Left),
        "right" => Some(Side::Right),
        _ => None,
    };
    let ends: Vec<Side> = [words.first(), words.last()]
        .into_iter()
        .flatten()
        .filter_map(|w| side(w))
        .collect();
    match ends.as_slice() {
        [s] | [s, _] if ends.iter().all(|x| x == s) => return NameSide::Leg(*s),
        [_, _] => {
            return NameSide::Unclear(
                "its name starts with one side word and ends with the other".into(),
            )
        }
        _ => {}
    }
    if let Some(w) = words.iter().find(|w| side(w).is_some()) {
        return NameSide::Unclear(format!(
            "the side word '{w}' is neither the first nor the last word of its name"
        ));
    }
    for s in ["left", "right"] {
        if let Some(w) = words.iter().find(|w| w.contains(s)) {
            return NameSide::Unclear(format!(
                "'{s}' is part of the word '{w}', not a separate side word at the start or the end of the name"
            ));
        }
    }
    NameSide::Silent
}

/// The legs found in a folder, and every file looked at but not taken, with why.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FolderPairing {
    /// The left leg's file.
    pub left: Option<PathBuf>,
    /// The right leg's file.
    pub right: Option<PathBuf>,
    /// One sentence per file not taken (or per ambiguity), naming the file(s).
    pub unpaired: Vec<String>,
    /// A file name (or a dangling symlink's) says a side.
    sided: bool,
}

impl FolderPairing {
    /// Whether a file name of the folder says a side (a subject folder), even when no leg
    /// could be taken (a dangling symlink, two files of one side). A name with a side word
    /// only inside a word (`copyright.txt`) does not make a subject folder.
    pub fn is_subject(&self) -> bool {
        self.sided
    }
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default()
}

/// Pair the files of folder `d` (not recursive; unreadable folder: nothing found). A folder
/// is a subject folder when a data file's name says a side ([`FolderPairing::is_subject`]).
pub fn pair_folder(d: &Path) -> FolderPairing {
    let mut entries: Vec<PathBuf> = match std::fs::read_dir(d) {
        Ok(rd) => rd.filter_map(|e| e.ok().map(|e| e.path())).collect(),
        Err(_) => return FolderPairing::default(),
    };
    entries.sort();
    let mut out = FolderPairing::default();
    let mut found: [Vec<PathBuf>; 2] = [vec![], vec![]];
    for p in entries {
        let name = file_name(&p);
        let data = Path::new(&name)
            .extension()
            .is_some_and(|e| DATA_EXTENSIONS.iter().any(|x| e.eq_ignore_ascii_case(x)));
        let is_link = p
            .symlink_metadata()
            .is_ok_and(|m| m.file_type().is_symlink());
        if p.is_dir() || !data {
            continue;
        }
        let says = side_of_name(&name);
        out.sided |= matches!(says, NameSide::Leg(_));
        if is_link && !p.exists() {
            if says != NameSide::Silent {
                let target = std::fs::read_link(&p)
                    .map(|t| t.display().to_string())
                    .unwrap_or_default();
                out.unpaired.push(format!(
                    "{name}: a dangling symlink (its target {target} does not exist), ignored"
                ));
            }
            continue;
        }
        match says {
            NameSide::Leg(s) => found[(s == Side::Right) as usize].push(p),
            NameSide::Unclear(why) => out.unpaired.push(format!("{name}: ignored, {why}")),
            NameSide::Silent => {}
        }
    }
    for (k, side) in [Side::Left, Side::Right].into_iter().enumerate() {
        let files = std::mem::take(&mut found[k]);
        let canonical = files
            .iter()
            .position(|p| file_name(p) == format!("{side}.csv"));
        let chosen = match (canonical, files.len()) {
            (Some(i), _) => Some(i),
            (None, 1) => Some(0),
            (None, 0) => None,
            (None, n) => {
                let names: Vec<String> = files.iter().map(|p| file_name(p)).collect();
                out.unpaired.push(format!(
                    "{} files look like the {side} leg: {} (neither is taken: remove or rename all but one)",
                    if n == 2 { "two".to_string() } else { n.to_string() },
                    names.join(", ")
                ));
                None
            }
        };
        if let Some(i) = chosen {
            for (j, p) in files.iter().enumerate() {
                if j != i {
                    out.unpaired.push(format!(
                        "{}: ignored, {side}.csv is the {side} leg",
                        file_name(p)
                    ));
                }
            }
            let p = files[i].clone();
            match side {
                Side::Left => out.left = Some(p),
                Side::Right => out.right = Some(p),
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_side_word_counts_only_as_a_word_at_the_start_or_the_end() {
        use NameSide::*;
        for (n, want) in [
            ("left.csv", Some(Side::Left)),
            ("P07_left.csv", Some(Side::Left)),
            ("Albright_left.csv", Some(Side::Left)),
            ("Albright-RIGHT.txt", Some(Side::Right)),
            ("right-P07.csv", Some(Side::Right)),
            ("left_old.csv", Some(Side::Left)),
        ] {
            assert_eq!(side_of_name(n), Leg(want.unwrap()), "{n}");
        }
        assert!(matches!(side_of_name("Albright.csv"), Unclear(w) if w.contains("'albright'")));
        assert!(
            matches!(side_of_name("P07_left_v2.csv"), Unclear(w) if w.contains("neither the first"))
        );
        assert!(matches!(side_of_name("left_to_right.csv"), Unclear(_)));
        assert_eq!(side_of_name("a.csv"), Silent);
        assert_eq!(side_of_name("HuGaDB_v1_walking_01_00.txt"), Silent);
    }

    #[test]
    fn a_folders_ignored_ambiguous_and_dangling_files_are_named() {
        let d = tempfile::tempdir().unwrap();
        let w = |n: &str| std::fs::write(d.path().join(n), "x").unwrap();
        w("a_left.csv");
        w("b_left.csv");
        w("Albright.csv");
        w("notes.md");
        #[cfg(unix)]
        std::os::unix::fs::symlink("../gone/right.csv", d.path().join("right.csv")).unwrap();
        let f = pair_folder(d.path());
        assert!(f.left.is_none() && f.right.is_none() && f.is_subject());
        let only = tempfile::tempdir().unwrap();
        std::fs::write(only.path().join("copyright.txt"), "x").unwrap();
        assert!(!pair_folder(only.path()).is_subject());
        let all = f.unpaired.join("\n");
        assert!(
            all.contains("two files look like the left leg: a_left.csv, b_left.csv"),
            "{all}"
        );
        assert!(
            all.contains("Albright.csv: ignored, 'right' is part of the word 'albright'"),
            "{all}"
        );
        #[cfg(unix)]
        assert!(
            all.contains("right.csv: a dangling symlink (its target ../gone/right.csv"),
            "{all}"
        );
        assert!(!all.contains("notes.md"));
        // left.csv wins over another left name; a name with the side word at its end is a leg
        w("left.csv");
        std::fs::remove_file(d.path().join("right.csv")).unwrap();
        w("Albright_right.csv");
        let f = pair_folder(d.path());
        assert_eq!(f.left, Some(d.path().join("left.csv")));
        assert_eq!(f.right, Some(d.path().join("Albright_right.csv")));
        let all = f.unpaired.join("\n");
        assert!(
            all.contains("a_left.csv: ignored, left.csv is the left leg"),
            "{all}"
        );
        // a folder of subject folders is no subject
        let c = tempfile::tempdir().unwrap();
        std::fs::create_dir(c.path().join("left")).unwrap();
        assert!(!pair_folder(c.path()).is_subject());
    }
}
