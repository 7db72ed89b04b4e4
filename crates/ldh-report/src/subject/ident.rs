//! The subject page's identification under its title: per trial its id, visit, setting (a
//! treadmill's belt speed) and the files by name only (no machine's folders).

use maud::{html, Markup};

use super::super::html::base_name;
use ldh_core::output::{labels, RecordingRow};

/// Where the walk happened, as given: `treadmill, belt 1.10 m/s`, `overground`; `None` when
/// the manifest does not say (nothing is printed for it).
pub(crate) fn setting_text(r: &RecordingRow) -> Option<String> {
    match (labels::text(&r.setting), r.belt_speed_mps) {
        ("treadmill", Some(b)) => Some(format!("treadmill, belt {b:.2} m/s")),
        ("treadmill", None) => Some("treadmill (belt speed not given)".into()),
        ("", _) => None,
        (other, _) => Some(other.to_string()),
    }
}

/// One trial's line: `trial 2, visit pre, treadmill, belt 1.10 m/s: files a.csv (left leg),
/// b.csv (right leg)`; without trial, visit or setting, the files alone.
fn trial_line(legs: &[&RecordingRow]) -> String {
    let first = legs[0];
    let mut head: Vec<String> = Vec::new();
    if !first.trial_id.is_empty() {
        head.push(format!("trial {}", first.trial_id));
    }
    if !first.visit.is_empty() {
        head.push(format!("visit {}", first.visit));
    }
    head.extend(setting_text(first));
    let files: Vec<String> = legs
        .iter()
        .map(|r| {
            let name = base_name(&r.source);
            if name.is_empty() {
                format!("no file read ({} leg)", r.side)
            } else {
                format!("{name} ({} leg)", r.side)
            }
        })
        .collect();
    let files = format!("files {}", files.join(", "));
    if head.is_empty() {
        files
    } else {
        format!("{}: {files}", head.join(", "))
    }
}

/// When a trial was recorded, from the first of its files that says it (a header line, UTC
/// columns or the first timestamp: `recorded_at`): `Recorded 2024-03-05 10:21 UTC (from the
/// left file)`, or that the files do not say.
fn recorded_text(legs: &[&RecordingRow]) -> String {
    match legs.iter().find(|r| !r.recorded_at.is_empty()) {
        Some(r) => match r.recorded_at.parse::<ldh_core::io::DateTime>() {
            Ok(at) => format!("Recorded {} (from the {} file)", at.to_minute(), r.side),
            Err(_) => format!("Recorded {} (from the {} file)", r.recorded_at, r.side),
        },
        None => "Recording date and time: not in the files".to_string(),
    }
}

/// One line per trial of a page's recordings, in order.
fn lines(recordings: &[RecordingRow]) -> Vec<String> {
    trials(recordings).iter().map(|t| trial_line(t)).collect()
}

/// The recordings grouped by trial, in order.
fn trials(recordings: &[RecordingRow]) -> Vec<Vec<&RecordingRow>> {
    let mut trials: Vec<Vec<&RecordingRow>> = Vec::new();
    for r in recordings {
        match trials.iter_mut().find(|t| t[0].trial_id == r.trial_id) {
            Some(t) => t.push(r),
            None => trials.push(vec![r]),
        }
    }
    trials
}

/// The identification of a page with one trial, as sentences that end the header's paragraph
/// (one paragraph: the printed page keeps its length).
pub(crate) fn identification_inline(recordings: &[RecordingRow]) -> Markup {
    let l = lines(recordings);
    html! {
        @if l.len() == 1 {
            " Recorded: " (l[0]) ". " (recorded_text(&trials(recordings)[0])) "."
        }
    }
}

/// The identification of a page with several trials: one line each; when no file gives its
/// date and time, that is said once above them (not once per trial).
pub(crate) fn identification_list(recordings: &[RecordingRow]) -> Markup {
    let l = lines(recordings);
    let undated = recordings.iter().all(|r| r.recorded_at.is_empty());
    html! {
        @if l.len() > 1 {
            @if undated {
                p.meta { "Recorded (date and time: not in the files):" } "\n"
                ul.meta { @for x in &l { li { (x) "." } "\n" } } "\n"
            } @else {
                p.meta { "Recorded:" } "\n"
                ul.meta { @for (x, t) in l.iter().zip(trials(recordings)) { li { (x) ". " (recorded_text(&t)) "." } "\n" } } "\n"
            }
        }
    }
}
