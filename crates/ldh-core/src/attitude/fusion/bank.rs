//! The bank of filters (paper eq. 15) stepped four filters at a time ([`super::lanes`]): each
//! lane runs the step of one filter with the operations of the scalar filter, so the numbers
//! are those of four separate filters bit for bit; a gated-out measurement keeps the lane's
//! prediction by a per-lane selection instead of a branch.

use super::lanes::{array, Num, L4, LANES};
use super::products::{self, Mat};
use super::{acc_tilt, predict_n, Model, Sample, SinCos, M5, V5};

/// Up to four filters side by side (a bank of n filters has ⌈n / 4⌉ groups; the unused lanes
/// of the last one repeat its first filter and are never read).
#[derive(Clone)]
pub(super) struct FilterGroup {
    /// The filtered states, what the smoother stores of each step (one copy).
    pub(super) f: Filtered,
    /// The diagonal of the adapted R (its off-diagonal stays 0).
    r: [L4; 2],
    gate2: L4,
    logw: L4,
    rejected: [usize; LANES],
}

/// One group's filtered states (with the sines and cosines of their tilt) and covariances:
/// what the smoother keeps of every step, kept together so that the store copies it in one
/// block (its fields copied one by one went through three `memcpy` calls and a copy on the
/// stack) and the backward pass reads it in one descending stream.
#[derive(Clone, Copy)]
pub(super) struct Filtered {
    pub(super) x: [L4; 5],
    /// [`SinCos::of`] the tilt of `x`.
    pub(super) sc: SinCos<L4>,
    pub(super) p: Mat<L4>,
}

impl FilterGroup {
    /// Predict to sample k (none at k = 0) and update with its tilt in the lanes that do not
    /// gate it out; `d_k` is the Sage–Husa weight of this sample.
    #[inline(always)]
    fn step(&mut self, m: &Model, s: &Sample, k: usize, d_k: f64) {
        let p = m.p;
        let sp = L4::splat;
        let (xp, pp) = if k == 0 {
            (self.f.x, self.f.p)
        } else {
            let (xp, pp, _) = predict_n(&self.f.x, &self.f.sc, &self.f.p, &s.wm, m.dt, &m.q);
            (xp, pp)
        };
        // H selects (φ, θ): H x, H P Hᵀ and P Hᵀ are sub-blocks (bit for bit, see products)
        let nu = [(sp(s.z[0]) - xp[0]).wrap(), (sp(s.z[1]) - xp[1]).wrap()];
        let infl = sp(s.infl);
        let mut rk = [self.r[0] * infl, self.r[1] * infl];
        if s.anchor {
            // Gravity re-acquisition: the tilt is trusted to σ_anchor per window.
            for r in rk.iter_mut() {
                *r = r.map(|v| v.min(m.r_anchor));
            }
        }
        // S = H P Hᵀ + R (R's off-diagonal: 0 · inflation) and nalgebra's 2 × 2 inverse
        let r01 = sp(0.0) * infl;
        let sm = [
            [pp[0][0] + rk[0], pp[0][1] + r01],
            [pp[1][0] + r01, pp[1][1] + rk[1]],
        ];
        let det = sm[0][0] * sm[1][1] - sm[1][0] * sm[0][1];
        let invertible = det.0.map(|d| d != 0.0);
        let (s_inv, fallback) = (
            [
                [sm[1][1] / det, -sm[0][1] / det],
                [-sm[1][0] / det, sm[0][0] / det],
            ],
            [[sp(1.0 / m.r0), sp(0.0)], [sp(0.0), sp(1.0 / m.r0)]],
        );
        let s_inv: [[L4; 2]; 2] =
            array(|i| array(|j| L4::select(invertible, s_inv[i][j], fallback[i][j])));
        let row = [
            nu[0] * s_inv[0][0] + nu[1] * s_inv[1][0],
            nu[0] * s_inv[0][1] + nu[1] * s_inv[1][1],
        ];
        let d2 = row[0] * nu[0] + row[1] * nu[1];
        let det = det.map(|d| d.max(1e-300));
        let ll = det.zip(d2, |det, d2| {
            -0.5 * d2 - 0.5 * (det * (std::f64::consts::TAU).powi(2)).ln()
        });
        self.logw = self.logw + ll;
        let accept: [bool; LANES] = array(|l| {
            let reacquire = self.rejected[l] as f64 * m.dt >= p.reacquire_s;
            d2.0[l] <= self.gate2.0[l] || reacquire || s.anchor
        });
        let kg = products::gain(&pp, &s_inv);
        let xu: [L4; 5] = array(|i| xp[i] + (kg[i][0] * nu[0] + kg[i][1] * nu[1]));
        // the updated covariance straight into the filter's (the gated lanes get P_pred back)
        products::joseph_into(&pp, &kg, rk, &mut self.f.p);
        // Sage–Husa adaptation of R from quasi-static innovations.
        if s.dyn_dev < 2.0 * p.dynamic_scale_g {
            for i in 0..2 {
                let est = nu[i] * nu[i] - pp[i][i];
                let v = (sp(1.0 - d_k) * self.r[i] + sp(d_k) * est).map(|v| v.clamp(m.rlo, m.rhi));
                self.r[i] = L4::select(accept, v, self.r[i]);
            }
        }
        for (l, a) in accept.iter().enumerate() {
            self.rejected[l] = if *a { 0 } else { self.rejected[l] + 1 };
        }
        if accept.iter().all(|a| *a) {
            self.f.x = xu;
        } else {
            self.f.x = array(|i| L4::select(accept, xu[i], xp[i]));
            for (row, pp_row) in self.f.p.iter_mut().zip(&pp) {
                for (v, pv) in row.iter_mut().zip(pp_row) {
                    *v = L4::select(accept, *v, *pv);
                }
            }
        }
        self.f.x[2] = self.f.x[2].wrap();
        self.f.sc = SinCos::of_lanes(self.f.x[0], self.f.x[1]);
    }
}

