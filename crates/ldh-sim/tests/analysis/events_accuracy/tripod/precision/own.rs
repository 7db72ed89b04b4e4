//! ldh's *own* heel-strike precision on TRIPOD, per candidate rule (issue 49; docs/accuracy.md
//! "ldh's own heel-strike precision"): each candidate scored against the heel's own sensor (whose
//! own scatter is 2–7 ms, the footfall hat) as well as against OptoGait (9–13 ms), and ldh's own
//! scatter by the three-cornered hat of the three, per half. **Tuned on** the contacts before
//! [`TUNE_UNTIL_S`] (the mean over the shanks of the SD against the heel sensor decides; the SD
//! against OptoGait must not grow), **reported on** the second halves.
//!
//! The candidates beyond `precision.rs`'s: wider zero-phase kernels, a threshold relative to the
//! terminal swing's noise instead of the peak, the onset of |a′(t)| from a cubic (Catmull–Rom)
//! interpolation of the raw acceleration at 8 × the rate, and alignment of each impact to the
//! shank's mean impact waveform by cross-correlation (|Δa| or the signed Δa vector).
//!
//! The winner on the tuning halves ([1 2 3 4 3 2 1]/16 at 0.6 of the peak, defined as a
//! half-width of 3/128 s) was built into the core and withdrawn: it made family B's normal
//! walkers worse (HS P95 6.2 → 9.2 ms, seed 4949; `family_b_normal_events_are_not_off_like_the_family_a_models`
//! failed, HS mean absolute error above 5 ms on seed 41). The shipped rule is unchanged.

use super::*;

/// `d` smoothed by the symmetric kernel `k` (odd length; the ends kept).
fn smooth(d: &[f64], k: &[f64]) -> Vec<f64> {
    let h = k.len() / 2;
    let sum: f64 = k.iter().sum();
    (0..d.len())
        .map(|i| {
            if i < h || i + h >= d.len() {
                d[i]
            } else {
                k.iter()
                    .enumerate()
                    .map(|(j, w)| w * d[i + j - h])
                    .sum::<f64>()
                    / sum
            }
        })
        .collect()
}

/// The core's window after the crossing `zc` (s): (w0, w1, median of raw |Δa| over terminal
/// swing, peak of `d` in the window); `None` without an impact (the core's ratio test on `raw`).
fn window(raw: &[f64], d: &[f64], fs: f64, zc: f64, t: f64) -> Option<(usize, usize, f64, f64)> {
    let idx = |x: f64| (x * fs).round();
    let (b0, b1) = (idx(zc - 0.15 * t), idx(zc - 0.03 * t));
    let (w0, w1) = ((zc * fs).floor() + 1.0, idx(zc + 0.12 * t));
    if b0 < 1.0 || w1 + 1.0 >= raw.len() as f64 || b1 <= b0 || w1 < w0 {
        return None;
    }
    let mut base: Vec<f64> = raw[b0 as usize..b1 as usize].to_vec();
    base.sort_by(f64::total_cmp);
    let base = base[base.len() / 2];
    let (w0, w1) = (w0 as usize, w1 as usize);
    let peak_raw = raw[w0..=w1].iter().copied().fold(0.0, f64::max);
    if peak_raw < (4.0 * base).max(0.1) {
        return None;
    }
    let peak = d[w0..=w1].iter().copied().fold(0.0, f64::max);
    Some((w0, w1, base, peak))
}

/// Where `d` first reaches `h` in `[w0, w1]`, in samples, interpolated linearly (`None` when it
/// is already above `h` before the window).
fn first_cross(d: &[f64], w0: usize, w1: usize, h: f64) -> Option<f64> {
    let i = (w0..=w1).find(|&i| d[i] >= h)?;
    let prev = d[i - 1];
    (prev < h).then(|| i as f64 - 1.0 + (h - prev) / (d[i] - prev))
}

