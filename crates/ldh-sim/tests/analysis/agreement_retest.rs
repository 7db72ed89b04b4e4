//! The done-when test of `ldh stats --reliability` (issue 38 item 2): a simulated retest
//! cohort of 10 people × 3 trials with a known day-to-day variation, analysed, tabled by
//! [`reliability_table`]; the variance components must recover the simulator's.

use ldh_core::agreement::{test_retest, ValidAgreementParams};
use ldh_core::cohort::reliability_table;
use ldh_core::output::Parameter;
use ldh_sim::CohortParams;

const PEOPLE: usize = 10;
const TRIALS: usize = 3;
const F: f64 = 0.04;

fn cohort() -> CohortParams {
    CohortParams {
        healthy: PEOPLE,
        ldh: 0,
        trials: TRIALS,
        day_to_day_sd_fraction: F,
        duration_s: 30.0,
        turn: false,
        seed: 38,
        ..CohortParams::default()
    }
}

/// The simulator's true value of each person's trials: the day's mean stride time, stride
/// length and speed (length / time) the trial was simulated with.
fn truth(c: &CohortParams, p: Parameter) -> Vec<Vec<f64>> {
    (0..PEOPLE)
        .map(|i| {
            let (person, _) = c.draw(i);
            (0..TRIALS)
                .map(|t| {
                    let day = person.on_another_day(F, &mut c.trial_rng(i, t));
                    match p {
                        Parameter::StrideTime => day.stride_time_s,
                        Parameter::StrideLength => day.stride_length_m,
                        _ => day.stride_length_m / day.stride_time_s,
                    }
                })
                .collect()
        })
        .collect()
}

/// The person-level values (no day-to-day variation) of `p`.
fn person_values(c: &CohortParams, p: Parameter) -> Vec<f64> {
    (0..PEOPLE)
        .map(|i| {
            let (q, _) = c.draw(i);
            match p {
                Parameter::StrideTime => q.stride_time_s,
                _ => q.stride_length_m,
            }
        })
        .collect()
}

fn sample_var(x: &[f64]) -> f64 {
    let m = x.iter().sum::<f64>() / x.len() as f64;
    x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (x.len() as f64 - 1.0)
}

/// Standard errors of the one-way ANOVA estimates with n people, k trials, between-person
/// sample variance `sb2` of the person values and mean within-person variance `sw2` (normal
/// day-to-day deviations, person values fixed):
///
/// - within, MSW: Var = 2·sw2²/(n(k − 1)) (χ² with n(k − 1) = 20 degrees of freedom: SE 32 %);
/// - between, (MSB − MSW)/k = s²(person means) − MSW/k, the person mean T_i + d̄_i with
///   Var d̄_i = sw2/k: Var ≈ 4·sb2·(sw2/k)/(n − 1) + 2·(sw2/k)²/(n − 1) + 2·sw2²/(k²·n(k − 1))
///   (cross term, the χ² of the d̄_i's own spread, and MSW's).
fn standard_errors(sb2: f64, sw2: f64) -> (f64, f64) {
    let (n, k) = (PEOPLE as f64, TRIALS as f64);
    let within = (2.0 * sw2 * sw2 / (n * (k - 1.0))).sqrt();
    let d = sw2 / k;
    let between = (4.0 * sb2 * d / (n - 1.0)
        + 2.0 * d * d / (n - 1.0)
        + 2.0 * sw2 * sw2 / (k * k * n * (k - 1.0)))
        .sqrt();
    (between, within)
}

