#!/usr/bin/env python3
"""Generate the golden values for `ldh_core::stats` (scipy.stats parity).

Usage (from the repository root):

    python3 data-fixtures/scripts/gen_stats_golden.py

Writes one JSON file per test family into `data-fixtures/golden/stats/`.
Every file records the python / numpy / scipy versions, and every case
stores its input samples, so the Rust tests need nothing but the JSON.

Determinism: every sample comes from `numpy.random.default_rng(seed)` with a
fixed seed and is rounded to 6 decimals (tie-heavy samples are integers or
halves), so the decimal text in the JSON parses to exactly the same f64 in
Rust and in Python.

Cases where scipy returns NaN / inf or warns ("undefined" cases) are recorded
with `"expect_error": true` and a short description of what scipy did; the
Rust side asserts that it returns a `StatsError` for them.

The Holm reference is a numpy re-implementation of
`statsmodels.stats.multitest.multipletests(p, method="holm")[1]` (statsmodels
is not a dependency); if statsmodels is importable it is cross-checked.
"""

import json
import math
import os
import platform
import sys
import warnings

import numpy as np
import scipy
from scipy import stats

OUT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "golden", "stats")

META = {
    "python": platform.python_version(),
    "numpy": np.__version__,
    "scipy": scipy.__version__,
    "generator": "data-fixtures/scripts/gen_stats_golden.py",
}

ALTS = ["two-sided", "less", "greater"]


def r6(a):
    """Round to 6 decimals and return a plain list of floats."""
    return [float(v) for v in np.round(np.asarray(a, dtype=float), 6)]


def normal(seed, n, loc=0.0, scale=1.0):
    return r6(np.random.default_rng(seed).normal(loc, scale, n))


def fnum(v):
    """JSON-safe float: NaN / inf become strings."""
    v = float(v)
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return v


def call(fn):
    """Run a scipy call; return (result or None, description of what happened)."""
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        try:
            res = fn()
        except Exception as e:  # noqa: BLE001 - recorded, not hidden
            return None, f"raises {type(e).__name__}: {e}"
    msgs = sorted({str(x.message).split("\n")[0][:100] for x in w})
    return res, "; ".join(msgs)


def ok_case(name, args, res, warn="", df=None, extra=None):
    case = {
        "name": name,
        "args": args,
        "expect_error": False,
        "statistic": fnum(res.statistic),
        "pvalue": fnum(res.pvalue),
    }
    if df is not None:
        case["df"] = fnum(df)
    if warn:
        case["scipy_warning"] = warn
    if extra:
        case.update(extra)
    for k in ("statistic", "pvalue", "df"):
        if isinstance(case.get(k), str):
            raise RuntimeError(f"{name}: scipy gave {k}={case[k]} in a case marked defined")
    return case


def err_case(name, args, fn):
    res, note = call(fn)
    if res is None:
        scipy_did = note
    else:
        parts = [f"{f}={fnum(getattr(res, f))}" for f in ("statistic", "pvalue") if hasattr(res, f)]
        scipy_did = "returns " + ", ".join(parts) + (f" (warns: {note})" if note else "")
    return {"name": name, "args": args, "expect_error": True, "scipy_behaviour": scipy_did}


def write(fname, cases):
    os.makedirs(OUT_DIR, exist_ok=True)
    path = os.path.join(OUT_DIR, fname)
    with open(path, "w") as f:
        json.dump({"meta": META, "cases": cases}, f, separators=(",", ":"))
        f.write("\n")
    print(f"{path}: {len(cases)} cases, {os.path.getsize(path)} bytes")


