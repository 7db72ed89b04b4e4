//! Can the sensor's height above the ankle joint be estimated from the recording itself?
//! (issue 49: TRIPOD's stride length within 2 % of belt speed × stride time; TRIPOD gives no
//! height, and many users do not know it: `sensor_height_unknown`). Measured here; **not
//! adopted** by the pipeline (docs/accuracy.md "Sensor height from the signals (issue 49)").
//!
//! **Why the height matters.** The stride integration starts and ends at the sensor's velocity
//! ω × r at the zero-velocity instant (`gait::length`); a wrong r is a velocity error ω Δr at
//! both ends, which de-drifting cannot see, so the length is off by ω Δr T, a share ω Δr / v of
//! it (v the walking speed). [`height_estimate_on_tripod`] prints the sagittal rate at each
//! zero-velocity instant and the length's error at six heights.
//!
//! **The estimator.** While the foot is flat the shank pivots about the ankle joint, at rest
//! (on a treadmill it moves at the belt's constant speed: the same for an accelerometer). A
//! sensor at p = r e₃ from the joint (frame F of `ldh_core::align`) feels the rigid-body
//! acceleration α × p + ω × (ω × p) — across the shank α r, along it −ω² r — on top of gravity,
//! which turns with the shank as the gyroscope says (the lever-arm model of Seel, Raisch &
//! Schauer, Sensors 2014, 14:6891, eq. 4, with the joint's own acceleration zero). Per stance,
//! over a window of samples, the specific force f(t) (m/s², F) is fitted by least squares as
//!
//! f(t) = r k(t) + g R(t)ᵀ u₀,   k(t) = α(t) × e₃ + ω(t) × (ω(t) × e₃),
//!
//! R(t) the shank's rotation since the window's start (gyroscope integrated), u₀ the vertical
//! in the shank frame there (free: no attitude needed — ldh's attitude anchors its tilt at foot
//! flat, where part of α r was read as gravity — and it absorbs an accelerometer offset), α the
//! central difference of ω. Four unknowns, three equations per sample. Each stance keeps the
//! window (0.2 of the stance, moved over 10–70 % of it) whose r has the smallest standard
//! error, if that error is ≤ 3 cm and |u₀| within 5 % of 1; the walk's height is the median of
//! at least 5 stances, with their interquartile range. Window, search range and gates chosen on
//! the simulators, seed 100 (both families); reported on seed 200 (`LDH_SEED=200`), TRIPOD and
//! HuGaDB. `LDH_IDEAL=1` draws family B with ideal sensors.
//!
//! `cargo test --profile ci -p ldh-sim --test analysis height_estimate -- --nocapture --test-threads 1`

use super::events_accuracy::tripod::{tripod_dir, TRIPOD_RUNS};
use super::events_accuracy::{no_sta, summary};
use super::events_to_hugadb::{hugadb_dir, hugadb_pair};
use super::real_data::RealWalk;
use ldh_core::align::Aligned;
use ldh_core::domain::Parameter;
use ldh_core::gait::{zero_velocity_sample, Stride, ZeroVelocity};
use ldh_core::pipeline::quality::codes;
use ldh_core::pipeline::{Analysis, LegResult, SubjectInput, SubjectResult};
use ldh_core::recording::STANDARD_GRAVITY_MPS2;
use ldh_sim::evaluate::stride_scores;
use ldh_sim::family_b::CohortParamsB;
use ldh_sim::{analyze_simulated_with, simulated_input, CohortParams, SimSubject};
use nalgebra::{Matrix3, Matrix4, Rotation3, Vector3, Vector4};

/// One stance's fit: the lever arm and how well the rigid-body model explains the samples.
#[derive(Debug, Clone, Copy, PartialEq)]
struct StanceFit {
    /// The sensor's height above the ankle joint along the shank, m.
    height_m: f64,
    /// RMS of the fit's residual, m/s².
    residual_mps2: f64,
    /// |u₀|: the fitted vertical's length (1 when the accelerometer reads 1 g at rest).
    gravity_norm: f64,
    /// RMS of |k|, m/s² per m: how much the window's rotation says about the height (near 0
    /// when the shank is still, as on simulator family A).
    leverage: f64,
    /// Standard error of the height, m: the residual through the fit's normal equations
    /// (large when the model does not hold, or when the window's rotation says little).
    se_m: f64,
    /// Samples fitted.
    samples: usize,
}

