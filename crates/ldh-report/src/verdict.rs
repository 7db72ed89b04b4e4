//! The verdicts of a subject's page, made once: each quantity judged against its range and
//! its left–right asymmetry judged against the threshold, in one place that the clinical
//! summary, section 2 and the cohort page's triage table all render from.
//!
//! Rules (docs/reports.md "Verdicts"):
//! - **Whole-walk quantities are one value per walk from both legs**: cadence is every heel
//!   strike of both legs per minute of walking, 60·(1/ST_left + 1/ST_right) (each leg strikes
//!   once per stride), never 60 / one side's step time; walking speed and stride time are the
//!   mean of the legs that have them (one leg alone is named).
//! - **Per-side quantities** (step time, stance, stride length, variability, shank angles, STA)
//!   are judged per side; those with [`Quantity::asymmetry`] also get one symmetry index.
//! - **A parameter and its inverse or complement are one quantity**: step frequency is the
//!   inverse of step time and swing the complement of stance; they are shown beside it and
//!   never judged on their own.
//! - **One rounding for display and comparison**: the value and the range's bounds are rounded
//!   to the decimals shown, and the bounds are inclusive ("126" lies within "96–126").
//! - **No verdict without a reference range**: a quantity without one reads "no reference".
//!   Its asymmetry is still judged when it is a relative timing or length ([`relative_asymmetry`]:
//!   step time, stance, stride length): the symmetry index compares the legs with each other, so
//!   an offset of the method that moves both legs alike (the shank's toe off, docs/reports.md)
//!   does not make it up (issue 50: a stance of 71.6 % against 52.7 % was "not judged"). The
//!   shank angles' asymmetry still needs a range (an index of angles depends on their zero).

use super::measured::not_measured;
use super::{symmetry_index_pct, Reference, ReferenceRange};
use ldh_core::domain::WalkValue;
use ldh_core::output::{Parameter, RecordingRow};
use ldh_core::Side;

/// Whether a quantity is one value per walk or one per side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scope {
    /// One value per walk, from both legs.
    Walk,
    /// One value per side.
    Side,
}

/// One quantity of the page, in clinical units: its name, unit and scale are its
/// [`Parameter`]'s ([`Parameter::label`], [`Parameter::display`]); what is here is how the
/// page uses it.
#[derive(Debug)]
pub(crate) struct Quantity {
    /// The parameter whose reference range judges it.
    pub parameter: Parameter,
    /// Decimals shown (and compared).
    pub decimals: usize,
    /// One per walk or one per side.
    pub scope: Scope,
    /// The parameter shown beside it as its inverse or complement (never judged on its own).
    pub companion: Option<Parameter>,
    /// Whether its left–right asymmetry is shown.
    pub asymmetry: bool,
    /// In the clinical summary (the rest only in section 2).
    pub in_summary: bool,
}

impl Quantity {
    /// What a clinician calls it (the parameter's name, capitalised).
    pub fn label(&self) -> String {
        self.parameter.label()
    }
    /// The clinical unit.
    pub fn unit(&self) -> &'static str {
        self.parameter.display().1
    }
    /// Factor from the table's unit to the clinical unit.
    pub fn scale(&self) -> f64 {
        self.parameter.display().0
    }
}

const fn q(
    parameter: Parameter,
    decimals: usize,
    scope: Scope,
    companion: Option<Parameter>,
    asymmetry: bool,
    in_summary: bool,
) -> Quantity {
    Quantity {
        parameter,
        decimals,
        scope,
        companion,
        asymmetry,
        in_summary,
    }
}

use Parameter as P;
use Scope::{Side as S, Walk as W};

/// How the page lays out the parameters it has a layout for, in page order; the cadence is
/// judged against the step frequency's range (in steps/min). The page shows every parameter
/// of [`Parameter::ALL`] ([`quantities`]): one without a line here follows with
/// [`default_layout`], so a new parameter reaches the page with no edit here.
pub(crate) const QUANTITIES: [Quantity; 13] = [
    q(P::StepFrequency, 0, W, None, false, true),
    q(P::Speed, 2, W, None, false, true),
    q(P::StrideTime, 2, W, None, false, true),
    q(P::StepTime, 2, S, Some(P::StepFrequency), true, true),
    q(P::StanceRatio, 1, S, Some(P::SwingRatio), true, true),
    // Issue 49: double support, one value per walk (both legs' strides share its periods).
    q(P::DoubleSupport, 1, W, None, false, false),
    q(P::StrideLength, 2, S, None, true, true),
    q(P::StrideTimeCv, 1, S, None, false, true),
    q(P::StrideLengthCv, 1, S, None, false, true),
    q(P::Wqk, 1, S, None, true, false),
    q(P::Pbi, 1, S, None, true, false),
    q(P::Bdk, 1, S, None, true, false),
    q(P::Sta, 3, S, None, false, false),
];