/// [`FilterGroup::step`] of every group, in an AVX2 clone (4 lanes per instruction instead of SSE2's
/// 2; the same IEEE operations, so the same numbers) where the CPU has it.
#[multiversion::multiversion(targets("x86_64+avx2"))]
fn step_groups(groups: &mut [FilterGroup], m: &Model, s: &Sample, k: usize, d_k: f64) {
    for g in groups.iter_mut() {
        g.step(m, s, k, d_k);
    }
}

/// The bank of filters and its weights after the last step: everything the forward pass
/// carries from one sample to the next (a smoother checkpoint is a copy of it).
#[derive(Clone)]
pub(super) struct Bank {
    pub(super) groups: Vec<FilterGroup>,
    nf: usize,
    /// b^k, for the Sage–Husa weight d_k = (1 − b) / (1 − b^k).
    bpow: f64,
    pub(super) weights: Vec<f64>,
}

impl Bank {
    pub(super) fn new(m: &Model) -> Bank {
        let p = m.p;
        let (phi0, th0) = acc_tilt(m.f_at(0));
        let x0 = [phi0, th0, 0.0, 0.0, 0.0].map(L4::splat);
        let b0 = p.gyro_bias_sd_dps.to_radians().powi(2);
        let r0 = m.r0;
        let p0 = products::rows(&M5::from_diagonal(&V5::from_column_slice(&[
            r0, r0, 1e-6, b0, b0,
        ])))
        .map(|row| row.map(L4::splat));
        let gates = &p.gates_sigma;
        let groups = gates
            .chunks(LANES)
            .map(|g| FilterGroup {
                f: Filtered {
                    x: x0,
                    sc: SinCos::of_lanes(x0[0], x0[1]),
                    p: p0,
                },
                r: [L4::splat(r0); 2],
                gate2: L4(std::array::from_fn(|l| g.get(l).unwrap_or(&g[0]).powi(2))),
                logw: L4::splat(0.0),
                rejected: [0; LANES],
            })
            .collect();
        Bank {
            groups,
            nf: gates.len(),
            bpow: 1.0,
            weights: vec![0.0; gates.len()],
        }
    }

    /// Number of filters.
    pub(super) fn len(&self) -> usize {
        self.nf
    }

    /// The state of filter `i`.
    pub(super) fn state(&self, i: usize) -> V5 {
        let (g, l) = (&self.groups[i / LANES], i % LANES);
        V5::from_fn(|r, _| g.f.x[r].0[l])
    }

    /// State, sin/cos of the tilt and covariance of filter `i`.
    #[cfg(test)]
    pub(super) fn filter(&self, i: usize) -> (V5, SinCos, M5) {
        let (g, l) = (&self.groups[i / LANES], i % LANES);
        (
            self.state(i),
            g.f.sc.lane(l),
            M5::from_fn(|r, c| g.f.p[r][c].0[l]),
        )
    }

    /// The diagonal of filter `i`'s adapted R, rad².
    pub(super) fn tilt_noise(&self, i: usize) -> [f64; 2] {
        let (g, l) = (&self.groups[i / LANES], i % LANES);
        [g.r[0].0[l], g.r[1].0[l]]
    }

    /// Filter sample k with every filter and re-weight the bank.
    pub(super) fn step(&mut self, m: &Model, k: usize) {
        let s = m.sample(k);
        let b = m.p.forgetting;
        self.bpow *= b;
        let d_k = (1.0 - b) / (1.0 - self.bpow);
        step_groups(&mut self.groups, m, &s, k, d_k);
        self.reweight(m.p.min_weight);
    }

    /// Normalised likelihood weights with a floor (eq. 15); the filters' log-weights are reset
    /// to them.
    fn reweight(&mut self, floor: f64) {
        for (i, wi) in self.weights.iter_mut().enumerate() {
            *wi = self.groups[i / LANES].logw.0[i % LANES];
        }
        let mx = self.weights.iter().copied().fold(f64::MIN, f64::max);
        for wi in self.weights.iter_mut() {
            *wi = (*wi - mx).exp();
        }
        let w = &mut self.weights;
        let sum: f64 = w.iter().sum();
        w.iter_mut().for_each(|x| *x /= sum);
        w.iter_mut().for_each(|x| *x = x.max(floor));
        let sum: f64 = w.iter().sum();
        w.iter_mut().for_each(|x| *x /= sum);
        for (i, wi) in self.weights.iter().enumerate() {
            self.groups[i / LANES].logw.0[i % LANES] = wi.ln();
        }
    }
}
