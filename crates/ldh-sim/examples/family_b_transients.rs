//! Write two of family B's slow hemiparetic walkers on a 90 s treadmill walk, the pages a
//! clinician reads for start-up, slow-down and trend (docs/reports.md "2026-12-03, evening
//! reading"): `BP01` with a 10 s belt start-up and a 10 s slow-down, `BP02` speeding up
//! throughout (its last stride 25 % shorter than its first). The parameters are set on the
//! drawn subjects (`SubjectParamsB::ramp_s`, `slowdown_s`, `trend_share`; not on the command
//! line, docs/simulator.md).
//!
//! `cargo run --profile ci -p ldh-sim --example family_b_transients -- OUT [SEED]` writes
//! `OUT/<subject>/{left,right}.csv`, `truth.json` and `OUT/manifest.csv` (seed 50 by default);
//! then `ldh analyze OUT/manifest.csv --out RES --report`.

use ldh_core::io::FormatSpec;
use ldh_core::recording::Setting;
use ldh_sim::family_b::{simulate_subject_b, CohortParamsB};
use ldh_sim::{manifest_csv, ManifestRow};
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().ok_or("usage: family_b_transients OUT [SEED]")?);
    let seed: u64 = args.next().map_or(Ok(50), |s| s.parse())?;
    let cohort = CohortParamsB {
        healthy: 0,
        patients: 2,
        duration_s: 90.0,
        seed,
        setting: Some(Setting::Treadmill),
        ..CohortParamsB::default()
    };
    let format = FormatSpec::builtin("ldh")?;
    let mut rows = Vec::new();
    for i in 0..cohort.len() {
        let (mut p, mut rng) = cohort.draw(i);
        if i == 0 {
            (p.ramp_s, p.slowdown_s) = (10.0, 10.0);
        } else {
            p.trend_share = -0.25;
        }
        let s = simulate_subject_b(&p, &cohort.sensor, &mut rng)?;
        s.write(&out.join(&s.params.subject_id), &format)?;
        rows.push(ManifestRow::of(&s));
    }
    std::fs::write(out.join("manifest.csv"), manifest_csv(&rows))?;
    Ok(())
}