# --------------------------------------------------------------------------- shapiro
def gen_shapiro():
    cases = []
    samples = {
        "n3_normal": normal(1, 3),
        "n3_collinear": [1.0, 2.0, 3.0],
        "n3_min_w": [0.0, 0.0, 1.0],
        "n4_normal": normal(2, 4),
        "n5_normal": normal(3, 5),
        "n6_normal": normal(4, 6),
        "n11_normal": normal(5, 11),
        "n12_normal": normal(6, 12),
        "n20_normal": normal(7, 20),
        "n50_normal": normal(8, 50, 10.0, 2.0),
        "n200_normal": normal(9, 200),
        "n30_exponential": r6(np.random.default_rng(10).exponential(1.0, 30)),
        "n100_uniform": r6(np.random.default_rng(11).uniform(0, 1, 100)),
        "n40_heavy_ties": [float(v) for v in np.random.default_rng(12).integers(0, 4, 40)],
        "n500_lognormal": r6(np.random.default_rng(13).lognormal(0, 1, 500)),
        "n5001_normal": [float(v) for v in np.round(np.random.default_rng(14).normal(0, 1, 5001), 4)],
    }
    for name, x in samples.items():
        res, warn = call(lambda: stats.shapiro(x))
        cases.append(ok_case(name, {"x": x}, res, warn))
    cases.append(err_case("n2_too_small", {"x": [1.0, 2.0]}, lambda: stats.shapiro([1.0, 2.0])))
    cases.append(err_case("constant", {"x": [1.0] * 5}, lambda: stats.shapiro([1.0] * 5)))
    cases.append(err_case("empty", {"x": []}, lambda: stats.shapiro([])))
    write("shapiro.json", cases)


# --------------------------------------------------------------------------- mannwhitneyu
def gen_mwu():
    cases = []
    rng = np.random.default_rng(100)
    ints = lambda seed, n, hi: [float(v) for v in np.random.default_rng(seed).integers(0, hi, n)]
    pairs = {
        "exact_5_7": (normal(101, 5), normal(102, 7, 0.8)),
        "exact_3_3": (normal(103, 3), normal(104, 3, 1.0)),
        "exact_8_30": (normal(105, 8, 0.7), normal(106, 30)),
        "exact_40_2": (normal(107, 40), normal(108, 2, 1.5)),
        "exact_8_8_separated": (normal(109, 8), normal(110, 8, 10.0)),
        "ties_small_6_6": (ints(111, 6, 4), ints(112, 6, 4)),
        "asymp_20_25": (normal(113, 20), normal(114, 25, 0.5)),
        "asymp_9_9": (normal(115, 9), normal(116, 9, 0.3)),
        "asymp_200_150": (normal(117, 200), normal(118, 150, 0.2)),
        "heavy_ties_30_35": (ints(119, 30, 5), ints(120, 35, 5)),
        "asymp_tiny_p_60_60": (normal(121, 60), normal(122, 60, 3.0)),
        "all_tied_5_5": ([2.0] * 5, [2.0] * 5),
        "all_tied_10_12": ([1.5] * 10, [1.5] * 12),
    }
    del rng
    for name, (x, y) in pairs.items():
        for alt in ALTS:
            res, warn = call(lambda: stats.mannwhitneyu(x, y, alternative=alt))
            cases.append(ok_case(f"{name}_{alt}", {"x": x, "y": y, "alternative": alt}, res, warn))
    for name, (x, y) in {"empty_x": ([], [1.0, 2.0]), "nan_in_y": ([1.0, 2.0, 3.0], [1.0, float("nan")])}.items():
        args = {"x": x, "y": [fnum(v) for v in y], "alternative": "two-sided"}
        cases.append(err_case(name, args, lambda: stats.mannwhitneyu(x, y)))
    write("mannwhitneyu.json", cases)