/// The layout of a parameter without a line in [`QUANTITIES`]: 2 decimals, one value per
/// side, no companion, no asymmetry, not in the clinical summary.
pub(crate) const fn default_layout(parameter: Parameter) -> Quantity {
    q(parameter, 2, S, None, false, false)
}

/// Every quantity of the page, in page order: [`QUANTITIES`], then every other parameter of
/// [`Parameter::ALL`] that is no quantity's companion, with [`default_layout`].
pub(crate) fn quantities() -> &'static [Quantity] {
    static ALL: std::sync::LazyLock<Vec<Quantity>> = std::sync::LazyLock::new(|| {
        let shown = |p: Parameter| {
            QUANTITIES
                .iter()
                .any(|q| q.parameter == p || q.companion == Some(p))
        };
        let rest = Parameter::ALL
            .into_iter()
            .filter(|p| !shown(*p))
            .map(default_layout);
        QUANTITIES.into_iter().chain(rest).collect()
    });
    &ALL
}

/// Whether the asymmetry of `p` is judged against the threshold without a reference range: the
/// relative timings and lengths of the two legs (module docs).
pub(crate) fn relative_asymmetry(p: Parameter) -> bool {
    matches!(p, P::StepTime | P::StanceRatio | P::StrideLength)
}

/// A value against its range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Judgement {
    /// Below the range.
    Below,
    /// Inside the range (bounds included).
    Within,
    /// Above the range.
    Above,
    /// No range to judge against.
    NoReference,
}

impl Judgement {
    /// ▲/▼ for a value outside its range.
    pub(crate) fn mark(self) -> Option<&'static str> {
        match self {
            Judgement::Below => Some("▼"),
            Judgement::Above => Some("▲"),
            _ => None,
        }
    }
    /// The plain words.
    pub(crate) fn words(self) -> &'static str {
        match self {
            Judgement::Below => "below normal",
            Judgement::Within => "within normal",
            Judgement::Above => "above normal",
            Judgement::NoReference => "no reference",
        }
    }
    /// Judged against a range (whether or not inside it).
    pub(crate) fn judged(self) -> bool {
        self != Judgement::NoReference
    }
}

/// Round `x` to `d` decimals, as it is shown.
fn round(x: f64, d: usize) -> f64 {
    format!("{x:.d$}").parse().unwrap_or(x)
}

/// `v` (clinical units, rounded) against `rr` (rounded the same way), bounds inclusive.
pub(crate) fn judge(v: f64, rr: Option<&ReferenceRange>, scale: f64, d: usize) -> Judgement {
    match rr.map(|r| (r.low, r.high)) {
        Some((Some(l), Some(h))) => {
            let (v, l, h) = (round(v, d), round(l * scale, d), round(h * scale, d));
            if v < l {
                Judgement::Below
            } else if v > h {
                Judgement::Above
            } else {
                Judgement::Within
            }
        }
        _ => Judgement::NoReference,
    }
}

/// One cell: a value with its verdict, or why it was not measured.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Cell {
    /// Measured: the value in clinical units (rounded as shown) and its verdict; `note` names
    /// a whole-walk value that comes from one leg only.
    Value {
        /// The value shown.
        v: f64,
        /// Its verdict.
        judgement: Judgement,
        /// e.g. "from the right leg only".
        note: Option<String>,
    },
    /// Not measured, with the reason.
    NotMeasured(String),
}

impl Cell {
    /// The verdict, when measured.
    pub(crate) fn judgement(&self) -> Option<Judgement> {
        match self {
            Cell::Value { judgement, .. } => Some(*judgement),
            Cell::NotMeasured(_) => None,
        }
    }
}

/// The left–right asymmetry of a quantity.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Asymmetry {
    /// The symmetry index (%, rounded to 0.1) and whether it is beyond the threshold; `None`:
    /// not judged (a shank angle without a reference range, [`relative_asymmetry`]).
    Value(f64, Option<bool>),
    /// Not measured, with the reason.
    NotMeasured(String),
}

/// The verdicts of one quantity.
#[derive(Debug)]
pub(crate) struct Row {
    /// The quantity.
    pub q: &'static Quantity,
    /// One cell per walk ([`Scope::Walk`]) or `[left, right]`.
    pub cells: Vec<Cell>,
    /// The left–right asymmetry (quantities with [`Quantity::asymmetry`]).
    pub asymmetry: Option<Asymmetry>,
    /// On a mean of trials, the trials the row's values come from when not all measured them
    /// ([`trials_note`], "from trial PWS-20 only"); what the headline's findings add.
    pub from_trials: Option<String>,
}