/// Fit one window of samples `a..b` (the stance's foot flat; see the module doc). `None` when
/// the window has fewer than 6 samples or the fit is singular.
fn fit_stance(al: &Aligned, a: usize, b: usize) -> Option<StanceFit> {
    let n = al.gyro_dps[0].len();
    if a < 1 || b + 1 >= n || b < a + 5 {
        return None;
    }
    let dt = 1.0 / al.fs_hz;
    let acc = al.acc_motion_g();
    let w = |i: usize| Vector3::from_fn(|k, _| al.gyro_dps[k][i].to_radians());
    let f = |i: usize| Vector3::from_fn(|k, _| acc[k][i] * STANDARD_GRAVITY_MPS2);
    let e3 = Vector3::z();
    // R(t): the shank frame at t in the frame at the window's start.
    let mut rot = Rotation3::identity();
    let mut ata = Matrix4::<f64>::zeros();
    let mut atb = Vector4::<f64>::zeros();
    let mut rows: Vec<(Vector3<f64>, Matrix3<f64>, Vector3<f64>)> = Vec::with_capacity(b - a + 1);
    let mut lev = 0.0;
    for i in a..=b {
        if i > a {
            let wm = (w(i - 1) + w(i)) * (0.5 * dt);
            rot *= Rotation3::new(wm);
        }
        let (wi, alpha) = (w(i), (w(i + 1) - w(i - 1)) / (2.0 * dt));
        let k = alpha.cross(&e3) + wi.cross(&wi.cross(&e3));
        lev += k.norm_squared();
        let gr = rot.matrix().transpose() * STANDARD_GRAVITY_MPS2;
        let fi = f(i);
        for row in 0..3 {
            let x = Vector4::new(k[row], gr[(row, 0)], gr[(row, 1)], gr[(row, 2)]);
            ata += x * x.transpose();
            atb += x * fi[row];
        }
        rows.push((k, gr, fi));
    }
    let chol = ata.cholesky()?;
    let sol = chol.solve(&atb);
    let var_r = chol.inverse()[(0, 0)];
    let (r, u0) = (sol[0], Vector3::new(sol[1], sol[2], sol[3]));
    let sse: f64 = rows
        .iter()
        .map(|(k, gr, fi)| (fi - k * r - gr * u0).norm_squared())
        .sum();
    let m = rows.len() as f64;
    let residual = (sse / (3.0 * m - 4.0)).sqrt();
    Some(StanceFit {
        height_m: r,
        residual_mps2: residual,
        se_m: residual * var_r.sqrt(),
        gravity_norm: u0.norm(),
        leverage: (lev / m).sqrt(),
        samples: rows.len(),
    })
}

/// The part of each stance (heel strike to toe off) searched for foot flat.
const FOOT_FLAT_SHARE: [f64; 2] = [0.1, 0.7];
/// The window fitted, a share of the stance, moved in steps of 0.05 over [`FOOT_FLAT_SHARE`];
/// each stance keeps the window whose height has the smallest standard error (where the foot
/// is flat the rigid pivot holds and the residual is small).
const WINDOW_SHARE: f64 = 0.2;
/// A stance's fit is kept when its height's standard error is at most this, m ...
const MAX_SE_M: f64 = 0.03;
/// ... and the fitted vertical's length is within this of 1 (the accelerometer reads 1 g).
const MAX_GRAVITY_ERROR: f64 = 0.05;

/// A walk's sensor height from its strides' stance fits.
#[derive(Debug, Clone, PartialEq)]
struct HeightEstimate {
    /// Median of the strides' heights, m.
    height_m: f64,
    /// Interquartile range of the strides' heights, m.
    iqr_m: f64,
    /// Median RMS residual of the fits, m/s².
    residual_mps2: f64,
    /// Median leverage of the fits ([`StanceFit::leverage`]).
    leverage: f64,
    /// Strides fitted.
    strides: usize,
}

/// Quantile `q` of sorted `v` (linear interpolation).
fn quantile(v: &[f64], q: f64) -> f64 {
    let x = q * (v.len() - 1) as f64;
    let (i, fr) = (x.floor() as usize, x - x.floor());
    v[i] + fr * (v[(i + 1).min(v.len() - 1)] - v[i])
}

