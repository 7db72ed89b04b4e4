//! The per-recording pipeline (SPEC §3): recording → preprocessed → aligned → attitude →
//! events → strides → parameters, for one subject's two legs, and the discovery of inputs
//! (a pair of files, a subject folder, a cohort folder, a manifest, or the embedded demo).
//!
//! One bad recording never stops the other leg or the other subjects: each side's outcome is a
//! `Result`, with the error message naming the file.

mod analysis;
mod batch;
mod bilateral;
mod finalize;
mod heights;
mod inputs;
mod leg;
mod manifest;
mod many;
pub mod output_hint;
pub mod pairing;
pub mod quality;
mod subject;
mod subject_input;

pub use crate::domain::Group;
pub use analysis::{AnalysedLeg, Analysis, LentHeelStrikes, Many};
pub use batch::{bare_subject, leg_from_arrays};
pub use bilateral::{bilateral_events, bilateral_events_on_clock, BilateralEvent, EventKind};
pub use heights::{HeightConflict, SensorHeights, MAX_SENSOR_HEIGHT_M};
pub use inputs::{
    demo_inputs, discover, discover_with, is_manifest, read_manifest, subject_id_from_files,
    Clocks, InputOptions, PeopleTrials, Source, SubjectInput,
};
pub use leg::{leg_back, leg_front, memory_report, LegFront, LegResult, STA_TURNED_OFF};
pub use manifest::{is_manifest_text, MANIFEST_COLUMNS};
pub use many::{bounded_jobs, check_output_names, FolderOptions, FolderSummary, KeptRun};
pub use quality::{
    all_leg_warnings, codes, leg_checks, leg_warnings, pair_warnings, params as quality_params,
    withhold, LegChecks, Severity, Warning, WarningCode, WarningList, WithheldList,
    RUNNING_STRIDE_TIME_S,
};
pub use subject::{LoadedLeg, SubjectResult};

use serde::{Deserialize, Serialize};

use crate::align::{AlignParams, ValidAlignParams};
use crate::attitude::{AttitudeModel, AttitudeParams, ValidAttitudeParams};
use crate::error::Result;
use crate::events::{EventParams, ValidEventParams};
use crate::gait::{SteadyParams, StrideParams, ValidSteadyParams, ValidStrideParams};
use crate::nonlinear::GaitStaParams;
use crate::preprocess::PreprocessParams;

/// All analysis parameters (each stage's own type; validated by [`AnalysisParams::check`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AnalysisParams {
    /// Preprocessing (paper §3.1).
    pub preprocess: PreprocessParams,
    /// Sensor-to-segment alignment.
    pub align: AlignParams,
    /// Attitude model and filter.
    pub attitude: AttitudeParams,
    /// Event detection.
    pub events: EventParams,
    /// Strides and stride length. `sensor_height_m` is overridden per subject by the manifest;
    /// when neither gives it, 0.10 m is assumed and checked (docs/quality.md
    /// `sensor_height_unknown`).
    pub strides: StrideParams,
    /// Gait stability (STA).
    pub sta: GaitStaParams,
    /// Compute STA. Default true.
    pub compute_sta: bool,
    /// Most strides STA is computed over: the first `sta_max_strides` of the longest run of
    /// valid strides. Default 150. The exponent depends on the length of the series, so a fixed
    /// number of strides keeps recordings of different lengths comparable (Bruijn et al., J
    /// Neurosci Methods 2009;178:327–333, who advise ≥ 150 strides and equal numbers across
    /// subjects), and it bounds the cost of a 2-hour recording. 0 = no limit.
    pub sta_max_strides: usize,
    /// Steady-state walking: the strides of the belt's start-up, gait initiation and
    /// termination are excluded before any mean or CV ([`crate::gait::SteadyParams`]; module
    /// docs of `gait::steady` give the rule and its sources).
    pub steady: SteadyParams,
}

impl Default for AnalysisParams {
    fn default() -> Self {
        AnalysisParams {
            preprocess: PreprocessParams::default(),
            align: AlignParams::default(),
            attitude: AttitudeParams::default(),
            events: EventParams::default(),
            strides: StrideParams::default(),
            sta: GaitStaParams::default(),
            compute_sta: true,
            sta_max_strides: 150,
            steady: SteadyParams::default(),
        }
    }
}

