//! The Butterworth low-pass as second-order sections and zero-phase filtering with
//! `scipy.signal.sosfiltfilt`'s padding (sci-rs `butter_dyn`; sci-rs `sosfiltfilt_dyn`'s
//! operations written out, [`sosfiltfilt`]).

use super::PreprocessParams;
use crate::error::{LdhError, Result};
use sci_rs::signal::filter::design::{
    butter_dyn, DigitalFilter, FilterBandType, FilterOutputType, Sos,
};
use sci_rs::signal::filter::sosfilt_zi_dyn;

/// Smallest and largest cut-off as a fraction of the Nyquist frequency `fs/2` that
/// [`butterworth_lowpass_sos`] accepts. Beyond about 1e-13 from either end sci-rs's design
/// panics (found by fuzzing: a recording claiming 1e74 Hz); well before that the sections lose
/// their precision, and no IMU analysis filters that close to 0 or to Nyquist.
pub const BUTTERWORTH_WN_RANGE: (f64, f64) = (1e-6, 1.0 - 1e-6);

/// Second-order sections of a Butterworth low-pass (scipy `butter(order, cutoff_hz,
/// output='sos', fs=fs_hz)`).
///
/// Errors unless `fs_hz` and `cutoff_hz` are finite and positive, `order` is 1–20 and the
/// normalised cut-off `cutoff_hz / (fs_hz / 2)` lies in [`BUTTERWORTH_WN_RANGE`].
pub fn butterworth_lowpass_sos(order: usize, cutoff_hz: f64, fs_hz: f64) -> Result<Vec<Sos<f64>>> {
    if !(fs_hz.is_finite() && fs_hz > 0.0) {
        return Err(LdhError::param("fs_hz", fs_hz, "must be finite and > 0"));
    }
    if !(1..=20).contains(&order) {
        return Err(LdhError::param("filter_order", order, "must be 1–20"));
    }
    let wn = cutoff_hz / (fs_hz / 2.0);
    let (lo, hi) = BUTTERWORTH_WN_RANGE;
    if !(cutoff_hz.is_finite() && wn >= lo && wn <= hi) {
        return Err(LdhError::param(
            "cutoff_hz",
            cutoff_hz,
            format!(
                "is {wn:e} of the Nyquist frequency fs/2 = {} Hz; the Butterworth design needs {lo:e}–{hi} of it (is the sampling rate right?)",
                fs_hz / 2.0
            ),
        ));
    }
    match butter_dyn(
        order,
        vec![cutoff_hz],
        Some(FilterBandType::Lowpass),
        Some(false),
        Some(FilterOutputType::Sos),
        Some(fs_hz),
    ) {
        DigitalFilter::Sos(s) => Ok(s.sos),
        _ => unreachable!("butter_dyn returns SOS when asked for SOS"),
    }
}

/// Zero-phase filtering with `sos`, as `scipy.signal.sosfiltfilt(sos, x)` (odd padding of
/// `3 · (2 · sections + 1)` samples). Errors when `x` is not longer than the padding (scipy
/// raises; sci-rs would panic).
pub fn sosfiltfilt(sos: &[Sos<f64>], x: &[f64]) -> Result<Vec<f64>> {
    let [y] = sosfiltfilt_each(sos, [x])?;
    Ok(y)
}

/// [`sosfiltfilt`] of each of `xs`, the first error as calling it on each in turn would give.
/// Channels of equal length are filtered side by side: each section's recursion is a chain of
/// dependent operations, so one channel at a time waits on its latency, and `N` at once hide
/// it (the operations of each channel are the same, in the same order: the same bits).
pub fn sosfiltfilt_each<const N: usize>(
    sos: &[Sos<f64>],
    xs: [&[f64]; N],
) -> Result<[Vec<f64>; N]> {
    let padlen = 3 * (2 * sos.len() + 1);
    for x in xs {
        if x.len() <= padlen {
            return Err(LdhError::signal(
                "sosfiltfilt",
                format!(
                    "signal of {} samples is too short: at least {} are needed",
                    x.len(),
                    padlen + 1
                ),
            ));
        }
        if let Some(i) = crate::recording::first_non_finite(x) {
            return Err(LdhError::signal(
                "sosfiltfilt",
                format!("non-finite value at sample {i}"),
            ));
        }
    }
    if xs.iter().all(|x| x.len() == xs[0].len()) {
        Ok(zero_phase(sos, xs))
    } else {
        Ok(xs.map(|x| {
            let [y] = zero_phase(sos, [x]);
            y
        }))
    }
}