/// The sensor height of a walk from the stances of its valid strides (heel strike to toe off;
/// the window is searched in the `share` of each). `None` when fewer than 5 stances fit.
fn estimate_height(al: &Aligned, strides: &[Stride], share: [f64; 2]) -> Option<HeightEstimate> {
    let fits: Vec<StanceFit> = strides
        .iter()
        .filter(|s| s.valid && s.to_time_s.is_finite())
        .filter_map(|s| {
            let st = s.to_time_s - s.hs_time_s;
            let idx = |x: f64| ((s.hs_time_s + x * st) * al.fs_hz).round() as usize;
            let starts = ((share[1] - share[0] - WINDOW_SHARE) / 0.05)
                .round()
                .max(0.0) as usize;
            (0..=starts)
                .filter_map(|k| {
                    let a0 = share[0] + 0.05 * k as f64;
                    fit_stance(al, idx(a0), idx(a0 + WINDOW_SHARE))
                })
                .filter(|f| f.height_m.is_finite() && f.se_m.is_finite())
                .min_by(|a, b| a.se_m.total_cmp(&b.se_m))
        })
        .filter(|f| f.se_m <= MAX_SE_M && (f.gravity_norm - 1.0).abs() <= MAX_GRAVITY_ERROR)
        .collect();
    if fits.len() < 5 {
        return None;
    }
    let sorted = |g: fn(&StanceFit) -> f64| {
        let mut v: Vec<f64> = fits.iter().map(g).collect();
        v.sort_by(f64::total_cmp);
        v
    };
    let h = sorted(|f| f.height_m);
    Some(HeightEstimate {
        height_m: quantile(&h, 0.5),
        iqr_m: quantile(&h, 0.75) - quantile(&h, 0.25),
        residual_mps2: quantile(&sorted(|f| f.residual_mps2), 0.5),
        leverage: quantile(&sorted(|f| f.leverage), 0.5),
        strides: fits.len(),
    })
}

fn est(leg: &LegResult) -> Option<HeightEstimate> {
    estimate_height(leg.signals.as_ref()?, &leg.strides, FOOT_FLAT_SHARE)
}

fn fmt_est(e: &Option<HeightEstimate>) -> String {
    match e {
        Some(e) => format!(
            "{:.3} (IQR {:.3}, res {:.2}, lev {:.2}, n {})",
            e.height_m, e.iqr_m, e.residual_mps2, e.leverage, e.strides
        ),
        None => "—".into(),
    }
}

/// A simulated subject analysed with the given per-leg heights (`None`: not given).
fn analyse_sim(s: &SimSubject, h: [Option<f64>; 2]) -> SubjectResult {
    let input = SubjectInput {
        sensor_height_m: None,
        left_sensor_height_m: h[0],
        right_sensor_height_m: h[1],
        ..simulated_input(s)
    };
    analyze_simulated_with(s, &no_sta(), &input)
}