# --------------------------------------------------------------------------- t tests
def gen_ttest():
    cases = []
    ind = {
        "n3_3": (normal(201, 3), normal(202, 3, 1.0)),
        "n10_12": (normal(203, 10), normal(204, 12, 0.5, 2.0)),
        "n50_40": (normal(205, 50, 1.0), normal(206, 40, 0.6, 0.5)),
        "n1_4": ([0.3], normal(207, 4, 1.0)),
        "n30_30_tiny_p": (normal(208, 30), normal(209, 30, 5.0)),
        "n200_300": (normal(210, 200), normal(211, 300, 0.1, 3.0)),
    }
    for name, (x, y) in ind.items():
        for eq in (True, False):
            if not eq and (len(x) < 2 or len(y) < 2):
                continue
            for alt in ALTS:
                res, warn = call(lambda: stats.ttest_ind(x, y, equal_var=eq, alternative=alt))
                tag = "student" if eq else "welch"
                cases.append(ok_case(f"ind_{tag}_{name}_{alt}",
                                     {"kind": "ind", "x": x, "y": y, "equal_var": eq, "alternative": alt},
                                     res, warn, df=res.df))
    rel = {
        "n3": (normal(221, 3), normal(222, 3, 0.5)),
        "n10": (normal(223, 10), normal(224, 10, 0.3)),
        "n40": (normal(225, 40, 2.0), normal(226, 40, 2.4)),
    }
    for name, (x, y) in rel.items():
        for alt in ALTS:
            res, warn = call(lambda: stats.ttest_rel(x, y, alternative=alt))
            cases.append(ok_case(f"rel_{name}_{alt}", {"kind": "rel", "x": x, "y": y, "alternative": alt},
                                 res, warn, df=res.df))
    one = {
        "n3_mu0": (normal(231, 3, 0.5), 0.0),
        "n15_mu1": (normal(232, 15, 1.3), 1.0),
        "n100_mu_minus": (normal(233, 100, -0.1), 0.05),
        "n20_tiny_p": (normal(234, 20, 10.0), 0.0),
    }
    for name, (x, mu) in one.items():
        for alt in ALTS:
            res, warn = call(lambda: stats.ttest_1samp(x, mu, alternative=alt))
            cases.append(ok_case(f"1samp_{name}_{alt}",
                                 {"kind": "1samp", "x": x, "popmean": mu, "alternative": alt},
                                 res, warn, df=res.df))
    errs = [
        ("ind_student_both_constant_diff", {"kind": "ind", "x": [1.0] * 3, "y": [2.0] * 3, "equal_var": True},
         lambda: stats.ttest_ind([1.0] * 3, [2.0] * 3)),
        ("ind_student_both_constant_same", {"kind": "ind", "x": [1.0] * 3, "y": [1.0] * 3, "equal_var": True},
         lambda: stats.ttest_ind([1.0] * 3, [1.0] * 3)),
        ("ind_welch_constant", {"kind": "ind", "x": [1.0] * 3, "y": [2.0] * 3, "equal_var": False},
         lambda: stats.ttest_ind([1.0] * 3, [2.0] * 3, equal_var=False)),
        ("ind_student_n1_1", {"kind": "ind", "x": [1.0], "y": [2.0], "equal_var": True},
         lambda: stats.ttest_ind([1.0], [2.0])),
        ("ind_welch_n1", {"kind": "ind", "x": [1.0], "y": [2.0, 3.0, 4.0], "equal_var": False},
         lambda: stats.ttest_ind([1.0], [2.0, 3.0, 4.0], equal_var=False)),
        ("ind_empty", {"kind": "ind", "x": [], "y": [2.0, 3.0, 4.0], "equal_var": True},
         lambda: stats.ttest_ind([], [2.0, 3.0, 4.0])),
        ("rel_length_mismatch", {"kind": "rel", "x": [1.0, 2.0, 3.0], "y": [1.0, 2.0]},
         lambda: stats.ttest_rel([1.0, 2.0, 3.0], [1.0, 2.0])),
        ("rel_constant_difference", {"kind": "rel", "x": [1.0, 2.0, 3.0], "y": [2.0, 3.0, 4.0]},
         lambda: stats.ttest_rel([1.0, 2.0, 3.0], [2.0, 3.0, 4.0])),
        ("rel_identical", {"kind": "rel", "x": [1.0, 2.0, 3.0], "y": [1.0, 2.0, 3.0]},
         lambda: stats.ttest_rel([1.0, 2.0, 3.0], [1.0, 2.0, 3.0])),
        ("1samp_n1", {"kind": "1samp", "x": [1.0], "popmean": 0.0}, lambda: stats.ttest_1samp([1.0], 0.0)),
        ("1samp_constant", {"kind": "1samp", "x": [1.0] * 4, "popmean": 0.0},
         lambda: stats.ttest_1samp([1.0] * 4, 0.0)),
    ]
    for name, args, fn in errs:
        args.setdefault("alternative", "two-sided")
        cases.append(err_case(name, args, fn))
    write("ttest.json", cases)


