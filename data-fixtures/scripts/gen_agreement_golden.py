#!/usr/bin/env python3
"""Generate the golden values for `ldh_core::agreement` (pingouin / scipy parity).

Usage (from the repository root, in a venv with pingouin):

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pingouin
    /tmp/venv/bin/python data-fixtures/scripts/gen_agreement_golden.py

Writes into `data-fixtures/golden/agreement/`:

* `agreement.json` — paired (ldh, reference) values of one parameter: limits of agreement
  and their confidence intervals (the formula of `pingouin.plot_blandaltman`, cross-checked
  against the lines and bands pingouin draws), proportional bias (`scipy.stats.linregress` of
  the difference on the mean), MAE, relative MAE, `pingouin.intraclass_corr` rows ICC(1,1),
  ICC(A,1) = ICC2, ICC(C,1) = ICC3 (CI95 unrounded), `scipy.stats.pearsonr`.
* `reliability.json` — subjects x trials tables: the same ICC rows (nan_policy="omit"), the
  mean squares of `pingouin.anova` (two-way, ss_type=2), the SD of all values, SEM, MDC95,
  the root-mean-square within-subject CV and the variance components (numpy).

Every file records the python / numpy / scipy / pingouin versions, and every case stores its
input, so the Rust tests need nothing but the JSON. Inputs come from
`numpy.random.default_rng(seed)` with fixed seeds and are rounded to 6 decimals (so the decimal
text parses to the same f64 in Rust and Python); NaN is written as the string "nan".
Cases marked `"expect_error": true` are those where pingouin / scipy give NaN, inf or raise;
the Rust side must return an `AgreementError` for them.
"""

import json
import math
import os
import platform
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pingouin as pg  # noqa: E402
import scipy  # noqa: E402
from scipy import stats  # noqa: E402

OUT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "golden", "agreement")

META = {
    "python": platform.python_version(),
    "numpy": np.__version__,
    "scipy": scipy.__version__,
    "pingouin": pg.__version__,
    "pandas": pd.__version__,
    "generator": "data-fixtures/scripts/gen_agreement_golden.py",
}

# pingouin rounds the CI95 column to 2 decimals by default; the goldens want it unrounded.
pg.options.pop("round.column.CI95", None)
pg.options["round"] = None


def r6(a):
    return [float(v) for v in np.round(np.asarray(a, dtype=float), 6)]


def jnum(v):
    v = float(v)
    if math.isnan(v):
        return "nan"
    return v


def jlist(a):
    return [jnum(v) for v in a]


def close(a, b, what, tol=1e-12):
    if not abs(a - b) <= tol * max(1.0, abs(b)):
        raise RuntimeError(f"{what}: {a!r} vs {b!r}")


# --------------------------------------------------------------------------- ICC
def icc_rows(wide):
    """pingouin.intraclass_corr on a subjects x raters array (NaN = missing, omitted)."""
    n, k = wide.shape
    long = pd.DataFrame(
        {
            "subject": np.repeat(np.arange(n), k),
            "rater": np.tile(np.arange(k), n),
            "value": wide.ravel(),
        }
    )
    res = pg.intraclass_corr(long, targets="subject", raters="rater", ratings="value",
                             nan_policy="omit").set_index("Type")
    out = {}
    for key, row in (("icc_1_1", "ICC(1,1)"), ("icc_2_1", "ICC(A,1)"), ("icc_3_1", "ICC(C,1)")):
        r = res.loc[row]
        out[key] = {
            "value": float(r["ICC"]),
            "f": float(r["F"]),
            "df1": float(r["df1"]),
            "df2": float(r["df2"]),
            "pvalue": float(r["pval"]),
            "ci_low": float(r["CI95"][0]),
            "ci_high": float(r["CI95"][1]),
        }
    return out