/// Per leg of a simulated cohort: true height, estimate; stride-length MAE with the true, the
/// estimated and a 0.10 m height.
fn sim_rows(name: &str, subjects: &[SimSubject]) -> super::events_accuracy::Summary {
    println!("\n{name}: leg | true h | estimate | SL MAE % true h / est h / 0.10 / 0.20");
    let (mut errs, mut mae) = (Vec::new(), [Vec::new(), Vec::new(), Vec::new(), Vec::new()]);
    for s in subjects {
        let truth_h = [s.left.truth.sensor_height_m, s.right.truth.sensor_height_m];
        let base = analyse_sim(s, truth_h.map(Some));
        let e = [&base.left, &base.right].map(|l| l.as_ref().ok().and_then(est));
        let eh = [0, 1].map(|k| e[k].as_ref().map(|e| e.height_m.clamp(0.0, 0.45)));
        let runs = [
            base,
            analyse_sim(s, eh),
            analyse_sim(s, [Some(0.10); 2]),
            analyse_sim(s, [Some(0.20); 2]),
        ];
        let t = s.truth();
        let per: Vec<Vec<Vec<f64>>> = runs
            .iter()
            .map(|r| {
                let sc = stride_scores(std::slice::from_ref(r), std::slice::from_ref(&t));
                ["left", "right"]
                    .iter()
                    .map(|side| {
                        sc.iter()
                            .filter(|x| x.side == *side)
                            .filter_map(|x| x.stride_length_error_pct)
                            .collect()
                    })
                    .collect()
            })
            .collect();
        for k in 0..2 {
            let m = |v: &Vec<f64>| {
                if v.is_empty() {
                    f64::NAN
                } else {
                    v.iter().map(|x| x.abs()).sum::<f64>() / v.len() as f64
                }
            };
            println!(
                "{} {} | {:.3} | {} | {:.2} / {:.2} / {:.2} / {:.2}",
                s.params.subject_id,
                ["L", "R"][k],
                truth_h[k],
                fmt_est(&e[k]),
                m(&per[0][k]),
                m(&per[1][k]),
                m(&per[2][k]),
                m(&per[3][k])
            );
            if let Some(e) = &e[k] {
                errs.push(e.height_m - truth_h[k]);
            }
            for (j, p) in per.iter().enumerate() {
                mae[j].extend(p[k].iter().map(|x| x.abs()));
            }
        }
    }
    let s = summary(&errs);
    println!(
        "{name}: height error bias {:.3} SD {:.3} P95 {:.3} m (n {}); SL MAE % true h {:.2} / est {:.2} / 0.10 {:.2} / 0.20 {:.2}",
        s.bias,
        s.sd,
        s.p95,
        s.n,
        mae[0].iter().sum::<f64>() / mae[0].len().max(1) as f64,
        mae[1].iter().sum::<f64>() / mae[1].len().max(1) as f64,
        mae[2].iter().sum::<f64>() / mae[2].len().max(1) as f64,
        mae[3].iter().sum::<f64>() / mae[3].len().max(1) as f64,
    );
    s
}

#[test]
fn height_estimate_on_the_simulators() {
    let seed: u64 = std::env::var("LDH_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let a = CohortParams {
        healthy: 4,
        ldh: 4,
        slow_ldh: 2,
        duration_s: 30.0,
        seed,
        ..CohortParams::default()
    };
    let sa: Vec<SimSubject> = (0..a.len()).map(|i| a.simulate(i).unwrap()).collect();
    let ea = sim_rows(&format!("family A seed {seed}"), &sa);
    // Family A's shank pivots rigidly over a flat foot: the model holds and the fit finds
    // every height to millimetres (seed 100: bias 0.000, SD 0.001, P95 0.002 m).
    assert!(
        ea.n >= 16 && ea.bias.abs() < 0.005 && ea.p95 < 0.01,
        "{ea:?}"
    );
    let b = CohortParamsB {
        healthy: 6,
        patients: 6,
        duration_s: 30.0,
        seed,
        sensor: if std::env::var("LDH_IDEAL").is_ok() {
            ldh_sim::family_b::SensorModelB::ideal()
        } else {
            Default::default()
        },
        ..CohortParamsB::default()
    };
    let sb: Vec<SimSubject> = (0..b.len()).map(|i| b.simulate(i).unwrap()).collect();
    let eb = sim_rows(&format!("family B seed {seed}"), &sb);
    assert!(eb.n >= 6, "{eb:?}");
}

/// One TRIPOD run analysed with per-leg heights (the shared loader, [`RealWalk::tripod`]).
fn tripod_run(dir: &std::path::Path, run: &str, belt: f64, h: [Option<f64>; 2]) -> SubjectResult {
    let mut walk = RealWalk::tripod(dir, run, belt);
    walk.input.left_sensor_height_m = h[0];
    walk.input.right_sensor_height_m = h[1];
    walk.analyse(&Analysis::new(no_sta().check().unwrap()))
}