# --------------------------------------------------------------------------- wilcoxon
def gen_wilcoxon():
    cases = []
    half = lambda seed, n, lo, hi: [float(v) / 2 for v in np.random.default_rng(seed).integers(lo, hi, n)]
    one = {
        "exact_n1": [0.7],
        "exact_n3": normal(301, 3, 0.5),
        "exact_n10": normal(302, 10, 0.4),
        "exact_n20": normal(303, 20, 0.6),
        "exact_n50_boundary": normal(304, 50, 0.2),
        "exact_n25_all_positive": [abs(v) + 0.01 for v in normal(305, 25)],
        "asymp_n51": normal(306, 51, 0.3),
        "asymp_n200": normal(307, 200, 0.1),
        "perm_ties_n10": half(308, 10, -6, 9),
        "perm_ties_zeros_n12": half(309, 12, -5, 8),
        "perm_zeros_n13": [0.0, 0.0] + normal(310, 11, 0.5),
        "asymp_ties_n14": half(311, 14, -6, 9),
        "asymp_ties_zeros_n30": half(312, 30, -8, 10),
        "asymp_zeros_n60": [0.0] * 5 + normal(313, 55, 0.3),
        "asymp_ties_n80": [float(v) for v in np.random.default_rng(314).integers(-3, 5, 80)],
    }
    for name, d in one.items():
        for alt in ALTS:
            res, warn = call(lambda: stats.wilcoxon(d, alternative=alt))
            cases.append(ok_case(f"{name}_{alt}", {"x": d, "alternative": alt}, res, warn))
    paired = {
        "paired_n8": (normal(321, 8), normal(322, 8, 0.5)),
        "paired_n60": (normal(323, 60), normal(324, 60, 0.2)),
        "paired_ties_n12": ([float(v) for v in np.random.default_rng(325).integers(0, 6, 12)],
                            [float(v) for v in np.random.default_rng(326).integers(0, 6, 12)]),
    }
    for name, (x, y) in paired.items():
        for alt in ALTS:
            res, warn = call(lambda: stats.wilcoxon(x, y, alternative=alt))
            cases.append(ok_case(f"{name}_{alt}", {"x": x, "y": y, "alternative": alt}, res, warn))
    errs = [
        ("all_zero_n3", {"x": [0.0] * 3}, lambda: stats.wilcoxon([0.0] * 3)),
        ("all_zero_n60", {"x": [0.0] * 60}, lambda: stats.wilcoxon([0.0] * 60)),
        ("paired_identical", {"x": [1.0, 2.0, 3.0, 4.0], "y": [1.0, 2.0, 3.0, 4.0]},
         lambda: stats.wilcoxon([1.0, 2.0, 3.0, 4.0], [1.0, 2.0, 3.0, 4.0])),
        ("paired_length_mismatch", {"x": [1.0, 2.0, 3.0], "y": [1.0, 2.0]},
         lambda: stats.wilcoxon([1.0, 2.0, 3.0], [1.0, 2.0])),
        ("empty", {"x": []}, lambda: stats.wilcoxon([])),
    ]
    for name, args, fn in errs:
        args["alternative"] = "two-sided"
        cases.append(err_case(name, args, fn))
    write("wilcoxon.json", cases)