/// Every verdict of a subject's page, in [`quantities`] order.
#[derive(Debug)]
pub(crate) struct Verdicts {
    /// One row per quantity.
    pub rows: Vec<Row>,
    /// Why no asymmetry can be computed at all (a side missing or not analysed).
    pub no_pair: Option<String>,
}

impl Verdicts {
    /// Values outside their range (each side counted once, a walk value once).
    pub(crate) fn outside(&self) -> usize {
        self.cells().filter(|c| c.mark().is_some()).count()
    }
    /// Values judged against a range.
    pub(crate) fn judged(&self) -> usize {
        self.cells().filter(|c| c.judged()).count()
    }
    /// Values not measured.
    pub(crate) fn not_measured(&self) -> usize {
        self.rows
            .iter()
            .flat_map(|r| &r.cells)
            .filter(|c| matches!(c, Cell::NotMeasured(_)))
            .count()
    }
    /// Asymmetries beyond the threshold.
    pub(crate) fn asymmetric(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| matches!(r.asymmetry, Some(Asymmetry::Value(_, Some(true)))))
            .count()
    }
    /// When no value and no asymmetry of the rows `keep` selects was measured, the reasons,
    /// each once, in table order: a table of those rows would say "not measured" in every cell,
    /// so the page says it in one sentence instead. `None` when one of them was measured (or
    /// no row is selected).
    pub(crate) fn all_withheld(&self, keep: impl Fn(&Row) -> bool) -> Option<Vec<String>> {
        let mut why: Vec<String> = Vec::new();
        let mut add = |w: &String| {
            if !why.contains(w) {
                why.push(w.clone());
            }
        };
        let mut any = false;
        for r in self.rows.iter().filter(|r| keep(r)) {
            any = true;
            for c in &r.cells {
                match c {
                    Cell::Value { .. } => return None,
                    Cell::NotMeasured(w) => add(w),
                }
            }
            match &r.asymmetry {
                Some(Asymmetry::Value(..)) => return None,
                Some(Asymmetry::NotMeasured(w)) => add(w),
                None => {}
            }
        }
        if let Some(w) = &self.no_pair {
            add(w);
        }
        any.then_some(why)
    }
    fn cells(&self) -> impl Iterator<Item = Judgement> + '_ {
        self.rows
            .iter()
            .flat_map(|r| &r.cells)
            .filter_map(Cell::judgement)
    }
}

/// A side's value of `p` in the table's unit, or why there is none (`None` side: no
/// recording).
fn side_value(r: Option<&RecordingRow>, p: Parameter) -> Result<f64, String> {
    let r = r.ok_or("no recording")?;
    match not_measured(r, p) {
        Some(why) => Err(why),
        None => r.value(p).ok_or_else(|| "not computable".into()),
    }
}

/// The whole-walk value of `q` in the table's unit: (value, which leg alone gave it). The
/// cadence is the run's own walk value (`walk_cadence_steps_per_min`, the same on both legs'
/// rows: one computation, [`ldh_core::domain::walk_cadence_steps_per_min`]), never recomputed
/// here; it names the leg alone when only one leg has a stride time.
fn walk_value(
    q: &Quantity,
    l: Option<&RecordingRow>,
    r: Option<&RecordingRow>,
) -> Result<(f64, Option<Side>), String> {
    if q.parameter == P::StepFrequency {
        let alone = match (side_value(l, P::StrideTime), side_value(r, P::StrideTime)) {
            (Ok(_), Err(_)) => Some(Side::Left),
            (Err(_), Ok(_)) => Some(Side::Right),
            (Err(a), Err(b)) if a == b => return Err(a),
            (Err(a), Err(b)) => return Err(format!("left leg: {a}; right leg: {b}")),
            (Ok(_), Ok(_)) => None,
        };
        let per_min = [l, r]
            .into_iter()
            .flatten()
            .find_map(|x| x.walk(WalkValue::Cadence))
            .ok_or_else(|| "not computable".to_string())?;
        // The table's unit of step frequency is steps/s.
        return Ok((per_min / 60.0, alone));
    }
    let p = q.parameter;
    match (side_value(l, p), side_value(r, p)) {
        (Ok(a), Ok(b)) => Ok((0.5 * (a + b), None)),
        (Ok(a), Err(_)) => Ok((a, Some(Side::Left))),
        (Err(_), Ok(b)) => Ok((b, Some(Side::Right))),
        (Err(a), Err(b)) if a == b => Err(a),
        (Err(a), Err(b)) => Err(format!("left leg: {a}; right leg: {b}")),
    }
}

