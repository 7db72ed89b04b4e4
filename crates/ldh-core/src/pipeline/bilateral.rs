//! Both legs' events merged into one bilateral sequence on a common clock.

use serde::{Deserialize, Serialize};

use crate::events::Events;
use crate::recording::Side;

pub use crate::domain::EventKind;

/// One event of the bilateral sequence.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BilateralEvent {
    /// Time, s from the recordings' first sample (both sensors share a clock).
    pub time_s: f64,
    /// The leg.
    pub side: Side,
    /// HS or TO.
    pub event: EventKind,
    /// Where the expected order (… HS_L, TO_R, HS_R, TO_L, HS_L …) is broken, why; else "".
    pub order: String,
    /// The event's confidence, 0–1 (`events::confidence`); `None` when the detector gives none.
    #[serde(default)]
    pub confidence: Option<f64>,
}

/// Both legs' events merged into one time-ordered sequence. In walking the sequence cycles
/// HS(a) → TO(b) → HS(b) → TO(a) → HS(a) (the other leg leaves the ground after the loading
/// response and lands before this leg's push-off): each event is checked against its
/// predecessor — a HS must follow the same leg's TO, a TO the other leg's HS — and breaks are
/// marked, e.g. at gait initiation and termination, pauses or missed events.
pub fn bilateral_events(left: Option<&Events>, right: Option<&Events>) -> Vec<BilateralEvent> {
    bilateral_events_on_clock(left.map(|e| (e, 0.0)), right.map(|e| (e, 0.0)))
}

/// As [`bilateral_events`], each leg's events shifted by its offset (s) onto a common clock.
pub fn bilateral_events_on_clock(
    left: Option<(&Events, f64)>,
    right: Option<(&Events, f64)>,
) -> Vec<BilateralEvent> {
    let mut v: Vec<BilateralEvent> = Vec::new();
    for (side, ev) in [(Side::Left, left), (Side::Right, right)] {
        let Some((ev, offset)) = ev else { continue };
        let conf = |c: &[f64], i: usize| c.get(i).copied().filter(|x| x.is_finite());
        for (i, &t) in ev.hs_s.iter().enumerate() {
            v.push(BilateralEvent {
                time_s: t + offset,
                side,
                event: EventKind::HeelStrike,
                order: String::new(),
                confidence: conf(&ev.hs_confidence, i),
            });
        }
        for (i, &t) in ev.to_s.iter().enumerate() {
            v.push(BilateralEvent {
                time_s: t + offset,
                side,
                event: EventKind::ToeOff,
                order: String::new(),
                confidence: conf(&ev.to_confidence, i),
            });
        }
    }
    v.sort_by(|a, b| {
        a.time_s
            .partial_cmp(&b.time_s)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for i in 1..v.len() {
        let (p, c) = (&v[i - 1], &v[i]);
        let (want_side, want_event) = match c.event {
            EventKind::HeelStrike => (c.side, EventKind::ToeOff),
            EventKind::ToeOff => (c.side.other(), EventKind::HeelStrike),
        };
        if p.side != want_side || p.event != want_event {
            let name = |e: EventKind| {
                if e == EventKind::HeelStrike {
                    "HS"
                } else {
                    "TO"
                }
            };
            v[i].order = format!(
                "follows {} {} (expected {} {})",
                p.side,
                name(p.event),
                want_side,
                name(want_event)
            );
        }
    }
    v
}
