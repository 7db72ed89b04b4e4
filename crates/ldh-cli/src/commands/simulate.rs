//! `ldh simulate`: a cohort with exact ground truth ([`ldh_sim::write_cohort`]),
//! from simulator family a (default) or the independent family b.

use std::process::ExitCode;

use anyhow::Result;
use ldh_sim::family_b::{CohortParamsB, Family, SensorModelB};
use ldh_sim::{write_cohort, Cohort, CohortParams, SensorModel};

use super::{progress, resolve_format, thread_pool};
use crate::args::SimulateArgs;

/// Run `ldh simulate`.
pub fn run(a: SimulateArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    if a.free_living {
        return free_living(&a);
    }
    let (healthy, ldh) = (a.healthy.unwrap_or(2), a.ldh.unwrap_or(2));
    let format = resolve_format(&a.format)?;
    match a.family {
        Family::A => {
            anyhow::ensure!(
                a.speed_mps.is_none() && a.setting.is_none(),
                "--speed-mps and --setting apply to --family b"
            );
            let params = CohortParams {
                healthy,
                ldh,
                slow_ldh: a.slow_ldh,
                duration_s: a.seconds,
                fs_hz: a.rate_hz,
                seed: a.seed,
                turn: !a.no_turn,
                ldh_severity_min: a.ldh_severity_min,
                ramp_s: a.ramp_s,
                trials: a.trials,
                day_to_day_sd_fraction: ldh_sim::retest::day_to_day_sd_fraction_or_default(
                    a.trials,
                    a.day_to_day_sd_fraction,
                ),
                sensor: family_a_sensor(&a),
            };
            let ldh_words = if a.slow_ldh > 0 {
                format!("LDH, of them {} slow", a.slow_ldh)
            } else {
                "LDH".to_string()
            };
            write(&params, &a, &format, [healthy, ldh], "healthy", &ldh_words)
        }
        Family::B => {
            anyhow::ensure!(
                !a.no_turn
                    && a.ldh_severity_min == 1.0
                    && a.slow_ldh == 0
                    && a.ramp_s == 0.0
                    && a.acc_range_g.is_none()
                    && a.trials == 1
                    && a.day_to_day_sd_fraction.is_none(),
                "--no-turn, --ldh-severity-min, --slow-ldh, --ramp-s, --acc-range-g, --trials and --day-to-day-sd-fraction apply to --family a (family b: --setting treadmill walks without turns; its ranges are drawn per subject)"
            );
            let params = CohortParamsB {
                healthy,
                patients: ldh,
                duration_s: a.seconds,
                fs_hz: a.rate_hz,
                seed: a.seed,
                speed_mps: a.speed_mps,
                setting: a.setting,
                sensor: if a.ideal {
                    SensorModelB::ideal()
                } else {
                    SensorModelB::default()
                },
                ..CohortParamsB::default()
            };
            write(
                &params,
                &a,
                &format,
                [healthy, ldh],
                "family-b normal gait",
                "slow hemiparetic as 'ldh'",
            )
        }
    }
}

/// Family a's sensor model: ideal or the default, with `--acc-range-g` when given (checked by
/// the cohort's validation).
fn family_a_sensor(a: &SimulateArgs) -> SensorModel {
    let sensor = if a.ideal {
        SensorModel::ideal()
    } else {
        SensorModel::default()
    };
    match a.acc_range_g {
        Some(g) => sensor.acc_range_g(g),
        None => sensor,
    }
}

fn write<C: Cohort>(
    params: &C,
    a: &SimulateArgs,
    format: &ldh_core::io::FormatSpec,
    [n_healthy, n_ldh]: [usize; 2],
    healthy: &str,
    ldh: &str,
) -> Result<ExitCode> {
    params.validate()?;
    let pool = thread_pool(a.jobs)?;
    let trials = params.trials().max(1);
    let pb = progress((params.len() * trials) as u64, "simulate");
    let rows = pool.install(|| write_cohort(params, &a.out, format, &|| pb.inc(1)))?;
    pb.finish_and_clear();
    if a.reference {
        let [e, st] = ldh_sim::evaluate::write_cohort_reference(&a.out)?;
        super::note!(
            "wrote the true events and strides as {} and {}",
            e.display(),
            st.display()
        );
    }
    let trials = if trials > 1 {
        format!(", {trials} trials each")
    } else {
        String::new()
    };
    super::note!(
        "wrote {} ({} {healthy}, {} {ldh}{trials}) to {}",
        super::count(rows.len() / params.trials().max(1), "subject"),
        n_healthy,
        n_ldh + a.slow_ldh,
        a.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `ldh simulate --free-living`: days at home per subject, streamed
/// ([`ldh_sim::free_living::simulate_free_living`]).
fn free_living(a: &SimulateArgs) -> Result<ExitCode> {
    use ldh_sim::free_living::{simulate_free_living, FreeLivingParams, LongFormat};
    anyhow::ensure!(
        a.family == Family::A && a.trials == 1 && !a.reference && a.slow_ldh == 0,
        "--free-living simulates family a's gait, one recording per subject (no --family b, --trials, --reference or --slow-ldh)"
    );
    let format = match a.format.as_str() {
        "ldh" | "csv" => LongFormat::Csv,
        other => anyhow::bail!("--free-living writes format 'ldh' (CSV), not '{other}'"),
    };
    let duration_h = match (a.days, a.hours) {
        (_, Some(h)) => h,
        (Some(d), None) => d * 24.0,
        (None, None) => 24.0,
    };
    let params = FreeLivingParams {
        healthy: a.healthy.unwrap_or(1),
        ldh: a.ldh.unwrap_or(0),
        duration_h,
        fs_hz: a.rate_hz,
        seed: a.seed,
        drift_ppm: a.drift_ppm,
        sensor: family_a_sensor(a).acc_range_g(a.acc_range_g.unwrap_or(16.0)),
        format,
        ..FreeLivingParams::default()
    };
    params.validate()?;
    let pool = thread_pool(a.jobs)?;
    let pb = progress(params.len() as u64, "simulate");
    let subjects = pool.install(|| simulate_free_living(&params, &a.out, &|| pb.inc(1)))?;
    pb.finish_and_clear();
    super::note!(
        "wrote {} of {duration_h} h each at {} Hz to {}",
        super::count(subjects.len(), "free-living subject"),
        params.fs_hz,
        a.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
