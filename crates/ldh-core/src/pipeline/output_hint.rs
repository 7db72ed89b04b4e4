//! An ldh output folder given where recordings are expected (`ldh stats <analyze output>`): it
//! is recognised by the files its command writes, and refused with the way to pass it.

use std::path::Path;

use crate::error::LdhError;

/// Which ldh command wrote a folder, told by the files it holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// `ldh analyze`: `recordings.json`.
    Analyze,
    /// `ldh report`: `index.html` beside `subjects/`.
    Report,
    /// `ldh train`: `model_*.json` or `cv_results.json`.
    Train,
    /// `ldh stats`: `table3.json` or `stats.md`.
    Stats,
    /// `ldh predict`: `predictions.csv`.
    Predict,
}

impl OutputKind {
    /// The command whose output `dir` looks like, if any (a folder with a `manifest.csv` is an
    /// input: it is never one).
    pub fn of_folder(dir: &Path) -> Option<OutputKind> {
        let has = |name: &str| dir.join(name).is_file();
        if has("manifest.csv") {
            return None;
        }
        if has("index.html") && dir.join("subjects").is_dir() {
            Some(OutputKind::Report)
        } else if has("recordings.json") || has(crate::output::MARKER) {
            Some(OutputKind::Analyze)
        } else if [
            "model_rf.json",
            "model_svm.json",
            "model_mlp.json",
            "cv_results.json",
        ]
        .iter()
        .any(|f| has(f))
        {
            Some(OutputKind::Train)
        } else if has("table3.json") || has("stats.md") {
            Some(OutputKind::Stats)
        } else if has("predictions.csv") {
            Some(OutputKind::Predict)
        } else {
            None
        }
    }

    /// What the folder is and how it is passed instead, for a folder `d`.
    pub fn hint(self, d: &str) -> String {
        match self {
            OutputKind::Analyze => format!(
                "this is the output of `ldh analyze` (it holds recordings.json), not recordings: pass it as `--results {d}` (`ldh stats --results {d}`, `ldh train --results {d}`, `ldh predict --results {d}`) or `ldh report {d}`"
            ),
            OutputKind::Report => format!(
                "this is the output of `ldh report` (open {d}/index.html), not recordings: commands read the `ldh analyze` folder it was made from, with `--results`"
            ),
            OutputKind::Train => format!(
                "this is the output of `ldh train`, not recordings: give one of its models to `ldh predict --model {d}/model_rf.json` or `ldh analyze --classifier {d}/model_rf.json`, or the folder to `ldh report RESULTS --train {d}`"
            ),
            OutputKind::Stats => format!(
                "this is the output of `ldh stats`, not recordings: give it to `ldh report RESULTS --stats {d}`"
            ),
            OutputKind::Predict => "this is the output of `ldh predict` (predictions.csv), not recordings: its inputs were the recordings, or an `ldh analyze` folder given with `--results`".to_string(),
        }
    }
}

/// Files ldh writes into its output folders (a recording is never named so).
const OUTPUT_FILES: [&str; 12] = [
    "recordings.csv",
    "recordings.json",
    "strides.csv",
    "strides.json",
    "events.csv",
    "params.json",
    "predictions.csv",
    "dataset.csv",
    "folds.csv",
    "cv_results.json",
    "table3.csv",
    "table3.json",
];

/// The refusal of an input that is an ldh output folder, or one of the tables in one.
pub fn refusal(input: &Path) -> Option<LdhError> {
    let dir = if input.is_dir() {
        input
    } else {
        let name = input.file_name()?.to_string_lossy();
        if !OUTPUT_FILES.contains(&name.as_ref()) && !name.starts_with("model_") {
            return None;
        }
        match input.parent() {
            Some(p) if p.as_os_str().is_empty() => Path::new("."),
            Some(p) => p,
            None => return None,
        }
    };
    let kind = OutputKind::of_folder(dir)?;
    Some(LdhError::signal(
        input.display().to_string(),
        kind.hint(&dir.display().to_string()),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_folders_are_told_apart_and_inputs_are_not_one() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path();
        assert_eq!(OutputKind::of_folder(p), None);
        std::fs::write(p.join("recordings.json"), "[]").unwrap();
        assert_eq!(OutputKind::of_folder(p), Some(OutputKind::Analyze));
        let e = refusal(&p.join("recordings.csv")).unwrap().to_string();
        assert!(
            e.contains("`ldh stats --results") && e.contains("ldh analyze"),
            "{e}"
        );
        std::fs::write(p.join("manifest.csv"), "").unwrap();
        assert_eq!(OutputKind::of_folder(p), None);
        let t = tempfile::tempdir().unwrap();
        std::fs::write(t.path().join("model_svm.json"), "{}").unwrap();
        assert_eq!(OutputKind::of_folder(t.path()), Some(OutputKind::Train));
        assert!(refusal(t.path())
            .unwrap()
            .to_string()
            .contains("ldh predict --model"));
        let r = tempfile::tempdir().unwrap();
        std::fs::write(r.path().join("index.html"), "").unwrap();
        std::fs::create_dir(r.path().join("subjects")).unwrap();
        assert_eq!(OutputKind::of_folder(r.path()), Some(OutputKind::Report));
        let s = tempfile::tempdir().unwrap();
        std::fs::write(s.path().join("stats.md"), "").unwrap();
        assert_eq!(OutputKind::of_folder(s.path()), Some(OutputKind::Stats));
        std::fs::remove_file(s.path().join("stats.md")).unwrap();
        std::fs::write(s.path().join("predictions.csv"), "").unwrap();
        assert_eq!(OutputKind::of_folder(s.path()), Some(OutputKind::Predict));
    }
}