# --------------------------------------------------------------------------- anova / kruskal
def gen_anova():
    cases = []
    ints = lambda seed, n, hi: [float(v) for v in np.random.default_rng(seed).integers(0, hi, n)]
    groups = {
        "three_n10": [normal(401, 10), normal(402, 10, 0.5), normal(403, 10, 1.0)],
        "three_unequal_5_8_12": [normal(404, 5), normal(405, 8, 0.2, 2.0), normal(406, 12, -0.3, 0.5)],
        "two_n15": [normal(407, 15), normal(408, 15, 0.4)],
        "three_n3": [normal(409, 3), normal(410, 3, 2.0), normal(411, 3, 4.0)],
        "one_group_constant": [[1.0, 1.0, 1.0], normal(412, 6, 2.0), normal(413, 4, 0.0)],
        "singletons_and_pair": [[0.5], [1.5], [2.0, 3.0]],
        "four_n100": [normal(414, 100), normal(415, 100, 0.1), normal(416, 100, 0.2), normal(417, 100, 0.0)],
        "tiny_p": [normal(418, 30), normal(419, 30, 4.0), normal(420, 30, 8.0)],
        "heavy_ties": [ints(421, 20, 4), ints(422, 25, 4), ints(423, 15, 5)],
        "large_offset": [normal(424, 12, 1e6), normal(425, 12, 1e6 + 0.5), normal(426, 12, 1e6 + 1.0)],
    }
    for name, gs in groups.items():
        res, warn = call(lambda: stats.f_oneway(*gs))
        c = ok_case(f"f_oneway_{name}", {"test": "f_oneway", "groups": gs}, res, warn)
        c["df"] = [len(gs) - 1, sum(len(g) for g in gs) - len(gs)]
        cases.append(c)
        res, warn = call(lambda: stats.kruskal(*gs))
        c = ok_case(f"kruskal_{name}", {"test": "kruskal", "groups": gs}, res, warn)
        c["df"] = len(gs) - 1
        cases.append(c)
    errs = {
        "all_constant_diff_means": [[1.0] * 3, [2.0] * 3],
        "all_same_constant": [[1.0] * 3, [1.0] * 4],
        "empty_group": [[1.0, 2.0], [], [3.0, 4.0]],
        "one_group": [[1.0, 2.0, 3.0]],
        "all_length_one": [[1.0], [2.0], [3.0]],
    }
    for name, gs in errs.items():
        for test, fn in (("f_oneway", stats.f_oneway), ("kruskal", stats.kruskal)):
            if test == "kruskal" and name in ("all_constant_diff_means", "all_length_one"):
                continue  # defined for kruskal: recorded as a normal case below
            cases.append(err_case(f"{test}_{name}", {"test": test, "groups": gs}, lambda: fn(*gs)))
    for name in ("all_constant_diff_means", "all_length_one"):
        gs = errs[name]
        res, warn = call(lambda: stats.kruskal(*gs))
        c = ok_case(f"kruskal_{name}", {"test": "kruskal", "groups": gs}, res, warn)
        c["df"] = len(gs) - 1
        cases.append(c)
    write("anova.json", cases)