def anova_ms(wide):
    """Mean squares of pingouin.anova (two-way, no interaction) on the complete rows."""
    complete = wide[~np.isnan(wide).any(axis=1)]
    n, k = complete.shape
    long = pd.DataFrame(
        {
            "subject": np.repeat(np.arange(n), k),
            "trial": np.tile(np.arange(k), n),
            "value": complete.ravel(),
        }
    )
    with np.errstate(invalid="ignore"):
        aov = pg.anova(data=long, dv="value", between=["subject", "trial"], ss_type=2)
    msb, msj, mse = float(aov.at[0, "MS"]), float(aov.at[1, "MS"]), float(aov.at[2, "MS"])
    msw = (float(aov.at[1, "SS"]) + float(aov.at[2, "SS"])) / (
        float(aov.at[1, "DF"]) + float(aov.at[2, "DF"])
    )
    return complete, {"ms_subjects": msb, "ms_raters": msj, "ms_error": mse, "ms_within": msw}


# --------------------------------------------------------------------------- agreement
def bland_altman(x, y, agreement=1.96, confidence=0.95):
    """The numbers pingouin.plot_blandaltman draws, checked against its axes."""
    diff = x - y
    n = diff.size
    bias = np.mean(diff)
    sd = np.std(diff, ddof=1)
    high, low = bias + agreement * sd, bias - agreement * sd
    se_bias, se_loa = np.sqrt(sd**2 / n), np.sqrt(3 * sd**2 / n)
    ci_bias = stats.t.interval(confidence, n - 1, loc=bias, scale=se_bias)
    ci_high = stats.t.interval(confidence, n - 1, loc=high, scale=se_loa)
    ci_low = stats.t.interval(confidence, n - 1, loc=low, scale=se_loa)
    fig, ax = plt.subplots()
    pg.plot_blandaltman(x, y, agreement=agreement, confidence=confidence, ax=ax)
    drawn = [ln.get_ydata()[0] for ln in ax.lines]  # zero, bias, high, low
    for got, want, what in zip(drawn[1:], (bias, high, low), ("bias", "upper", "lower")):
        close(got, want, f"pingouin line {what}")
    for patch, (lo, hi), what in zip(ax.patches, (ci_bias, ci_high, ci_low),
                                     ("bias", "upper", "lower")):
        ys = patch.get_path().transformed(patch.get_patch_transform()).vertices[:, 1] \
            if hasattr(patch, "get_patch_transform") else patch.get_xy()[:, 1]
        close(min(ys), lo, f"pingouin band {what} low", 1e-9)
        close(max(ys), hi, f"pingouin band {what} high", 1e-9)
    plt.close(fig)
    return {
        "bias": bias, "sd_diff": sd, "lower": low, "upper": high,
        "bias_ci": list(ci_bias), "lower_ci": list(ci_low), "upper_ci": list(ci_high),
    }


def agreement_case(name, x, y, note=""):
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = ~(np.isnan(x) | np.isnan(y))
    xs, ys = x[keep], y[keep]
    la = bland_altman(xs, ys)
    means, diff = (xs + ys) / 2, xs - ys
    lr = stats.linregress(means, diff)
    pr = stats.pearsonr(xs, ys)
    case = {
        "name": name,
        "ldh": jlist(x),
        "reference": jlist(y),
        "expect_error": False,
        "n_pairs": int(keep.sum()),
        "n_dropped": int((~keep).sum()),
        "mean_ldh": float(np.mean(xs)),
        "mean_reference": float(np.mean(ys)),
        "limits": {k: (list(map(float, v)) if isinstance(v, list) else float(v))
                   for k, v in la.items()},
        "proportional_bias": {
            "slope": float(lr.slope), "intercept": float(lr.intercept),
            "rvalue": float(lr.rvalue), "pvalue": float(lr.pvalue),
            "stderr": float(lr.stderr), "intercept_stderr": float(lr.intercept_stderr),
        },
        "mae": float(np.mean(np.abs(diff))),
        "relative_mae": float(np.mean(np.abs(diff)) / np.mean(np.abs(ys))),
        "icc": icc_rows(np.column_stack([xs, ys])),
        "pearson_r": float(pr.statistic),
        "pearson_pvalue": float(pr.pvalue),
    }
    if note:
        case["note"] = note
    return case