/// Medians over the valid strides: the sagittal rate at the zero-velocity instant
/// (`gait::length`'s foot flat), deg/s — the ω of the length's error ω Δr T —, the smallest
/// |sagittal rate| anywhere in the stance, deg/s, and where the instant lies in the stance
/// (share from heel strike to toe off).
fn zupt_rates(leg: &LegResult) -> [f64; 3] {
    let al = leg.signals.as_ref().unwrap();
    let g = &al.gyro_dps;
    let w: Vec<f64> = (0..g[0].len())
        .map(|i| (g[0][i].powi(2) + g[1][i].powi(2) + g[2][i].powi(2)).sqrt())
        .collect();
    let idx = |t: f64| (t * al.fs_hz).round() as usize;
    let mut cols = [Vec::new(), Vec::new(), Vec::new()];
    for s in leg
        .strides
        .iter()
        .filter(|s| s.valid && s.to_time_s.is_finite())
    {
        let (a, b) = (idx(s.hs_time_s), idx(s.to_time_s));
        if let Some(z) = zero_velocity_sample(ZeroVelocity::FootFlat, al, &w, a, b) {
            cols[0].push(g[1][z]);
            cols[1].push((a..b).map(|i| g[1][i].abs()).fold(f64::MAX, f64::min));
            cols[2].push((z - a) as f64 / (b - a) as f64);
        }
    }
    cols.map(|mut v| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    })
}

/// Stride length − belt speed × stride time, % (valid strides with a length): bias, SD.
fn belt_error(leg: &LegResult, belt: f64) -> (f64, String) {
    let v: Vec<f64> = leg
        .strides
        .iter()
        .filter(|s| s.valid && s.stride_length_m.is_finite())
        .map(|s| 100.0 * (s.stride_length_m / (belt * s.stride_time_s) - 1.0))
        .collect();
    let s = summary(&v);
    (s.bias, format!("{:+.1} ± {:.1} ({})", s.bias, s.sd, s.n))
}

#[test]
fn height_estimate_on_tripod() {
    let Some(dir) = tripod_dir() else {
        println!("skipped: ../shared/realdata/tripod not found (set LDH_REALDATA)");
        return;
    };
    let heights = [0.05, 0.10, 0.15, 0.20, 0.25, 0.30];
    println!("run shank | ω at the zero-velocity instants, min |ω| in stance (deg/s), instant's share of the stance | estimate | SL − belt × T at {heights:?} | at the estimate");
    for (run, belt) in TRIPOD_RUNS {
        let at: Vec<SubjectResult> = heights
            .iter()
            .map(|&h| tripod_run(&dir, run, belt, [Some(h); 2]))
            .collect();
        let e = [&at[0].left, &at[0].right].map(|l| l.as_ref().ok().and_then(est));
        let eh = [0, 1].map(|k| e[k].as_ref().map(|e| e.height_m.clamp(0.0, 0.45)));
        let with_est = tripod_run(&dir, run, belt, eh);
        let without = tripod_run(&dir, run, belt, [None; 2]);
        for k in 0..2 {
            let leg = |r: &SubjectResult| {
                if k == 0 {
                    r.left.as_ref().unwrap().clone()
                } else {
                    r.right.as_ref().unwrap().clone()
                }
            };
            let z = zupt_rates(&leg(&at[0]));
            let (bias, row): (Vec<f64>, Vec<String>) =
                at.iter().map(|r| belt_error(&leg(r), belt)).unzip();
            println!(
                "{run} {} | {:.1}, {:.1}, {:.2} | {} | {} | {}",
                ["L", "R"][k],
                z[0],
                z[1],
                z[2],
                fmt_est(&e[k]),
                row.join(" | "),
                belt_error(&leg(&with_est), belt).1
            );
            // What a user without a height gets: the finding and the leg's stride length.
            let w = leg(&without);
            let finding = w
                .warnings
                .iter()
                .find(|x| x.code == codes::SENSOR_HEIGHT_UNKNOWN)
                .map(|x| format!("{:?}", x.severity));
            println!(
                "  without a height: sensor_height_unknown {finding:?}, stride length {:.3} m",
                w.parameters[Parameter::StrideLength]
            );
            assert!(finding.is_some(), "{run}: no sensor_height_unknown");
            // The length grows with the height assumed (ω Δr T), by more at the slow speed.
            assert!(bias.windows(2).all(|p| p[1] > p[0]), "{run}: {bias:?}");
            assert!(e[k].is_some(), "{run}: no estimate");
        }
    }
}

#[test]
fn height_estimate_on_hugadb() {
    let Some(dir) = hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    for file in ["01_00", "06_00", "08_02-Test", "10_00-Test", "11_03-Test"] {
        let res = hugadb_pair(&dir, file, &no_sta());
        for (side, r) in [("L", &res.left), ("R", &res.right)] {
            let e = r.as_ref().ok().and_then(est);
            println!("HuGaDB {file} {side} | {}", fmt_est(&e));
        }
    }
}