/// |a′| of a Catmull–Rom interpolation of `acc` at `up` points per sample (index i·up + u is
/// sample i + u/up).
fn spline_slope(acc: &[Vec<f64>; 3], up: usize) -> Vec<f64> {
    let n = acc[0].len();
    let mut out = vec![0.0; n * up];
    for i in 1..n.saturating_sub(2) {
        for u in 0..up {
            let x = u as f64 / up as f64;
            let s2: f64 = (0..3)
                .map(|k| {
                    let (p0, p1, p2, p3) = (acc[k][i - 1], acc[k][i], acc[k][i + 1], acc[k][i + 2]);
                    let v = 0.5
                        * ((p2 - p0)
                            + 2.0 * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * x
                            + 3.0 * (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * x * x);
                    v * v
                })
                .sum();
            out[i * up + u] = s2.sqrt();
        }
    }
    out
}

/// Each strike of `init` (s, signal clock; `None`: left as it is) aligned to the mean waveform of
/// `chans` around the strikes ([−3, +8] samples) by cross-correlation over ±3 samples, refined by
/// a parabola: the shift added to each strike.
fn align(chans: &[Vec<f64>], init: &[Option<f64>], fs: f64) -> Vec<Option<f64>> {
    let (j0, j1, lmax) = (-3i64, 8i64, 3i64);
    let n = chans[0].len() as i64;
    let g: Vec<Option<i64>> = init
        .iter()
        .map(|x| {
            x.map(|x| (x * fs).round() as i64)
                .filter(|&g| g + j0 - lmax >= 0 && g + j1 + lmax < n)
        })
        .collect();
    let m = g.iter().flatten().count().max(1) as f64;
    let tmpl: Vec<Vec<f64>> = chans
        .iter()
        .map(|c| {
            (j0..=j1)
                .map(|j| {
                    g.iter()
                        .flatten()
                        .map(|&g| c[(g + j) as usize])
                        .sum::<f64>()
                        / m
                })
                .collect()
        })
        .collect();
    let corr = |g: i64, l: i64| -> f64 {
        chans
            .iter()
            .zip(&tmpl)
            .map(|(c, t)| {
                (j0..=j1)
                    .zip(t)
                    .map(|(j, w)| w * c[(g + j + l) as usize])
                    .sum::<f64>()
            })
            .sum()
    };
    init.iter()
        .zip(&g)
        .map(|(&x, g)| {
            let (x, g) = (x?, (*g)?);
            let c: Vec<f64> = (-lmax..=lmax).map(|l| corr(g, l)).collect();
            let k = (0..c.len()).max_by(|&a, &b| c[a].total_cmp(&c[b]))?;
            if k == 0 || k + 1 == c.len() {
                return Some(x);
            }
            let (a, b, d) = (c[k - 1], c[k], c[k + 1]);
            let den = a - 2.0 * b + d;
            let p = if den < 0.0 { 0.5 * (a - d) / den } else { 0.0 };
            Some(g as f64 / fs + (k as f64 - lmax as f64 + p) / fs)
        })
        .collect()
}

/// The candidates of this module for one shank (same order as `s.hs`; a strike a rule cannot
/// place keeps today's).
pub(super) fn more_candidates(s: &Shank) -> Vec<(String, Vec<f64>)> {
    let (fs, t) = (s.fs, s.stride_s);
    let da = diff3(&s.acc);
    let zc0: Vec<f64> = s.zc.iter().map(|z| z - s.t0()).collect();
    let keep = |v: Vec<Option<f64>>| -> Vec<f64> {
        v.iter()
            .zip(&s.hs)
            .map(|(x, &h)| x.map_or(h, |x| x + s.t0()))
            .collect()
    };
    let onset = |d: &[f64], f: f64| -> Vec<Option<f64>> {
        zc0.iter()
            .map(|&z| {
                let (w0, w1, _, peak) = window(&da, d, fs, z, t)?;
                Some(first_cross(d, w0, w1, f * peak)? / fs)
            })
            .collect()
    };
    let k121 = smooth(&da, &[1.0, 2.0, 1.0]);
    let k12321 = smooth(&da, &[1.0, 2.0, 3.0, 2.0, 1.0]);
    let k7 = smooth(&da, &[1.0, 2.0, 3.0, 4.0, 3.0, 2.0, 1.0]);
    let gauss = |sd: f64| -> Vec<f64> {
        let h = (3.0 * sd).ceil() as i32;
        (-h..=h)
            .map(|j| (-(j * j) as f64 / (2.0 * sd * sd)).exp())
            .collect()
    };
    let kg = smooth(&da, &gauss(1.5));
    let mut out: Vec<(String, Vec<f64>)> = vec![
        ("[1 2 3 2 1] onset 0.5".into(), keep(onset(&k12321, 0.5))),
        ("[1 2 3 2 1] onset 0.4".into(), keep(onset(&k12321, 0.4))),
        ("[1 2 3 2 1] onset 0.6".into(), keep(onset(&k12321, 0.6))),
        ("[1 2 3 4 3 2 1] onset 0.5".into(), keep(onset(&k7, 0.5))),
        (
            "Gaussian σ 1.5 samples onset 0.5".into(),
            keep(onset(&kg, 0.5)),
        ),
    ];
    for sd in [1.0, 2.0, 2.5, 3.0] {
        let k = smooth(&da, &gauss(sd));
        out.push((
            format!("Gaussian σ {sd} samples onset 0.5"),
            keep(onset(&k, 0.5)),
        ));
    }
    let k9 = smooth(&da, &[1.0, 2.0, 3.0, 4.0, 5.0, 4.0, 3.0, 2.0, 1.0]);
    out.push((
        "[1 2 3 4 5 4 3 2 1] onset 0.5".into(),
        keep(onset(&k9, 0.5)),
    ));
    for f in [0.4, 0.6] {
        out.push((format!("[1 2 3 4 3 2 1] onset {f}"), keep(onset(&k7, f))));
    }
    let each: Vec<Vec<Option<f64>>> = [0.3, 0.4, 0.5, 0.6, 0.7]
        .iter()
        .map(|&f| onset(&k12321, f))
        .collect();
    out.push((
        "[1 2 3 2 1] onsets 0.3–0.7 (5) averaged".into(),
        keep(
            (0..zc0.len())
                .map(|i| {
                    let v: Option<Vec<f64>> = each.iter().map(|e| e[i]).collect();
                    v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
                })
                .collect(),
        ),
    ));
    for k in [3.0, 6.0, 10.0] {
        out.push((
            format!("[1 2 1] onset at {k} × the swing's median |Δa| (≤ ½ peak)"),
            keep(
                zc0.iter()
                    .map(|&z| {
                        let (w0, w1, base, peak) = window(&da, &k121, fs, z, t)?;
                        Some(first_cross(&k121, w0, w1, (k * base).min(0.5 * peak))? / fs)
                    })
                    .collect(),
            ),
        ));
    }
    let up = 8;
    let slope = spline_slope(&s.acc, up);
    out.push((
        "|a′| of a cubic spline at 8 × onset 0.5".into(),
        keep(
            zc0.iter()
                .map(|&z| {
                    let (w0, w1, _, _) = window(&da, &k121, fs, z, t)?;
                    // The change d[i] spans samples i − 1 … i.
                    let (f0, f1) = ((w0 - 1) * up, w1 * up);
                    let peak = slope[f0..=f1].iter().copied().fold(0.0, f64::max);
                    Some(first_cross(&slope, f0 + 1, f1, 0.5 * peak)? / (fs * up as f64))
                })
                .collect(),
        ),
    ));
    let shipped: Vec<Option<f64>> = s.hs.iter().map(|h| Some(h - s.t0())).collect();
    let comps: Vec<Vec<f64>> = (0..3)
        .map(|k| {
            (0..da.len())
                .map(|i| {
                    if i == 0 {
                        0.0
                    } else {
                        s.acc[k][i] - s.acc[k][i - 1]
                    }
                })
                .collect()
        })
        .collect();
    out.push((
        "shipped, aligned to the mean |Δa| waveform".into(),
        keep(align(std::slice::from_ref(&da), &shipped, fs)),
    ));
    out.push((
        "shipped, aligned to the mean signed Δa waveform (3 axes)".into(),
        keep(align(&comps, &shipped, fs)),
    ));
    let acc_hp: Vec<Vec<f64>> = s.acc.to_vec();
    out.push((
        "shipped, aligned to the mean acceleration waveform (3 axes)".into(),
        keep(align(&acc_hp, &shipped, fs)),
    ));
    out
}

/// SD (ms) on one half of ldh's strikes `hs` against `reference`, and ldh's own by the hat.
fn half_scores(hs: &[f64], s: &Shank, tune: bool) -> [f64; 3] {
    let lo = half_sd(hs, &s.opto, tune);
    let lh = half_sd(hs, &s.heel, tune);
    let ho = half_sd(&s.heel, &s.opto, tune);
    [
        lo,
        lh,
        (0.5 * (lo * lo + lh * lh - ho * ho)).max(0.0).sqrt(),
    ]
}

/// Every candidate (`precision.rs`'s and this module's) scored on each half against OptoGait,
/// against the heel sensor, and ldh's own by the hat; printed, and the shipped rule's returned.
#[test]
fn hs_own_precision_candidates_on_tripod() {
    let Some(dir) = tripod_dir() else {
        println!("skipped: ../shared/realdata/tripod not found (set LDH_REALDATA)");
        return;
    };
    let sh = shanks(&dir);
    let cands: Vec<Vec<(String, Vec<f64>)>> = sh
        .iter()
        .map(|s| {
            let mut c = candidates(s);
            c.extend(more_candidates(s));
            c
        })
        .collect();
    println!(
        "\n| rule | {} | mean vs OptoGait tune / report | mean vs heel tune / report | mean own (hat) tune / report |",
        sh.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(" | ")
    );
    println!("|---|{}---|---|---|", "---|".repeat(sh.len()));
    for (j, (name, _)) in cands[0].iter().enumerate() {
        let (mut m, mut cells) = ([[0.0; 3]; 2], vec![]);
        for (s, c) in sh.iter().zip(&cands) {
            let (a, b) = (
                half_scores(&c[j].1, s, true),
                half_scores(&c[j].1, s, false),
            );
            for k in 0..3 {
                m[0][k] += a[k] / sh.len() as f64;
                m[1][k] += b[k] / sh.len() as f64;
            }
            cells.push(format!(
                "{:.1} / {:.1} (heel {:.1} / {:.1})",
                a[0], b[0], a[1], b[1]
            ));
        }
        println!(
            "| {name} | {} | {:.2} / {:.2} | {:.2} / {:.2} | {:.2} / {:.2} |",
            cells.join(" | "),
            m[0][0],
            m[1][0],
            m[0][1],
            m[1][1],
            m[0][2],
            m[1][2]
        );
    }
}