/// 10 healthy people × 3 trials of 30 s (no turn), day-to-day SD 4 % of each person's stride
/// time and stride length, analysed by the default pipeline, tabled by [`reliability_table`].
///
/// Two checks per parameter, printed with their numbers:
///
/// 1. **The model's variances**, within sampling error. σ_w² = f²·mean(T_i²) (stride time;
///    L_i for stride length) and σ_b² = the sample variance of the 10 people's own values (the
///    simulator's draw). With n = 10 and k = 3 the estimates are noisy: the within-person
///    variance is χ² with 20 degrees of freedom (SE 32 % of σ_w²), the between-person one has
///    the SE of [`standard_errors`] (about 35 % of σ_b² for stride time). Required: within 3
///    SE (99.7 % for a normal estimate; the χ²₂₀/20 has 0.1 % below 1 − 3·0.32 = 0.05 and
///    0.5 % above 1.95).
/// 2. **The same people's true trial values**, tightly: the ANOVA of the simulator's true
///    value of every trial (the day's mean the trial was drawn with) has the same sampling
///    error as ldh's, so ldh's components minus the truth's are only ldh's measurement: a
///    trial's mean of about 20 strides (24 s of walking) with a 2 % stride-to-stride CV is off
///    its day's target by 0.02/√20 = 0.45 % (variance 1.3 % of f² = (4 %)²; with the cross
///    term's sampling, about ±5 % of the within-person variance), plus ldh's own estimation
///    error. Required: within-person within 10 % of the truth's; between-person within 5 %
///    for stride time, 15 % for stride length and speed (each person's sensor-height error
///    scales all their stride lengths alike, a between-person term). Measured (seed 38):
///    within +0.2 %, +4.6 %, −4.9 %; between +0.7 %, +3.9 %, +7.0 % (stride time, stride
///    length, speed); against the model −0.57 / −0.34 SE (stride time, between / within) and
///    −0.61 / −0.64 SE (stride length).
#[test]
fn a_retest_cohort_of_10_people_by_3_trials_recovers_the_simulators_variances() {
    use ldh_core::io::{FormatSpec, ReadParams};
    let c = cohort();
    let dir = tempfile::tempdir().unwrap();
    ldh_sim::write_cohort(&c, dir.path(), &FormatSpec::default(), &|| {}).unwrap();
    let subjects = ldh_core::pipeline::discover(&[dir.path().to_path_buf()]).unwrap();
    assert_eq!(subjects.len(), PEOPLE * TRIALS);
    let params = ldh_core::pipeline::AnalysisParams::default()
        .with_options(None, None, None, Some(false))
        .unwrap();
    let read = ReadParams::default().check().unwrap();
    let analysis = ldh_core::pipeline::Analysis::new(params.check().unwrap()).read(read);
    let results = analysis.many(&subjects).results().unwrap();
    let rows = ldh_core::output::recording_rows(&results);
    let p = ValidAgreementParams::default();
    let table = reliability_table(&rows, &p);
    assert_eq!(table.rows.len(), 14);
    for (param, tight_between) in [
        (Parameter::StrideTime, 0.05),
        (Parameter::StrideLength, 0.15),
        (Parameter::Speed, 0.15),
    ] {
        let row = table.row(param).unwrap();
        assert_eq!((row.n_subjects, row.k_trials), (PEOPLE, TRIALS), "{row:?}");
        let (between, within) = (
            row.between_subject_var.unwrap(),
            row.within_subject_var.unwrap(),
        );
        let realized = test_retest(&truth(&c, param), &p).unwrap().variance;
        println!(
            "{}: ldh between {between:.3e} within {within:.3e}; true trials between {:.3e} \
             within {:.3e}; MDC95 {:.4}",
            param.column(),
            realized.between_subject,
            realized.within_subject,
            row.mdc95.unwrap()
        );
        assert!(
            (within / realized.within_subject - 1.0).abs() < 0.10,
            "{}: within {within} vs the true trials' {}",
            param.column(),
            realized.within_subject
        );
        assert!(
            (between - realized.between_subject).abs() < tight_between * realized.between_subject,
            "{}: between {between} vs the true trials' {}",
            param.column(),
            realized.between_subject
        );
        if param == Parameter::Speed {
            continue; // speed = L/T: its model variance is not a parameter of the simulator
        }
        let own = person_values(&c, param);
        let sb2 = sample_var(&own);
        let sw2 = F * F * own.iter().map(|v| v * v).sum::<f64>() / PEOPLE as f64;
        let (se_b, se_w) = standard_errors(sb2, sw2);
        println!(
            "  model: between {sb2:.3e} (SE {se_b:.1e}), within {sw2:.3e} (SE {se_w:.1e}): \
             ldh's off by {:+.2} and {:+.2} SE",
            (between - sb2) / se_b,
            (within - sw2) / se_w
        );
        assert!((within - sw2).abs() < 3.0 * se_w, "{}", param.column());
        assert!((between - sb2).abs() < 3.0 * se_b, "{}", param.column());
    }
}
