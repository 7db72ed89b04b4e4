//! Minimal FFT used only to reproduce nolds' default `lag` and `min_tsep` in
//! [`super::lyap_r`] (both come from `np.fft.rfft(data, 2n − 1)`).
//!
//! Hand written on purpose: none of the crates the host workspace already builds
//! provides an FFT, and the two uses here (an iterative radix-2 transform and
//! Bluestein's chirp-z algorithm for the odd length 2n − 1) are ~80 lines.

use std::f64::consts::PI;

#[derive(Clone, Copy, Debug, Default)]
struct C {
    re: f64,
    im: f64,
}

impl C {
    fn mul(self, o: C) -> C {
        C {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
    fn conj(self) -> C {
        C {
            re: self.re,
            im: -self.im,
        }
    }
}

/// In-place iterative radix-2 FFT; `a.len()` must be a power of two.
/// `inverse` uses the positive exponent and does not scale.
fn fft_pow2(a: &mut [C], inverse: bool) {
    let n = a.len();
    if n <= 1 {
        return;
    }
    let mut j = 0usize;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            a.swap(i, j);
        }
    }
    let sign = if inverse { 1.0 } else { -1.0 };
    let mut len = 2;
    while len <= n {
        let ang = sign * 2.0 * PI / len as f64;
        let half = len / 2;
        // twiddles computed directly (not by recurrence) for accuracy
        let tw: Vec<C> = (0..half)
            .map(|k| {
                let t = ang * k as f64;
                C {
                    re: t.cos(),
                    im: t.sin(),
                }
            })
            .collect();
        for start in (0..n).step_by(len) {
            for k in 0..half {
                let u = a[start + k];
                let v = a[start + k + half].mul(tw[k]);
                a[start + k] = C {
                    re: u.re + v.re,
                    im: u.im + v.im,
                };
                a[start + k + half] = C {
                    re: u.re - v.re,
                    im: u.im - v.im,
                };
            }
        }
        len <<= 1;
    }
}

/// |DFT|² of `x` zero-padded to length `l` (any `l ≥ x.len()`), bins `0..nbins`,
/// by Bluestein's algorithm.
fn power_spectrum_bluestein(x: &[f64], l: usize, nbins: usize) -> Vec<f64> {
    let p = (2 * l - 1).next_power_of_two();
    // chirp w_k = exp(-iπk²/l); k² reduced mod 2l to keep the angle accurate
    let chirp: Vec<C> = (0..l)
        .map(|k| {
            let kk = ((k as u128 * k as u128) % (2 * l as u128)) as f64;
            let t = -PI * kk / l as f64;
            C {
                re: t.cos(),
                im: t.sin(),
            }
        })
        .collect();
    let mut a = vec![C::default(); p];
    for (k, &v) in x.iter().enumerate() {
        a[k] = C {
            re: v * chirp[k].re,
            im: v * chirp[k].im,
        };
    }
    let mut b = vec![C::default(); p];
    b[0] = chirp[0].conj();
    for k in 1..l {
        b[k] = chirp[k].conj();
        b[p - k] = chirp[k].conj();
    }
    fft_pow2(&mut a, false);
    fft_pow2(&mut b, false);
    for (u, v) in a.iter_mut().zip(&b) {
        *u = u.mul(*v);
    }
    fft_pow2(&mut a, true);
    let scale = 1.0 / p as f64;
    (0..nbins)
        .map(|k| {
            let y = C {
                re: a[k].re * scale,
                im: a[k].im * scale,
            }
            .mul(chirp[k]);
            y.re * y.re + y.im * y.im
        })
        .collect()
}

/// Linear (non-circular, unnormalised, mean not removed) autocorrelation
/// `r[τ] = Σ_t x[t]·x[t+τ]` for `τ = 0..n`, as nolds obtains it from
/// `irfft(f·conj(f))` with `f = rfft(x, 2n − 1)`.
pub(crate) fn autocorrelation(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    let p = (2 * n - 1).max(1).next_power_of_two();
    let mut a = vec![C::default(); p];
    for (k, &v) in x.iter().enumerate() {
        a[k].re = v;
    }
    fft_pow2(&mut a, false);
    for v in a.iter_mut() {
        *v = C {
            re: v.re * v.re + v.im * v.im,
            im: 0.0,
        };
    }
    fft_pow2(&mut a, true);
    a[..n].iter().map(|c| c.re / p as f64).collect()
}

/// nolds' mean frequency (cycles per sample): the power-weighted mean of
/// `rfftfreq(2n − 1)` over the bins `1..n` of `|rfft(x, 2n − 1)|²`.
pub(crate) fn mean_frequency(x: &[f64]) -> f64 {
    let n = x.len();
    let l = 2 * n - 1;
    let psd = power_spectrum_bluestein(x, l, n);
    let mut num = Vec::with_capacity(n);
    for (k, &p) in psd.iter().enumerate().skip(1) {
        num.push(k as f64 / l as f64 * p);
    }
    super::neighbours::np_sum(&num) / super::neighbours::np_sum(&psd[1..])
}
