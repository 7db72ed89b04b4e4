//! The subject page's identification under its title: per trial its id, visit, setting (a
//! treadmill's belt speed) and the files by name only (no machine's folders).

use maud::{html, Markup};

use super::super::html::base_name;
use crate::output::{labels, RecordingRow};

/// Where the walk happened, as given: `treadmill, belt 1.10 m/s`, `overground`, or that it
/// was not said.
pub(crate) fn setting_text(r: &RecordingRow) -> String {
    match (labels::text(&r.setting), r.belt_speed_mps) {
        ("treadmill", Some(b)) => format!("treadmill, belt {b:.2} m/s"),
        ("treadmill", None) => "treadmill (belt speed not given)".into(),
        ("", _) => "setting not given (analysed as overground)".into(),
        (other, _) => other.to_string(),
    }
}

/// One trial's line: `trial 2, visit pre, treadmill, belt 1.10 m/s: left a.csv, right b.csv`.
fn trial_line(legs: &[&RecordingRow]) -> String {
    let first = legs[0];
    let mut head: Vec<String> = Vec::new();
    if !first.trial_id.is_empty() {
        head.push(format!("trial {}", first.trial_id));
    }
    if !first.visit.is_empty() {
        head.push(format!("visit {}", first.visit));
    }
    head.push(setting_text(first));
    let files: Vec<String> = legs
        .iter()
        .map(|r| {
            let name = base_name(&r.source);
            if name.is_empty() {
                format!("{} (no file read)", r.side)
            } else {
                format!("{} {name}", r.side)
            }
        })
        .collect();
    format!("{}: {}", head.join(", "), files.join(", "))
}

/// The identification of a page's recordings (every trial, in order).
pub(crate) fn identification(recordings: &[RecordingRow]) -> Markup {
    let mut trials: Vec<Vec<&RecordingRow>> = Vec::new();
    for r in recordings {
        match trials.iter_mut().find(|t| t[0].trial_id == r.trial_id) {
            Some(t) => t.push(r),
            None => trials.push(vec![r]),
        }
    }
    let lines: Vec<String> = trials.iter().map(|t| trial_line(t)).collect();
    html! {
        @if lines.len() == 1 {
            p.meta { "Recorded: " (lines[0]) ". Recording date and time: not read from the files (not yet parsed)." } "\n"
        } @else if !lines.is_empty() {
            p.meta { "Recorded (recording date and time: not read from the files, not yet parsed):" } "\n"
            ul.meta { @for l in &lines { li { (l) } "\n" } } "\n"
        }
    }
}