impl AnalysisParams {
    /// These parameters for a walk on a treadmill (manifest `setting`, `--setting`): no stride
    /// is a turn (`strides.turn_deg` = 180), since the walker cannot turn and a heading change
    /// is gyroscope drift; every other parameter as given (docs/input.md "Setting").
    pub fn for_treadmill(&self) -> Self {
        let mut p = self.clone();
        p.strides.turn_deg = 180.0;
        p
    }
    /// With another attitude model.
    pub fn model(mut self, m: AttitudeModel) -> Self {
        self.attitude.model = m;
        self
    }
    /// These parameters with the options of a command line or an API call applied (each `None`
    /// keeps the current value), then checked. One place for the CLI and the Python binding.
    pub fn with_options(
        mut self,
        model: Option<&str>,
        detector: Option<&str>,
        sensor_height_m: Option<f64>,
        compute_sta: Option<bool>,
    ) -> Result<Self> {
        if let Some(m) = model {
            self.attitude.model = m.parse()?;
        }
        if let Some(d) = detector {
            self.events.detector = d.parse()?;
        }
        if let Some(h) = sensor_height_m {
            self.strides.sensor_height_m = Some(h);
        }
        if let Some(c) = compute_sta {
            self.compute_sta = c;
        }
        self.check()?;
        Ok(self)
    }

    /// Validate every stage's parameters that do not depend on the recording, once per run
    /// ([`crate::ParamGuard`]): the checked parameters are what [`Analysis::new`] takes, so no
    /// stage re-checks per leg. Preprocessing needs the recording's rate, so it is checked with
    /// it at the call ([`PreprocessParams::check`]).
    pub fn check(&self) -> Result<ValidAnalysisParams> {
        // The pipeline's low-pass keeps the gait: walking's shank signals carry their events in
        // harmonics up to ~6 Hz, so below 2 Hz the mid-swing peak and the heel strike smear
        // (the upper bound, Nyquist, is checked with each recording's rate).
        if !(self.preprocess.cutoff_hz >= 2.0) {
            return Err(crate::error::LdhError::param(
                "preprocess.cutoff_hz",
                self.preprocess.cutoff_hz,
                "outside its physical range [2, fs/2) Hz",
            ));
        }
        if self.compute_sta {
            self.sta.check()?;
        }
        Ok(ValidAnalysisParams {
            align: self.align.check()?,
            attitude: self.attitude.check()?,
            events: self.events.check()?,
            strides: self.strides.check()?,
            steady: self.steady.check()?,
            params: self.clone(),
        })
    }
}

/// Every stage's checked parameters ([`AnalysisParams::check`]). The preprocessing parameters
/// and the STA parameters are held as given: preprocessing is checked with the recording's rate
/// at the call; STA's series-free bounds ([`crate::nonlinear::GaitStaParams::check`]) are
/// checked here once, and what depends on the series' rate and mean stride time inside
/// [`crate::nonlinear::gait_sta`].
#[derive(Debug, Clone, PartialEq)]
pub struct ValidAnalysisParams {
    params: AnalysisParams,
    align: ValidAlignParams,
    attitude: ValidAttitudeParams,
    events: ValidEventParams,
    strides: ValidStrideParams,
    steady: ValidSteadyParams,
}

impl ValidAnalysisParams {
    /// The parameters as given.
    pub fn params(&self) -> &AnalysisParams {
        &self.params
    }
    /// The checked alignment parameters.
    pub fn align(&self) -> &ValidAlignParams {
        &self.align
    }
    /// The checked attitude parameters.
    pub fn attitude(&self) -> &ValidAttitudeParams {
        &self.attitude
    }
    /// The checked event parameters.
    pub fn events(&self) -> &ValidEventParams {
        &self.events
    }
    /// The checked steady-state parameters.
    pub fn steady(&self) -> &ValidSteadyParams {
        &self.steady
    }
    /// The checked stride parameters with a subject's sensor height, m, when it has one (the
    /// height belongs to the subject, so it is checked here, at the call). Without one, the
    /// run's height applies, given or not ([`ValidStrideParams::sensor_height_given`]): a height
    /// neither the subject nor the run gives is assumed, and the stride length is checked for
    /// its dependence on it ([`crate::gait::height_sensitivity`]).
    pub fn strides(&self, sensor_height_m: Option<f64>) -> Result<ValidStrideParams> {
        match sensor_height_m {
            None => Ok(self.strides.clone()),
            Some(h) => self.strides.with_sensor_height_m(h),
        }
    }
    /// These parameters for a walk on a treadmill: no stride is a turn (as
    /// [`AnalysisParams::for_treadmill`]).
    pub fn for_treadmill(&self) -> Self {
        ValidAnalysisParams {
            params: self.params.for_treadmill(),
            strides: self.strides.without_turns(),
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests;