def error_case(name, x, y, what_scipy_does):
    return {"name": name, "ldh": jlist(x), "reference": jlist(y), "expect_error": True,
            "reference_behaviour": what_scipy_does}


def scipy_behaviour(fn):
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        try:
            res = fn()
        except Exception as e:  # noqa: BLE001 - recorded
            return f"raises {type(e).__name__}: {str(e)[:100]}"
    msgs = sorted({str(m.message).split(chr(10))[0][:80] for m in w})
    return f"returns {res}" + (f" (warns: {'; '.join(msgs)})" if msgs else "")


def gen_agreement():
    cases = []
    rng = np.random.default_rng(3801)
    ref = rng.normal(1.25, 0.15, 30)
    cases.append(agreement_case("random_n30", r6(ref + rng.normal(0.02, 0.05, 30)), r6(ref),
                                "stride length-like, m: small bias, no proportional bias"))
    rng = np.random.default_rng(3802)
    ref = rng.uniform(0.6, 1.6, 40)
    ldh = 0.85 * ref + 0.12 + rng.normal(0, 0.03, 40)
    cases.append(agreement_case("proportional_bias_n40", r6(ldh), r6(ref),
                                "ldh = 0.85 ref + 0.12 + noise: slope of diff on mean ~ -0.16"))
    rng = np.random.default_rng(3803)
    ref = rng.normal(105, 8, 5)
    cases.append(agreement_case("few_subjects_n5", r6(ref + rng.normal(1, 2, 5)), r6(ref),
                                "cadence-like, steps/min, 5 subjects"))
    rng = np.random.default_rng(3804)
    ref = rng.normal(0.55, 0.05, 3)
    cases.append(agreement_case("few_subjects_n3", r6(ref + rng.normal(0, 0.02, 3)), r6(ref),
                                "the minimum: 3 pairs"))
    rng = np.random.default_rng(3805)
    ref = r6(rng.normal(1.1, 0.2, 25))
    ldh = r6(np.asarray(ref) + rng.normal(-0.03, 0.06, 25))
    for i in (2, 9, 17):
        ldh[i] = float("nan")
    for i in (9, 21):
        ref[i] = float("nan")
    cases.append(agreement_case("with_nan_n25", ldh, ref, "NaN in ldh at 2, 9, 17, in "
                                "reference at 9, 21: 4 pairs dropped"))
    rng = np.random.default_rng(3806)
    ref = rng.normal(0.0, 4.0, 20)
    cases.append(agreement_case("signed_near_zero_n20", r6(ref + rng.normal(0.5, 1.5, 20)),
                                r6(ref), "an asymmetry index, %: values of both signs"))
    # a small realistic table: gait speed, m/s, ldh vs an optical reference, 12 subjects
    ref = [1.21, 1.05, 0.88, 1.34, 0.97, 1.12, 0.72, 1.28, 1.01, 0.93, 1.18, 0.81]
    ldh = [1.24, 1.03, 0.93, 1.37, 1.01, 1.10, 0.78, 1.33, 1.00, 0.97, 1.22, 0.86]
    cases.append(agreement_case("realistic_gait_speed", ldh, ref,
                                "gait speed, m/s, 12 subjects, hand-made"))
    bad = [
        ("too_few_pairs", [1.0, 2.0], [1.1, 2.1]),
        ("too_few_after_nan", [1.0, float("nan"), 2.0, 3.0], [1.1, 2.0, float("nan"), 3.2]),
        ("constant_differences", [1.1, 2.1, 3.1, 4.1], [1.0, 2.0, 3.0, 4.0]),
        ("constant_reference", [1.0, 2.0, 3.0, 4.0], [2.0, 2.0, 2.0, 2.0]),
    ]
    for name, x, y in bad:
        xa, ya = np.asarray(x), np.asarray(y)
        keep = ~(np.isnan(xa) | np.isnan(ya))
        did = "; ".join([
            "pearsonr " + scipy_behaviour(lambda: stats.pearsonr(xa[keep], ya[keep])),
            "ICC " + scipy_behaviour(lambda: icc_rows(np.column_stack([xa[keep], ya[keep]]))
                                     ["icc_2_1"]["ci_low"]),
        ])
        cases.append(error_case(name, x, y, did))
    write("agreement.json", cases)