/// On a mean of trials, the trials a value of `p` comes from when not all of them measured it
/// ("from trial PWS-20 only"): the legs' trials together; `None` when a leg's value is every
/// trial's, or the row is no mean (issue 50: the step time of one belt speed of three read as
/// "the mean of 3 trials").
pub(crate) fn trials_note(legs: &[Option<&RecordingRow>], p: Parameter) -> Option<String> {
    let means: Vec<&ldh_core::output::TrialMean> = legs
        .iter()
        .flatten()
        .filter(|r| r.value(p).is_some())
        .map(|r| r.trial_mean.as_ref())
        .collect::<Option<_>>()?;
    let all = &means.first()?.trial_ids;
    let mut from: Vec<&String> = Vec::new();
    for m in &means {
        from.extend(m.only_from(p)?);
    }
    let ids: Vec<&str> = all
        .iter()
        .filter(|t| from.contains(t))
        .map(String::as_str)
        .collect();
    Some(match ids.as_slice() {
        [one] => format!("from trial {one} only"),
        more => format!("from trials {} only", more.join(", ")),
    })
}

/// A cell from a value in the table's unit.
fn cell(v: Result<f64, String>, q: &Quantity, rr: Option<&ReferenceRange>) -> Cell {
    match v {
        Ok(v) if v.is_finite() => Cell::Value {
            v: round(v * q.scale(), q.decimals),
            judgement: judge(v * q.scale(), rr, q.scale(), q.decimals),
            note: None,
        },
        Ok(_) => Cell::NotMeasured("not computable".into()),
        Err(why) => Cell::NotMeasured(why),
    }
}

/// Judge every quantity of a subject (its person rows, one per side) once.
pub(crate) fn verdicts(sides: &[&RecordingRow], reference: &Reference, limit_pct: f64) -> Verdicts {
    let find = |s: Side| sides.iter().copied().find(|r| r.side == s);
    let (left, right) = (find(Side::Left), find(Side::Right));
    let no_pair = match (left, right) {
        (None, None) => Some("no recording".to_string()),
        (Some(l), Some(r)) if !l.is_ok() && !r.is_ok() => {
            Some("neither leg was analysed (see above)".into())
        }
        (None, _) => Some("no left recording".to_string()),
        (_, None) => Some("no right recording".to_string()),
        (Some(l), _) if !l.is_ok() => Some("the left leg was not analysed (see above)".into()),
        (_, Some(r)) if !r.is_ok() => Some("the right leg was not analysed (see above)".into()),
        _ => None,
    };
    let rows = quantities()
        .iter()
        .map(|q| {
            let rr = reference.range(q.parameter);
            // The cadence is made of the stride times: their trials are its.
            let from = match q.parameter {
                P::StepFrequency => P::StrideTime,
                p => p,
            };
            let cells = match q.scope {
                Scope::Walk => vec![match walk_value(q, left, right) {
                    Ok((v, one)) => {
                        let mut c = cell(Ok(v), q, rr);
                        let legs = match one {
                            Some(Side::Left) => vec![left],
                            Some(Side::Right) => vec![right],
                            _ => vec![left, right],
                        };
                        let notes: Vec<String> = one
                            .map(|s| format!("from the {s} leg only"))
                            .into_iter()
                            .chain(trials_note(&legs, from))
                            .collect();
                        if let Cell::Value { note, .. } = &mut c {
                            *note = (!notes.is_empty()).then(|| notes.join("; "));
                        }
                        c
                    }
                    Err(why) => Cell::NotMeasured(why),
                }],
                Scope::Side => [left, right]
                    .into_iter()
                    .map(|r| {
                        let mut c = cell(side_value(r, q.parameter), q, rr);
                        if let Cell::Value { note, .. } = &mut c {
                            *note = trials_note(&[r], q.parameter);
                        }
                        c
                    })
                    .collect(),
            };
            let asymmetry = q.asymmetry.then(|| {
                if let Some(why) = &no_pair {
                    return Asymmetry::NotMeasured(why.clone());
                }
                let judged = relative_asymmetry(q.parameter)
                    || rr.is_some_and(|r| r.low.is_some() && r.high.is_some());
                match (
                    side_value(left, q.parameter),
                    side_value(right, q.parameter),
                ) {
                    // One reason for both legs: the same note as the legs' values.
                    (Err(a), Err(b)) if a == b => Asymmetry::NotMeasured(a),
                    (Err(w), _) => Asymmetry::NotMeasured(format!("left leg: {w}")),
                    (_, Err(w)) => Asymmetry::NotMeasured(format!("right leg: {w}")),
                    (Ok(a), Ok(b)) => match symmetry_index_pct(a, b) {
                        Some(si) => {
                            let si = round(si, 1);
                            Asymmetry::Value(si, judged.then_some(si.abs() > limit_pct))
                        }
                        None => Asymmetry::NotMeasured("not defined for these values".into()),
                    },
                }
            });
            Row {
                q,
                cells,
                asymmetry,
                from_trials: trials_note(&[left, right], from),
            }
        })
        .collect();
    Verdicts { rows, no_pair }
}
