//! The figure files of `ldh stats` and `ldh train`, drawn from the typed results of `ldh-core`:
//! a radar chart per attitude model (the paper's Fig. 5), the box plots of the fusion model
//! (Figs. 6–7) and a confusion matrix per classifier and cross-validation kind (Tables 6–7).

use ldh_core::attitude::AttitudeModel;
use ldh_core::cohort::{Cohort, StatsOutcome, PARAMETERS};
use ldh_core::error::Result;
use ldh_core::ml::TrainOutcome;

use crate::plots;

/// `(file name, SVG)` of `ldh stats`' figures: `radar_<model>.svg` for every model, then
/// `box_<code>.svg` per parameter for the fusion model.
pub fn stats_figures(outcome: &StatsOutcome) -> Result<Vec<(String, String)>> {
    let mut files = Vec::new();
    for (cohort, off) in outcome.cohorts.iter().zip(&outcome.offsets) {
        let series = [
            ("LDHH".into(), off.z_ldhh.clone()),
            ("LDHE".into(), off.z_ldhe.clone()),
            ("H".into(), off.z_h.clone()),
        ];
        let radar = plots::radar_svg(
            &format!("Gait parameters, {} model (z vs healthy)", cohort.model),
            &off.codes,
            &series,
        )?;
        files.push((format!("radar_{}.svg", cohort.model), radar));
        if cohort.model == AttitudeModel::Fusion {
            files.extend(box_plots(cohort)?);
        }
    }
    Ok(files)
}

/// One box plot per parameter with healthy values (LDHH, LDHE, H).
fn box_plots(cohort: &Cohort) -> Result<Vec<(String, String)>> {
    let mut files = Vec::new();
    for p in PARAMETERS {
        let g = cohort.groups(p);
        if g.h.is_empty() {
            continue;
        }
        let svg = plots::boxplot_svg(
            &format!("{} ({})", p.code(), p.unit()),
            &[
                ("LDHH".into(), g.ldhh),
                ("LDHE".into(), g.ldhe),
                ("H".into(), g.h),
            ],
            true,
        )?;
        files.push((format!("box_{}.svg", p.code()), svg));
    }
    Ok(files)
}

/// `(file name, SVG)` of `ldh train`'s confusion matrices, `confusion_<classifier>_<kind>.svg`,
/// one per cross-validation report.
pub fn train_figures(outcome: &TrainOutcome) -> Result<Vec<(String, String)>> {
    let mut files = Vec::new();
    for r in &outcome.reports {
        let kind = r.kind.as_str();
        let svg = plots::confusion_svg(
            &format!("{} — {kind} {}-fold × {}", r.classifier, r.k, r.repeats),
            &r.class_names,
            &r.confusion,
        )?;
        files.push((format!("confusion_{}_{kind}.svg", r.classifier), svg));
    }
    Ok(files)
}