# --------------------------------------------------------------------------- pearsonr
def gen_pearsonr():
    cases = []

    def corr(seed, n, rho):
        rng = np.random.default_rng(seed)
        x = rng.normal(0, 1, n)
        y = rho * x + math.sqrt(1 - rho * rho) * rng.normal(0, 1, n)
        return r6(x), r6(y)

    pairs = {
        "n3": corr(501, 3, 0.5),
        "n10": corr(502, 10, 0.3),
        "n10_negative": corr(503, 10, -0.7),
        "n100": corr(504, 100, 0.1),
        "n1000_tiny_p": corr(505, 1000, 0.6),
        "n30_strong": corr(506, 30, 0.99),
        "n2": ([1.0, 2.0], [3.0, 1.0]),
        "n4_ties": ([1.0, 1.0, 2.0, 2.0], [1.0, 2.0, 2.0, 3.0]),
    }
    for name, (x, y) in pairs.items():
        for alt in ALTS:
            res, warn = call(lambda: stats.pearsonr(x, y, alternative=alt))
            cases.append(ok_case(f"{name}_{alt}", {"x": x, "y": y, "alternative": alt}, res, warn))
    errs = {
        "constant_x": ([1.0] * 4, [1.0, 2.0, 3.0, 5.0]),
        "length_mismatch": ([1.0, 2.0, 3.0], [1.0, 2.0]),
        "n1": ([1.0], [2.0]),
    }
    for name, (x, y) in errs.items():
        cases.append(err_case(name, {"x": x, "y": y, "alternative": "two-sided"}, lambda: stats.pearsonr(x, y)))
    write("pearsonr.json", cases)


# --------------------------------------------------------------------------- holm + descriptives
def holm_reference(p):
    """numpy port of statsmodels multipletests(method='holm')[1]."""
    p = np.asarray(p, dtype=float)
    m = len(p)
    order = np.argsort(p)
    ps = p[order]
    adj = np.maximum.accumulate(ps * np.arange(m, 0, -1))
    adj[adj > 1] = 1
    out = np.empty(m)
    out[order] = adj
    return out


def gen_holm_desc():
    holm_cases = []
    vectors = {
        "single": [0.03],
        "four": [0.01, 0.04, 0.03, 0.005],
        "with_ties": [0.02, 0.02, 0.5, 0.001, 0.02],
        "capped": [0.3, 0.6, 0.9, 0.2],
        "random_20": [float(v) for v in np.random.default_rng(601).uniform(0, 0.2, 20)],
        "tiny": [1e-15, 3e-10, 0.04, 1.0],
        "paper_like": [0.0004, 0.012, 0.37, 0.051],
    }
    try:
        from statsmodels.stats.multitest import multipletests  # type: ignore
    except ImportError:
        multipletests = None
    for name, p in vectors.items():
        ref = holm_reference(p)
        if multipletests is not None:
            assert np.allclose(ref, multipletests(p, method="holm")[1], rtol=0, atol=0)
        holm_cases.append({"name": name, "p": p, "adjusted": [float(v) for v in ref]})
    desc_cases = []
    for name, x in {"n1": [2.5], "n2": [1.0, 4.0], "n10": normal(701, 10, 3.0, 2.0),
                    "n1000": normal(702, 1000, -1.0, 0.1), "large_offset": normal(703, 20, 1e8, 1.0)}.items():
        c = {"name": name, "x": x, "mean": float(np.mean(x))}
        if len(x) >= 2:
            c["std"] = float(np.std(x, ddof=1))
        desc_cases.append(c)
    meta = dict(META)
    meta["holm_reference"] = "statsmodels multipletests(method='holm') re-implemented in numpy" + (
        "; cross-checked with statsmodels " if multipletests is not None else " (statsmodels not installed)")
    path = os.path.join(OUT_DIR, "holm_descriptives.json")
    with open(path, "w") as f:
        json.dump({"meta": meta, "holm": holm_cases, "descriptives": desc_cases}, f, separators=(",", ":"))
        f.write("\n")
    print(f"{path}: {len(holm_cases)} holm + {len(desc_cases)} descriptive cases")


if __name__ == "__main__":
    print(f"python {META['python']}, numpy {META['numpy']}, scipy {META['scipy']}", file=sys.stderr)
    gen_shapiro()
    gen_mwu()
    gen_ttest()
    gen_wilcoxon()
    gen_anova()
    gen_pearsonr()
    gen_holm_desc()
