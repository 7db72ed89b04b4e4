//! Shapiro-Wilk W test: Royston (1995), Algorithm AS R94, line by line as
//! scipy's `swilk` (scipy/stats/_ansari_swilk_statistics.pyx). statrs has
//! no Shapiro-Wilk test, so it is written here.

use serde::{Deserialize, Serialize};

use super::{check_finite, StatsError};

/// Result of [`shapiro`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapiroResult {
    /// The W statistic (in (0, 1]).
    pub statistic: f64,
    /// p-value for the null hypothesis that the data are normal.
    pub pvalue: f64,
    /// `true` when n > 5000: AS R94's p-value approximation was fitted up
    /// to n = 5000 (scipy warns "computed p-value may not be accurate").
    pub large_sample: bool,
}

/// Shapiro-Wilk test for normality, equal to `scipy.stats.shapiro(x)`.
///
/// Royston's AS R94 approximation of the coefficients and of the p-value
/// (normalising transformations for 4 ≤ n ≤ 11 and n ≥ 12); for n = 3 the
/// p-value is exact: p = 1 − (6/π)·acos(√W), with W clamped at 0.75 (p = 0).
/// For n > 5000 the result is still computed, but `large_sample` is set
/// (scipy warns that the p-value may be inaccurate).
///
/// Errors: n < 3 ([`StatsError::TooFewObservations`]; scipy returns NaN);
/// NaN / ±inf ([`StatsError::NonFinite`]); zero range
/// ([`StatsError::ConstantInput`]; scipy warns and returns W = 1, p = 1).
pub fn shapiro(x: &[f64]) -> Result<ShapiroResult, StatsError> {
    let n = x.len();
    if n < 3 {
        return Err(StatsError::TooFewObservations {
            test: "shapiro",
            needed: 3,
            got: n,
            what: "",
        });
    }
    check_finite("shapiro", "x", x)?;
    // scipy: y = sort(x); y -= x[N//2]  (x in input order; see scipy gh-15777)
    let shift = x[n / 2];
    let mut y: Vec<f64> = x.to_vec();
    y.sort_by(f64::total_cmp);
    for v in &mut y {
        *v -= shift;
    }
    let (w, pw) = swilk(&y).ok_or_else(|| StatsError::ConstantInput {
        test: "shapiro",
        detail: format!("all {n} values equal {:?}", x[0]),
    })?;
    Ok(ShapiroResult {
        statistic: w,
        pvalue: pw,
        large_sample: n > 5000,
    })
}

const C1: [f64; 6] = [
    0.0,
    0.221157,
    -0.147981,
    -0.207119e1,
    0.4434685e1,
    -0.2706056e1,
];
const C2: [f64; 6] = [
    0.0,
    0.42981e-1,
    -0.293762,
    -0.1752461e1,
    0.5682633e1,
    -0.3582633e1,
];
const C3: [f64; 4] = [0.5440, -0.39978, 0.25054e-1, -0.6714e-3];
const C4: [f64; 4] = [0.13822e1, -0.77857, 0.62767e-1, -0.20322e-2];
const C5: [f64; 4] = [-0.15861e1, -0.31082, -0.83751e-1, 0.38915e-2];
const C6: [f64; 3] = [-0.4803, -0.82676e-1, 0.30302e-2];
const G: [f64; 2] = [-0.2273e1, 0.459];
const SMALL: f64 = 1e-19;

/// AS R94 on sorted data (no censoring). `None` when the range is zero.
fn swilk(x: &[f64]) -> Option<(f64, f64)> {
    let n = x.len();
    let nn2 = n / 2;
    let an = n as f64;
    let mut a = vec![0.0; nn2];

    // coefficients
    if n == 3 {
        a[0] = std::f64::consts::FRAC_1_SQRT_2;
    } else {
        let an25 = an + 0.25;
        let mut summ2 = 0.0;
        for (i, ai) in a.iter_mut().enumerate() {
            let m = ppnd(((i + 1) as f64 - 0.375) / an25);
            *ai = m;
            summ2 += m * m;
        }
        summ2 *= 2.0;
        let ssumm2 = summ2.sqrt();
        let rsn = 1.0 / an.sqrt();
        let a1 = poly(&C1, rsn) - a[0] / ssumm2;
        let (i1, fac) = if n > 5 {
            let a2 = -a[1] / ssumm2 + poly(&C2, rsn);
            let fac = ((summ2 - 2.0 * a[0] * a[0] - 2.0 * a[1] * a[1])
                / (1.0 - 2.0 * a1 * a1 - 2.0 * a2 * a2))
                .sqrt();
            a[1] = a2;
            (2, fac)
        } else {
            let fac = ((summ2 - 2.0 * a[0] * a[0]) / (1.0 - 2.0 * a1 * a1)).sqrt();
            (1, fac)
        };
        a[0] = a1;
        for ai in a.iter_mut().take(nn2).skip(i1) {
            *ai *= -1.0 / fac;
        }
    }

    let range = x[n - 1] - x[0];
    if range < SMALL {
        return None;
    }

    // signed coefficient of the ind1-th order statistic (ind2 = n-1-ind1)
    let coef = |ind1: usize, ind2: usize| -> f64 {
        if ind1 < ind2 {
            -a[ind1]
        } else {
            a[ind2]
        }
    };

    let mut sx = x[0] / range;
    let mut sa = -a[0];
    for (ind1, &xi) in x.iter().enumerate().skip(1) {
        let ind2 = n - 1 - ind1;
        sx += xi / range;
        if ind1 != ind2 {
            sa += coef(ind1, ind2);
        }
    }
    sa /= an;
    sx /= an;
    let (mut ssa, mut ssx, mut sax) = (0.0, 0.0, 0.0);
    for (ind1, &xi) in x.iter().enumerate() {
        let ind2 = n - 1 - ind1;
        let asa = if ind1 != ind2 {
            coef(ind1, ind2) - sa
        } else {
            -sa
        };
        let xsx = xi / range - sx;
        ssa += asa * asa;
        ssx += xsx * xsx;
        sax += asa * xsx;
    }
    let ssassx = (ssa * ssx).sqrt();
    let w1 = (ssassx - sax) * (ssassx + sax) / (ssa * ssx);
    let w = 1.0 - w1;

    // significance level (exact for n = 3)
    if n == 3 {
        if w < 0.75 {
            return Some((0.75, 0.0));
        }
        let pi6 = 6.0 / std::f64::consts::PI;
        return Some((w, 1.0 - pi6 * w.sqrt().acos()));
    }

    let mut y = w1.ln();
    let xx = an.ln();
    let (m, s) = if n <= 11 {
        let gamma = poly(&G, an);
        if y >= gamma {
            return Some((w, SMALL));
        }
        y = -(gamma - y).ln();
        (poly(&C3, an), poly(&C4, an).exp())
    } else {
        (poly(&C5, xx), poly(&C6, xx).exp())
    };
    Some((w, alnorm_upper((y - m) / s)))
}