# --------------------------------------------------------------------------- reliability
def reliability_case(name, wide, note=""):
    wide = np.asarray(wide, float)
    complete, ms = anova_ms(wide)
    n, k = complete.shape
    rows = icc_rows(wide)
    sd_all = float(np.std(complete.ravel(), ddof=1))
    sem = sd_all * math.sqrt(1 - rows["icc_2_1"]["value"])
    means = complete.mean(axis=1)
    cv = None
    if np.all(means > 0):
        cv = float(np.sqrt(np.mean((complete.std(axis=1, ddof=1) / means) ** 2)))
    case = {
        "name": name,
        "trials": [jlist(r) for r in wide],
        "expect_error": False,
        "n_subjects": int(n),
        "k_trials": int(k),
        "dropped_subjects": [int(i) for i in np.where(np.isnan(wide).any(axis=1))[0]],
        "icc": rows,
        **ms,
        "sd_all": sd_all,
        "sem": sem,
        "sem_from_mse": math.sqrt(ms["ms_error"]),
        "mdc95": 1.96 * math.sqrt(2) * sem,
        "within_subject_cv": cv,
        "variance": {
            "between_subject": (ms["ms_subjects"] - ms["ms_within"]) / k,
            "within_subject": ms["ms_within"],
            "subject": (ms["ms_subjects"] - ms["ms_error"]) / k,
            "trial": (ms["ms_raters"] - ms["ms_error"]) / n,
            "error": ms["ms_error"],
        },
    }
    if note:
        case["note"] = note
    return case


def people(seed, n, k, mean, sd_between, sd_within, trial_shift=0.0):
    rng = np.random.default_rng(seed)
    person = rng.normal(mean, sd_between, n)
    shift = trial_shift * np.arange(k)
    return np.round(person[:, None] + shift[None, :] + rng.normal(0, sd_within, (n, k)), 6)


def gen_reliability():
    cases = [
        reliability_case("random_10x3", people(3811, 10, 3, 20.0, 2.0, 1.0),
                         "between SD 2, within SD 1"),
        reliability_case("few_subjects_4x2", people(3812, 4, 2, 1.1, 0.15, 0.05),
                         "4 subjects, 2 trials"),
        reliability_case("learning_effect_15x4", people(3813, 15, 4, 100.0, 6.0, 2.5, 1.5),
                         "each trial 1.5 higher than the last: ICC(2,1) < ICC(3,1)"),
    ]
    wide = people(3814, 12, 3, 0.62, 0.04, 0.02)
    wide[3, 1] = np.nan
    wide[8, 2] = np.nan
    cases.append(reliability_case("missing_trials_12x3", wide,
                                  "subjects 3 and 8 miss a trial: dropped (nan_policy='omit')"))
    cases.append(reliability_case("signed_8x3", people(3815, 8, 3, 0.0, 3.0, 1.0),
                                  "means of both signs: no within-subject CV"))
    # realistic: cadence, steps/min, 8 subjects x 3 trials, hand-made
    cadence = [[108.2, 110.1, 109.4], [96.5, 98.0, 97.2], [115.3, 114.0, 116.1],
               [101.7, 103.9, 102.2], [89.4, 91.2, 90.8], [112.6, 111.8, 113.5],
               [104.1, 102.5, 105.0], [99.0, 100.6, 98.7]]
    cases.append(reliability_case("realistic_cadence_8x3", cadence, "cadence, steps/min"))
    write("reliability.json", cases)


def write(fname, cases):
    os.makedirs(OUT_DIR, exist_ok=True)
    path = os.path.join(OUT_DIR, fname)
    with open(path, "w") as f:
        json.dump({"meta": META, "cases": cases}, f, separators=(",", ":"))
        f.write("\n")
    print(f"{path}: {len(cases)} cases, {os.path.getsize(path)} bytes")


if __name__ == "__main__":
    gen_agreement()
    gen_reliability()
