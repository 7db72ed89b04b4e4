//! Where TRIPOD's heel-strike scatter comes from, and candidate rules (issue 49 item 1–2;
//! docs/accuracy.md "Heel-strike precision on TRIPOD").
//!
//! Each run is analysed twice: as shipped (each strike at its impact) and with `hs_impact` off
//! (each strike at its zero crossing plus the detector's offset), which gives every strike's
//! crossing. Candidate rules are computed per strike from the crossing and the raw
//! acceleration. **Tuned on** the contacts in the first half of each run (before 62.5 s),
//! **reported on** the second half; the diagnosis uses the whole run.

use super::*;
use ldh_core::events::EventDetector;

/// Contacts before this time (s, shank clock) tune; the others report.
const TUNE_UNTIL_S: f64 = 62.5;

/// |Δ| of a 3-vector signal per sample (`d[i]` = |x_i − x_(i−1)|).
fn diff3(a: &[Vec<f64>; 3]) -> Vec<f64> {
    let n = a[0].len();
    (0..n)
        .map(|i| {
            if i == 0 {
                0.0
            } else {
                (0..3)
                    .map(|k| (a[k][i] - a[k][i - 1]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            }
        })
        .collect()
}

/// The core rule's onset with a threshold `f` of the window's peak (0.5 in the core): the
/// impact after the crossing `zc` (s) in `d`, or `None` (no impact, or a step under way).
fn onset_at(d: &[f64], fs: f64, zc: f64, t: f64, f: f64) -> Option<f64> {
    let idx = |x: f64| (x * fs).round();
    let (b0, b1) = (idx(zc - 0.15 * t), idx(zc - 0.03 * t));
    let (w0, w1) = ((zc * fs).floor() + 1.0, idx(zc + 0.12 * t));
    if b0 < 1.0 || w1 >= d.len() as f64 || b1 <= b0 || w1 < w0 {
        return None;
    }
    let mut base: Vec<f64> = d[b0 as usize..b1 as usize].to_vec();
    base.sort_by(f64::total_cmp);
    let base = base[base.len() / 2];
    let (w0, w1) = (w0 as usize, w1 as usize);
    let peak = d[w0..=w1].iter().copied().fold(0.0, f64::max);
    if peak < (4.0 * base).max(0.1) {
        return None;
    }
    let h = f * peak;
    let i = (w0..=w1).find(|&i| d[i] >= h)?;
    if d[i - 1] >= h {
        return None;
    }
    let prev = d[i - 1];
    let frac = (h - prev) / (d[i] - prev);
    Some((i as f64 - 1.0 + frac) / fs)
}

/// The largest value of `x` in the window after the crossing, parabolically interpolated.
fn peak_at(x: &[f64], fs: f64, zc: f64, t: f64) -> Option<f64> {
    let w0 = (zc * fs).floor() as usize + 1;
    let w1 = ((zc + 0.12 * t) * fs).round() as usize;
    if w1 + 1 >= x.len() || w1 <= w0 {
        return None;
    }
    let i = (w0..=w1).max_by(|&a, &b| x[a].total_cmp(&x[b]))?;
    let (a, b, c) = (x[i - 1], x[i], x[i + 1]);
    let den = a - 2.0 * b + c;
    let p = if den < 0.0 { 0.5 * (a - c) / den } else { 0.0 };
    Some((i as f64 + p.clamp(-0.5, 0.5)) / fs)
}

/// SD (ms) of the residuals after one offset, on the contacts before (`tune`) or after
/// [`TUNE_UNTIL_S`] — the offset is the median of that half's differences.
fn half_sd(hs: &[f64], opto_s: &[f64], tune: bool) -> f64 {
    let o: Vec<f64> = opto_s
        .iter()
        .copied()
        .filter(|&t| (t < TUNE_UNTIL_S) == tune)
        .collect();
    let (m, off) = matched(hs, &o);
    summary(&m.iter().map(|d| 1e3 * (d.2 - off)).collect::<Vec<_>>()).sd
}

fn corr(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let c: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let vb: f64 = b.iter().map(|y| (y - mb).powi(2)).sum();
    c / (va * vb).sqrt()
}

/// One shank of one run: today's strikes, their crossings, the signals, the references.
struct Shank {
    name: String,
    t0_s: f64,
    hs: Vec<f64>,
    zc: Vec<f64>,
    stride_s: f64,
    fs: f64,
    acc: [Vec<f64>; 3],
    heel: Vec<f64>,
    opto: Vec<f64>,
}

fn shanks(dir: &Path) -> Vec<Shank> {
    let mut out = Vec::new();
    for (run, belt) in TRIPOD_RUNS {
        let tr = TripodRun::read(dir, run, belt);
        let (l, r) = (&tr.left, &tr.right);
        let run_with = |hs_impact: bool| {
            let mut p = no_sta();
            p.events.hs_impact = hs_impact;
            Analysis::new(p.check().unwrap()).pair(
                &tr.input,
                tr.loaded(l, "LS"),
                tr.loaded(r, "RS"),
            )
        };
        let (now, gyro) = (run_with(true), run_with(false));
        let heel_file = if run == "PWS" { "RL.csv" } else { "RH.csv" };
        for (side, (t0, raw, _), a, b, hf) in [
            ('L', l, &now.left, &gyro.left, "LH.csv"),
            ('R', r, &now.right, &gyro.right, heel_file),
        ] {
            let (a, b) = (&a.as_ref().unwrap().events, &b.as_ref().unwrap().events);
            let off = EventDetector::GyroBracket.offsets().0 * b.median_stride_s;
            // Each strike's crossing: the strike of the gyroscope-only run within 0.2 s.
            let (mut hs, mut zc) = (vec![], vec![]);
            for &h in &a.hs_s {
                if let Some(i) = nearest(&b.hs_s, h, 0.2) {
                    hs.push(h + t0);
                    zc.push(b.hs_s[i] - off + t0);
                }
            }
            let (_, heel_acc, _) = read_physilog(&tr.imu.join(hf), TRIPOD_UNTIL_S);
            let dh = diff3(&heel_acc);
            let t = a.median_stride_s;
            // The heel's impact, on its own clock (up to 0.2 s off the shank's): first that
            // clock's offset, the median delay from the shank's crossing to the heel's largest
            // change within [−0.3, +0.5] T of it; then each onset in a window from 0.1 T before
            // that delay (a single wide window caught swing events on PWS+20 L, whose heel
            // clock is 0.18 s late, and matched only half its contacts).
            let mut lags: Vec<f64> = zc
                .iter()
                .filter_map(|&z| {
                    let (a, b) = (z - t0 - 0.3 * t, z - t0 + 0.5 * t);
                    let (i0, i1) = ((a * 128.0).max(1.0) as usize, (b * 128.0) as usize);
                    (i1 < dh.len()).then(|| {
                        let i = (i0..=i1).max_by(|&x, &y| dh[x].total_cmp(&dh[y])).unwrap();
                        i as f64 / 128.0 - (z - t0)
                    })
                })
                .collect();
            lags.sort_by(f64::total_cmp);
            let lag = lags[lags.len() / 2];
            let heel: Vec<f64> = zc
                .iter()
                .filter_map(|&z| onset_at(&dh, 128.0, z - t0 + lag - 0.1 * t, t, 0.5))
                .map(|h| h + t0)
                .collect();
            let opto_s = tr.opto_s(side);
            out.push(Shank {
                name: format!("{run} {side}"),
                t0_s: *t0,
                hs,
                zc,
                stride_s: t,
                fs: 128.0,
                acc: raw.clone(),
                heel,
                opto: opto_s,
            });
        }
    }
    out
}

/// Candidate heel strikes of one shank (same order as `s.hs`; a strike a rule cannot place
/// keeps today's).
fn candidates(s: &Shank) -> Vec<(String, Vec<f64>)> {
    let fs = s.fs;
    let da = diff3(&s.acc);
    let dax: Vec<f64> = (0..da.len())
        .map(|i| {
            if i == 0 {
                0.0
            } else {
                (s.acc[0][i] - s.acc[0][i - 1]).abs()
            }
        })
        .collect();
    let mag: Vec<f64> = (0..s.acc[0].len())
        .map(|i| (0..3).map(|k| s.acc[k][i].powi(2)).sum::<f64>().sqrt())
        .collect();
    let dmag: Vec<f64> = (0..mag.len())
        .map(|i| {
            if i == 0 {
                0.0
            } else {
                (mag[i] - mag[i - 1]).abs()
            }
        })
        .collect();
    let t = s.stride_s;
    let zc0: Vec<f64> = s.zc.iter().map(|z| z - s.t0()).collect();
    let per = |f: &dyn Fn(f64) -> Option<f64>| -> Vec<f64> {
        zc0.iter()
            .zip(&s.hs)
            .map(|(&z, &h)| f(z).map_or(h, |x| x + s.t0()))
            .collect()
    };
    let mut delays: Vec<f64> = s.hs.iter().zip(&s.zc).map(|(h, z)| h - z).collect();
    delays.sort_by(f64::total_cmp);
    let med = delays[delays.len() / 2];
    let shrink = |a: f64| -> Vec<f64> {
        s.hs.iter()
            .zip(&s.zc)
            .map(|(h, z)| z + med + a * (h - z - med))
            .collect()
    };
    let mut out: Vec<(String, Vec<f64>)> = vec![
        ("shipped (the core's impact onset)".into(), s.hs.clone()),
        ("crossing + median delay".into(), shrink(0.0)),
        ("shrink 0.5 to the median delay".into(), shrink(0.5)),
        ("shrink 0.75".into(), shrink(0.75)),
    ];
    for f in [0.2, 0.3, 0.4, 0.5, 0.7] {
        out.push((
            format!("|Δa| onset {f}"),
            per(&|z| onset_at(&da, fs, z, t, f)),
        ));
    }
    out.push((
        "|Δa| onsets 0.3 and 0.7 averaged".into(),
        per(&|z| Some(0.5 * (onset_at(&da, fs, z, t, 0.3)? + onset_at(&da, fs, z, t, 0.7)?))),
    ));
    out.push((
        "|Δa| onsets 0.3–0.7 (5) averaged".into(),
        per(&|z| {
            let v: Option<Vec<f64>> = [0.3, 0.4, 0.5, 0.6, 0.7]
                .iter()
                .map(|&f| onset_at(&da, fs, z, t, f))
                .collect();
            v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
        }),
    ));
    out.push((
        "|Δa| onset 0.5 on the grid".into(),
        per(&|z| onset_at(&da, fs, z, t, 0.5).map(|x| ((x * fs).ceil() - 0.5) / fs)),
    ));
    let sm: Vec<f64> = (0..da.len())
        .map(|i| {
            if i == 0 || i + 1 == da.len() {
                da[i]
            } else {
                0.25 * da[i - 1] + 0.5 * da[i] + 0.25 * da[i + 1]
            }
        })
        .collect();
    out.push((
        "[1 2 1]-smoothed |Δa| onset 0.5".into(),
        per(&|z| onset_at(&sm, fs, z, t, 0.5)),
    ));
    out.push((
        "[1 2 1] onset 0.5, accepted on the raw |Δa|".into(),
        per(&|z| {
            let raw = onset_at(&da, fs, z, t, 0.5)?;
            Some(onset_at(&sm, fs, z, t, 0.5).unwrap_or(raw))
        }),
    ));
    out.push((
        "[1 2 1]-smoothed |Δa| onset 0.4".into(),
        per(&|z| onset_at(&sm, fs, z, t, 0.4)),
    ));
    let sm2: Vec<f64> = (0..da.len())
        .map(|i| {
            if i < 2 || i + 2 >= da.len() {
                da[i]
            } else {
                (da[i - 2] + 2.0 * da[i - 1] + 3.0 * da[i] + 2.0 * da[i + 1] + da[i + 2]) / 9.0
            }
        })
        .collect();
    out.push((
        "[1 2 3 2 1]-smoothed |Δa| onset 0.5".into(),
        per(&|z| onset_at(&sm2, fs, z, t, 0.5)),
    ));
    out.push((
        "axial |Δa_x| onset 0.5".into(),
        per(&|z| onset_at(&dax, fs, z, t, 0.5)),
    ));
    out.push((
        "|Δ|a|| onset 0.5".into(),
        per(&|z| onset_at(&dmag, fs, z, t, 0.5)),
    ));
    out.push((
        "|a| peak, parabolic".into(),
        per(&|z| peak_at(&mag, fs, z, t)),
    ));
    out.push((
        "|Δa| peak, parabolic".into(),
        per(&|z| peak_at(&da, fs, z, t)),
    ));
    out
}

impl Shank {
    /// The clock time of the first sample (strikes are on the clock; signals count from it).
    fn t0(&self) -> f64 {
        self.t0_s
    }
}

/// Print each candidate's SD per shank on the tuning / reporting halves; returns the mean over
/// the shanks on the reporting halves, per candidate.
fn print_candidates(sh: &[Shank]) -> Vec<f64> {
    println!(
        "\n| rule | {} | mean tune / report |",
        sh.iter()
            .map(|s| s.name.as_str())
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|{}---|", "---|".repeat(sh.len()));
    let cands: Vec<Vec<(String, Vec<f64>)>> = sh.iter().map(candidates).collect();
    let mut reported = vec![];
    for (j, (name, _)) in cands[0].iter().enumerate() {
        let (mut tune, mut rep, mut cells) = (0.0, 0.0, vec![]);
        for (s, c) in sh.iter().zip(&cands) {
            let (a, b) = (
                half_sd(&c[j].1, &s.opto, true),
                half_sd(&c[j].1, &s.opto, false),
            );
            tune += a / sh.len() as f64;
            rep += b / sh.len() as f64;
            cells.push(format!("{a:.1} / {b:.1}"));
        }
        println!("| {name} | {} | {tune:.2} / {rep:.2} |", cells.join(" | "));
        reported.push(rep);
    }
    reported
}

/// Where the scatter comes from and what the candidates score: printed tables.
#[test]
fn hs_precision_on_tripod() {
    let Some(dir) = tripod_dir() else {
        println!("skipped: ../shared/realdata/tripod not found (set LDH_REALDATA)");
        return;
    };
    let sh = shanks(&dir);
    let mut pairs = vec![
        "| run shank | SD ldh − OptoGait | SD heel sensor − OptoGait | SD ldh − heel sensor | r(residual, ldh's previous stride) | r(residual, OptoGait's next stride) |".to_string(),
        "|---|---:|---:|---:|---:|---:|".to_string(),
    ];
    println!("| run shank | SD | robust SD (1.48 MAD) | beyond 3 robust SD | SD without them | r(prev stride) | r(crossing→strike delay) | r(sub-sample phase) | lag-1 r | hat: ldh / heel / OptoGait own SD |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    for s in &sh {
        let (m, off) = matched(&s.hs, &s.opto);
        let r: Vec<f64> = m.iter().map(|d| 1e3 * (d.2 - off)).collect();
        let med_r = {
            let mut v = r.clone();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let mut dev: Vec<f64> = r.iter().map(|x| (x - med_r).abs()).collect();
        dev.sort_by(f64::total_cmp);
        let rsd = 1.4826 * dev[dev.len() / 2];
        let kept: Vec<f64> = r
            .iter()
            .copied()
            .filter(|x| (x - med_r).abs() <= 3.0 * rsd)
            .collect();
        let prev: Vec<(f64, f64)> = m
            .iter()
            .zip(&r)
            .filter(|(d, _)| d.0 > 0)
            .map(|(d, &x)| (s.opto[d.0] - s.opto[d.0 - 1], x))
            .collect();
        let (p0, p1): (Vec<f64>, Vec<f64>) = prev.into_iter().unzip();
        let delay: Vec<f64> = m.iter().map(|d| s.hs[d.1] - s.zc[d.1]).collect();
        let phase: Vec<f64> = m
            .iter()
            .map(|d| ((s.hs[d.1] - s.t0()) * s.fs).fract())
            .collect();
        let lag: (Vec<f64>, Vec<f64>) = m
            .windows(2)
            .zip(r.windows(2))
            .filter(|(w, _)| w[1].0 == w[0].0 + 1)
            .map(|(_, x)| (x[0], x[1]))
            .unzip();
        // ldh's own previous stride and OptoGait's next one.
        let own_prev: (Vec<f64>, Vec<f64>) = m
            .iter()
            .zip(&r)
            .filter(|(d, _)| d.1 > 0)
            .map(|(d, &x)| (s.hs[d.1] - s.hs[d.1 - 1], x))
            .unzip();
        let opto_next: (Vec<f64>, Vec<f64>) = m
            .iter()
            .zip(&r)
            .filter(|(d, _)| d.0 + 1 < s.opto.len())
            .map(|(d, &x)| (s.opto[d.0 + 1] - s.opto[d.0], x))
            .unzip();
        pairs.push(format!(
            "| {} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} |",
            s.name,
            summary(&r).sd,
            score_hs(&s.heel, &s.opto).hs.sd,
            score_hs(&s.hs, &s.heel).hs.sd,
            corr(&own_prev.0, &own_prev.1),
            corr(&opto_next.0, &opto_next.1),
        ));
        let v_lo = summary(&r).sd.powi(2);
        let v_lh = score_hs(&s.hs, &s.heel).hs.sd.powi(2);
        let v_ho = score_hs(&s.heel, &s.opto).hs.sd.powi(2);
        let own = |a: f64, b: f64, c: f64| (0.5 * (a + b - c)).max(0.0).sqrt();
        println!(
            "| {} | {:.1} | {:.1} | {} / {} | {:.1} | {:.2} | {:.2} | {:.2} | {:.2} | {:.1} / {:.1} / {:.1} (heel found {}) |",
            s.name,
            summary(&r).sd,
            rsd,
            r.len() - kept.len(),
            r.len(),
            summary(&kept).sd,
            corr(&p0, &p1),
            corr(&delay, &r),
            corr(&phase, &r),
            corr(&lag.0, &lag.1),
            own(v_lo, v_lh, v_ho),
            own(v_lh, v_ho, v_lo),
            own(v_lo, v_ho, v_lh),
            s.heel.len()
        );
    }
    println!("\n{}", pairs.join("\n"));
    let reported = print_candidates(&sh);
    // On the reporting halves the shipped rule (the smoothed onset, 12.1 ms when written)
    // beats the rule before it (the raw onset at half the peak, 13.4 ms).
    let (now, before) = (reported[0], reported[7]);
    assert!(
        now <= 12.5 && now < before - 0.8,
        "{now:.2} against {before:.2} ms"
    );
}

mod stride_cv;

mod own;
