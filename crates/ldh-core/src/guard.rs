//! The parameter guard: every stage's parameters are checked once into the type the stage
//! accepts (linfa's `ParamGuard`, `src/param_guard.rs`: one trait, an associated `Checked`
//! type and `Error`; `Fit` is written once, on the checked parameters). Here the checked
//! type is what each stage takes ([`crate::pipeline::Analysis::new`] takes the checked
//! [`crate::pipeline::AnalysisParams`]), so no stage re-checks per call.
//!
//! Every parameter type's `check` is its implementation of [`ParamGuard::check`] (the inherent
//! method of the same name is that body, so a caller need not import the trait); the list
//! below is every guarded type with its checked type and error.
//!
//! What a check needs beyond the parameters is checked where it exists, with it as an argument
//! (these types do not implement the trait):
//! - the recording's rate: [`crate::preprocess::PreprocessParams::check`]`(fs_hz)` (the
//!   low-pass cut-off below Nyquist), called by the pipeline on each recording; the rate-free
//!   bound (cut-off ≥ 2 Hz) is part of [`crate::pipeline::AnalysisParams`]'s check;
//! - a subject's sensor height: [`crate::pipeline::ValidAnalysisParams::strides`]`(height)`;
//! - the run's detector: [`crate::events::EventCalibration::check`]`(detector)`, inside
//!   [`crate::events::EventParams`]'s check;
//! - STA's series (its rate and mean stride time): inside [`crate::nonlinear::gait_sta`]; the
//!   series-free bounds ([`crate::nonlinear::GaitStaParams::check`]) and the training
//!   parameters ([`crate::ml::TrainParams::check`]) are checked into the parameters as given.

use crate::agreement::{AgreementError, AgreementParams, ValidAgreementParams};
use crate::align::{AlignParams, ValidAlignParams};
use crate::attitude::{AttitudeParams, ValidAttitudeParams};
use crate::error::LdhError;
use crate::events::{EventParams, ValidEventParams};
use crate::gait::{SteadyParams, StrideParams, ValidSteadyParams, ValidStrideParams};
use crate::io::{ReadParams, ValidReadParams};
use crate::nonlinear::{
    EckmannParams, NonlinearError, RosensteinParams, ValidEckmannParams, ValidRosensteinParams,
};
use crate::output::trace::{TraceParams, ValidTraceParams};
use crate::pipeline::{AnalysisParams, ValidAnalysisParams};

/// Parameters checked once into the type a stage accepts.
pub trait ParamGuard {
    /// The checked parameters (what the stage takes).
    type Checked;
    /// Why the parameters were refused (naming the parameter, its value and the bound).
    type Error: std::error::Error;
    /// Check the parameters into [`ParamGuard::Checked`].
    ///
    /// # Errors
    /// [`ParamGuard::Error`] naming the first parameter out of its range.
    fn check(&self) -> Result<Self::Checked, Self::Error>;
}

/// `ParamGuard` for types whose inherent `check(&self)` is the guard.
macro_rules! guarded {
    ($($params:ty => $checked:ty, $error:ty;)*) => {$(
        impl ParamGuard for $params {
            type Checked = $checked;
            type Error = $error;
            fn check(&self) -> Result<$checked, $error> {
                <$params>::check(self)
            }
        }
    )*};
}

guarded! {
    AnalysisParams => ValidAnalysisParams, LdhError;
    AlignParams => ValidAlignParams, LdhError;
    AttitudeParams => ValidAttitudeParams, LdhError;
    EventParams => ValidEventParams, LdhError;
    StrideParams => ValidStrideParams, LdhError;
    SteadyParams => ValidSteadyParams, LdhError;
    ReadParams => ValidReadParams, LdhError;
    TraceParams => ValidTraceParams, LdhError;
    AgreementParams => ValidAgreementParams, AgreementError;
    EckmannParams => ValidEckmannParams, NonlinearError;
    RosensteinParams => ValidRosensteinParams, NonlinearError;
}

impl ParamGuard for crate::ml::mlp::MlpParams {
    type Checked = crate::ml::mlp::ValidMlpParams;
    type Error = crate::ml::mlp::MlpError;
    fn check(&self) -> Result<Self::Checked, Self::Error> {
        crate::ml::mlp::MlpParams::check(self.clone())
    }
}

impl ParamGuard for crate::pipeline::SensorHeights {
    type Checked = crate::pipeline::SensorHeights;
    type Error = LdhError;
    fn check(&self) -> Result<Self::Checked, LdhError> {
        crate::pipeline::SensorHeights::check(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stage generic over its parameters: what the trait is for.
    fn checked<P: ParamGuard + Default>() -> Result<P::Checked, P::Error> {
        P::default().check()
    }

    #[test]
    fn every_default_passes_its_guard() {
        checked::<AnalysisParams>().unwrap();
        checked::<ReadParams>().unwrap();
        checked::<TraceParams>().unwrap();
        checked::<AgreementParams>().unwrap();
        checked::<EckmannParams>().unwrap();
        checked::<RosensteinParams>().unwrap();
        checked::<crate::ml::mlp::MlpParams>().unwrap();
        checked::<crate::pipeline::SensorHeights>().unwrap();
        // The analysis' default reader limits are the checked defaults.
        let read = checked::<ReadParams>().unwrap();
        assert_eq!(ValidReadParams::default(), read);
    }

    #[test]
    fn a_bad_value_is_refused_through_the_trait() {
        let p = AnalysisParams {
            compute_sta: true,
            ..AnalysisParams::default()
        };
        let mut bad = p.clone();
        bad.preprocess.cutoff_hz = 1.0;
        assert!(ParamGuard::check(&p).is_ok());
        let e = ParamGuard::check(&bad).unwrap_err().to_string();
        assert!(e.contains("preprocess.cutoff_hz"), "{e}");
    }
}