/// c[0] + c[1] x + c[2] x² + ... (AS R94 `POLY`).
fn poly(c: &[f64], x: f64) -> f64 {
    let nord = c.len();
    let mut res = c[0];
    if nord == 1 {
        return res;
    }
    let mut p = x * c[nord - 1];
    if nord == 2 {
        return res + p;
    }
    for &ci in c[1..nord - 1].iter().rev() {
        p = (p + ci) * x;
    }
    res += p;
    res
}

/// Upper normal tail, Algorithm AS 66 (Hill 1973) as in scipy's `_alnorm`
/// (kept instead of an exact erfc so that p-values match scipy bit for bit).
fn alnorm_upper(x: f64) -> f64 {
    const A1: f64 = 0.398942280444;
    const A2: f64 = 0.399903438504;
    const A3: f64 = 5.75885480458;
    const A4: f64 = 29.8213557808;
    const A5: f64 = 2.62433121679;
    const A6: f64 = 48.6959930692;
    const A7: f64 = 5.92885724438;
    const B1: f64 = 0.398942280385;
    const B2: f64 = 3.8052e-8;
    const B3: f64 = 1.00000615302;
    const B4: f64 = 3.98064794e-4;
    const B5: f64 = 1.98615381364;
    const B6: f64 = 0.151679116635;
    const B7: f64 = 5.29330324926;
    const B8: f64 = 4.8385912808;
    const B9: f64 = 15.1508972451;
    const B10: f64 = 0.742380924027;
    const B11: f64 = 30.789933034;
    const B12: f64 = 3.99019417011;
    const LTONE: f64 = 7.0;
    const UTZERO: f64 = 38.0;
    const CON: f64 = 1.28;

    let mut upper = true;
    let mut z = x;
    // `!(z > 0)` in AS 66 (also catches NaN, which cannot occur here)
    if z.is_nan() || z <= 0.0 {
        upper = false;
        z = -z;
    }
    if !(z <= LTONE || (upper && z <= UTZERO)) {
        return if upper { 0.0 } else { 1.0 };
    }
    let y = 0.5 * z * z;
    let temp = if z <= CON {
        0.5 - z * (A1 - A2 * y / (y + A3 - A4 / (y + A5 + A6 / (y + A7))))
    } else {
        B1 * (-y).exp()
            / (z - B2
                + B3 / (z + B4 + B5 / (z - B6 + B7 / (z + B8 - B9 / (z + B10 + B11 / (z + B12))))))
    };
    if upper {
        temp
    } else {
        1.0 - temp
    }
}

/// Normal quantile, Algorithm AS 111 (Beasley & Springer 1977), as scipy's `_ppnd`.
fn ppnd(p: f64) -> f64 {
    const A0: f64 = 2.50662823884;
    const A1: f64 = -18.61500062529;
    const A2: f64 = 41.39119773534;
    const A3: f64 = -25.44106049637;
    const B1: f64 = -8.47351093090;
    const B2: f64 = 23.08336743743;
    const B3: f64 = -21.06224101826;
    const B4: f64 = 3.13082909833;
    const C0: f64 = -2.78718931138;
    const C1: f64 = -2.29796479134;
    const C2: f64 = 4.85014127135;
    const C3: f64 = 2.32121276858;
    const D1: f64 = 3.54388924762;
    const D2: f64 = 1.63706781897;
    const SPLIT: f64 = 0.42;

    let q = p - 0.5;
    if q.abs() <= SPLIT {
        let r = q * q;
        let num = q * (((A3 * r + A2) * r + A1) * r + A0);
        return num / ((((B4 * r + B3) * r + B2) * r + B1) * r + 1.0);
    }
    let mut r = if q > 0.0 { 1.0 - p } else { p };
    if r > 0.0 {
        r = (-r.ln()).sqrt();
    } else {
        return 0.0;
    }
    let temp = (((C3 * r + C2) * r + C1) * r + C0) / ((D2 * r + D1) * r + 1.0);
    if q < 0.0 {
        -temp
    } else {
        temp
    }
}
