//! The values of a walk rather than of a leg (issue 50): one value per walk, written on both
//! legs' rows of the per-recording table, equal there, so a table, a data frame and the report
//! read one number. Each is defined once here (column, unit, meaning), as the gait parameters
//! are in [`super::parameter`]; the column dictionary and the report read these definitions.
//!
//! - the walk's cadence, every heel strike of both legs per minute of steady walking,
//!   60 · (1 / ST_left + 1 / ST_right) (each leg strikes once per stride; one leg alone:
//!   120 / ST), [`walk_cadence_steps_per_min`] — the per-leg step frequency (`SF`, 1 / that
//!   leg's step time) stays the paper's parameter;
//! - the walk's steady window ([`crate::gait::exclude_unsteady_walk`]): its first and last heel
//!   strike, on the left recording's clock.

/// A value of the walk, the same on both legs' rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum WalkValue {
    /// Steps of both legs per minute of steady walking.
    Cadence,
    /// Start of the walk's steady window, s.
    SteadyStart,
    /// End of the walk's steady window, s.
    SteadyEnd,
}

impl WalkValue {
    /// Every walk value, in the column order of the per-recording table.
    pub const ALL: [WalkValue; 3] = [
        WalkValue::Cadence,
        WalkValue::SteadyStart,
        WalkValue::SteadyEnd,
    ];

    /// Column of the per-recording table (units in the name).
    pub const fn column(self) -> &'static str {
        match self {
            WalkValue::Cadence => "walk_cadence_steps_per_min",
            WalkValue::SteadyStart => "steady_start_s",
            WalkValue::SteadyEnd => "steady_end_s",
        }
    }

    /// Unit.
    pub const fn unit(self) -> &'static str {
        match self {
            WalkValue::Cadence => "steps/min",
            WalkValue::SteadyStart | WalkValue::SteadyEnd => "s",
        }
    }

    /// Plain name, as in a sentence.
    pub const fn name(self) -> &'static str {
        match self {
            WalkValue::Cadence => "cadence",
            WalkValue::SteadyStart => "start of steady walking",
            WalkValue::SteadyEnd => "end of steady walking",
        }
    }

    /// What it means (the column dictionary).
    pub const fn description(self) -> &'static str {
        match self {
            WalkValue::Cadence => "The walk's cadence: heel strikes of both legs per minute of steady walking, 60 · (1 / stride time left + 1 / stride time right) (one leg alone: 120 / its stride time). One value per walk, the same on both legs' rows; `step_frequency_steps_per_s` is each leg's own SF (1 / its step time, the paper's parameter). Empty when no leg has a stride time.",
            WalkValue::SteadyStart => "Start of the walk's steady walking, the one window both legs' means and CVs are of (heel strike of its first stride), s on the left recording's clock; the same on both legs' rows (each leg its own when the two recordings are not one walk). Empty when the rule is off, the walk has no valid stride, or it never becomes steady (warning `never_steady`; docs/quality.md \"Steady walking\").",
            WalkValue::SteadyEnd => "End of the walk's steady walking (heel strike ending its last stride), s on the same clock as `steady_start_s`.",
        }
    }
}

/// The walk's cadence, steps/min, from its legs' mean stride times, s (`None` or a non-finite
/// value: that leg has none): 60 · (1 / ST_left + 1 / ST_right), or 120 / ST with one leg.
pub fn walk_cadence_steps_per_min(
    left_stride_time_s: Option<f64>,
    right_stride_time_s: Option<f64>,
) -> Option<f64> {
    let ok = |x: Option<f64>| x.filter(|v| v.is_finite() && *v > 0.0);
    match (ok(left_stride_time_s), ok(right_stride_time_s)) {
        (Some(a), Some(b)) => Some(60.0 * (1.0 / a + 1.0 / b)),
        (Some(a), None) | (None, Some(a)) => Some(120.0 / a),
        (None, None) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cadence_counts_both_legs_steps() {
        assert_eq!(
            walk_cadence_steps_per_min(Some(1.0), Some(1.0)),
            Some(120.0)
        );
        let c = walk_cadence_steps_per_min(Some(1.0), Some(1.25)).unwrap();
        assert!((c - 108.0).abs() < 1e-9);
        assert_eq!(walk_cadence_steps_per_min(None, Some(1.2)), Some(100.0));
        assert_eq!(walk_cadence_steps_per_min(Some(f64::NAN), None), None);
        assert_eq!(WalkValue::Cadence.column(), "walk_cadence_steps_per_min");
    }
}
