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
        ("", _) => "setting not given".into(),
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

/// One line per trial of a page's recordings, in order.
fn lines(recordings: &[RecordingRow]) -> Vec<String> {
    let mut trials: Vec<Vec<&RecordingRow>> = Vec::new();
    for r in recordings {
        match trials.iter_mut().find(|t| t[0].trial_id == r.trial_id) {
            Some(t) => t.push(r),
            None => trials.push(vec![r]),
        }
    }
    trials.iter().map(|t| trial_line(t)).collect()
}

/// The identification of a page with one trial, as sentences that end the header's paragraph
/// (one paragraph: the printed page keeps its length).
pub(crate) fn identification_inline(recordings: &[RecordingRow]) -> Markup {
    let l = lines(recordings);
    html! {
        @if l.len() == 1 {
            " Recorded: " (l[0]) "."
            // On screen only: the printed page keeps its length (at most 3 A4 pages).
            span.screen-only { " Recording date and time: not read from the files (not yet parsed)." }
        }
    }
}

/// The identification of a page with several trials: one line each.
pub(crate) fn identification_list(recordings: &[RecordingRow]) -> Markup {
    let l = lines(recordings);
    html! {
        @if l.len() > 1 {
            p.meta { "Recorded (recording date and time: not read from the files, not yet parsed):" } "\n"
            ul.meta { @for x in &l { li { (x) } "\n" } } "\n"
        }
    }
}
