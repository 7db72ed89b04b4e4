//! Why an event is unsure (issue 49): the typed reason a stride bounded by such an event is
//! withheld (docs/quality.md "Unsure events"). It is vocabulary, here at the bottom, so the
//! strides (`gait::StrideCode::UnsureEvent`) can name it without depending on `events`, which
//! decides it (`events/confidence.rs`).

/// Why an event is unsure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UnsureEvent {
    /// A heel strike without an impact in a walk whose other strikes show one.
    NoImpact,
    /// A heel strike followed by a second step of the acceleration almost as large.
    TwoLandings,
    /// A toe off whose late-stance peak has a rival of nearly its height.
    TwoPushOffs,
}

impl UnsureEvent {
    /// The stride's reason, as `strides.csv` writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            UnsureEvent::NoImpact => "heel strike unsure (no impact)",
            UnsureEvent::TwoLandings => "heel strike unsure (two candidate landings)",
            UnsureEvent::TwoPushOffs => "toe off unsure (two push-off peaks)",
        }
    }
}

impl std::fmt::Display for UnsureEvent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}