/// sci-rs `sosfiltfilt_dyn(x, sos)` bit for bit on each of `xs` (of equal length, longer than
/// the padding): the same odd extension, initial conditions (sci-rs `sosfilt_zi_dyn`) and
/// per-section operations in the same order. Written out because sci-rs builds the extension
/// as an `nalgebra` matrix (zeroed, then filled), collects each pass into a new vector and
/// filters one channel at a time (issue 17).
fn zero_phase<const N: usize>(sos: &[Sos<f64>], xs: [&[f64]; N]) -> [Vec<f64>; N] {
    // sci-rs: 2 · sections + 1 taps, less one per section that is first order in both b and a
    let bzeros = sos.iter().filter(|s| s.b[2] == 0.0).count();
    let azeros = sos.iter().filter(|s| s.a[2] == 0.0).count();
    let edge = 3 * (2 * sos.len() + 1 - bzeros.min(azeros));
    let n = xs[0].len();
    let mut init = sos.to_vec();
    sosfilt_zi_dyn::<_, _, Sos<f64>>(init.iter_mut());
    let zi: Vec<[f64; 2]> = init.iter().map(|s| [s.zi0, s.zi1]).collect();
    // odd extension, the channels side by side: 2 x₀ − x[edge − i] before, the signal, then
    // 2 x_last − x[last − edge + i] (reversed)
    let mut ext: Vec<[f64; N]> = Vec::with_capacity(n + 2 * edge);
    ext.extend((0..edge).map(|i| std::array::from_fn(|c| 2.0 * xs[c][0] - xs[c][edge - i])));
    ext.extend((0..n).map(|i| std::array::from_fn(|c| xs[c][i])));
    ext.extend(
        (0..edge)
            .rev()
            .map(|i| std::array::from_fn(|c| 2.0 * xs[c][n - 1] - xs[c][n - 1 - edge + i])),
    );
    // forward, in place, from zi · ext[0]
    sosfilt_in_place(sos, &zi, ext[0], ext.iter_mut());
    // backward from zi · (the forward pass's last value), in place, then the signal's part
    let y0 = ext[ext.len() - 1];
    sosfilt_in_place(sos, &zi, y0, ext.iter_mut().rev());
    std::array::from_fn(|c| ext[edge..edge + n].iter().map(|v| v[c]).collect())
}

/// sci-rs `sosfilt_dyn` over `values` (`N` channels side by side), each replaced by its
/// output, every section's state starting at its `zi` times the channel's `scale`: per section
/// x' = b₀ x + z₀, z₀ = b₁ x − a₁ x' + z₁, z₁ = b₂ x − a₂ x' (transposed direct form II),
/// evaluated in that order. The usual section counts (filter orders 2–10) run with the count
/// fixed at compile time, so the states stay in registers.
fn sosfilt_in_place<'a, const N: usize>(
    sos: &[Sos<f64>],
    zi: &[[f64; 2]],
    scale: [f64; N],
    values: impl Iterator<Item = &'a mut [f64; N]>,
) {
    match sos.len() {
        1 => sections::<1, N>(sos, zi, scale, values),
        2 => sections::<2, N>(sos, zi, scale, values),
        3 => sections::<3, N>(sos, zi, scale, values),
        4 => sections::<4, N>(sos, zi, scale, values),
        5 => sections::<5, N>(sos, zi, scale, values),
        _ => {
            let mut z: Vec<[[f64; N]; 2]> = zi.iter().map(|z| start(z, &scale)).collect();
            for v in values {
                for (s, z) in sos.iter().zip(z.iter_mut()) {
                    section(&s.b, &s.a, z, v);
                }
            }
        }
    }
}

/// [`sosfilt_in_place`] with `S` sections.
fn sections<'a, const S: usize, const N: usize>(
    sos: &[Sos<f64>],
    zi: &[[f64; 2]],
    scale: [f64; N],
    values: impl Iterator<Item = &'a mut [f64; N]>,
) {
    let coef: [([f64; 3], [f64; 3]); S] = std::array::from_fn(|k| (sos[k].b, sos[k].a));
    let mut z: [[[f64; N]; 2]; S] = std::array::from_fn(|k| start(&zi[k], &scale));
    for v in values {
        for ((b, a), z) in coef.iter().zip(z.iter_mut()) {
            section(b, a, z, v);
        }
    }
}

/// A section's initial state: `zi` times each channel's `scale`.
#[inline(always)]
fn start<const N: usize>(zi: &[f64; 2], scale: &[f64; N]) -> [[f64; N]; 2] {
    [0, 1].map(|j| std::array::from_fn(|c| zi[j] * scale[c]))
}

/// One sample of one section on each channel: `x` becomes the section's output.
#[inline(always)]
fn section<const N: usize>(b: &[f64; 3], a: &[f64; 3], z: &mut [[f64; N]; 2], x: &mut [f64; N]) {
    for c in 0..N {
        let y = b[0] * x[c] + z[0][c];
        z[0][c] = b[1] * x[c] - a[1] * y + z[1][c];
        z[1][c] = b[2] * x[c] - a[2] * y;
        x[c] = y;
    }
}

/// Butterworth low-pass, zero phase: `sosfiltfilt(butter(order, cutoff_hz, fs=fs_hz,
/// output='sos'), x)`.
pub fn butter_filtfilt(x: &[f64], order: usize, cutoff_hz: f64, fs_hz: f64) -> Result<Vec<f64>> {
    let p = PreprocessParams::default()
        .filter_order(order)
        .cutoff_hz(cutoff_hz)
        .check(fs_hz)?;
    sosfiltfilt(&p.sos, x)
}
