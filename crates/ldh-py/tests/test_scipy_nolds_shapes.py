"""The Python API feels like scipy.stats and nolds (issue 18 item 3): result objects with
``statistic``/``pvalue``/``df``/``confidence_interval()``, ``axis`` and ``nan_policy`` equal to
live scipy; ``lyap_r`` with nolds' defaults (RANSAC, pinned to nolds' most frequent value) and
``debug_data``; the tables of ``analyze`` as pandas DataFrames."""
import json
import pathlib

import numpy as np
import pytest
from scipy import stats as ss

import ldh

ROOT = pathlib.Path(__file__).resolve().parents[3]
LYAP = ROOT / "data-fixtures" / "golden" / "lyapunov"
RNG = np.random.default_rng(11)
A, B = RNG.normal(0, 1, 14), RNG.normal(0.6, 1.4, 11)


def close(a, b):
    np.testing.assert_allclose(a, b, rtol=1e-6, atol=1e-12)


@pytest.mark.parametrize("alt", ["two-sided", "less", "greater"])
def test_ttests_have_scipys_df_and_confidence_interval(alt):
    pairs = [
        (ldh.ttest_ind(A, B, alternative=alt), ss.ttest_ind(A, B, alternative=alt)),
        (ldh.ttest_ind(A, B, equal_var=False, alternative=alt), ss.ttest_ind(A, B, equal_var=False, alternative=alt)),
        (ldh.ttest_rel(A[:11], B, alternative=alt), ss.ttest_rel(A[:11], B, alternative=alt)),
        (ldh.ttest_1samp(A, 0.3, alternative=alt), ss.ttest_1samp(A, 0.3, alternative=alt)),
    ]
    for ours, ref in pairs:
        close(ours.statistic, ref.statistic)
        close(ours.pvalue, ref.pvalue)
        close(ours.df, ref.df)
        for level in (0.95, 0.8):
            close(ours.confidence_interval(level), ref.confidence_interval(level))
        stat, p = ours
        assert (stat, p) == (ours.statistic, ours.pvalue)


@pytest.mark.parametrize("alt", ["two-sided", "less", "greater"])
def test_pearsonr_confidence_interval_equals_scipy(alt):
    ours, ref = ldh.pearsonr(A[:11], B, alternative=alt), ss.pearsonr(A[:11], B, alternative=alt)
    close(ours.statistic, ref.statistic)
    close(ours.pvalue, ref.pvalue)
    close(ours.confidence_interval(0.9), ref.confidence_interval(0.9))


def test_axis_equals_scipy():
    x, y = RNG.normal(0, 1, (3, 12, 4)), RNG.normal(0.3, 1, (3, 9, 4))
    for axis in (1, -2):
        for ours, ref in [
            (ldh.ttest_ind(x, y, axis=axis), ss.ttest_ind(x, y, axis=axis)),
            (ldh.mannwhitneyu(x, y, axis=axis), ss.mannwhitneyu(x, y, axis=axis)),
            (ldh.kruskal(x, y, axis=axis), ss.kruskal(x, y, axis=axis)),
            (ldh.f_oneway(x, y, axis=axis), ss.f_oneway(x, y, axis=axis)),
        ]:
            assert np.shape(ours.statistic) == (3, 4)
            close(ours.statistic, ref.statistic)
            close(ours.pvalue, ref.pvalue)
    t = ldh.ttest_ind(x, y, axis=1)
    close(t.df, ss.ttest_ind(x, y, axis=1).df)
    close(t.confidence_interval(), ss.ttest_ind(x, y, axis=1).confidence_interval())
    close(ldh.shapiro(x).statistic, ss.shapiro(x).statistic)  # axis=None: flattened, as scipy
    close(ldh.ttest_ind(x, y, axis=None).pvalue, ss.ttest_ind(x, y, axis=None).pvalue)


def test_nan_policy_equals_scipy():
    a, b = A.copy(), B.copy()
    a[3], b[5] = np.nan, np.nan
    for f, g in [(ldh.ttest_ind, ss.ttest_ind), (ldh.mannwhitneyu, ss.mannwhitneyu), (ldh.ttest_rel, ss.ttest_rel)]:
        u, v = (a, b) if f is not ldh.ttest_rel else (a[:11], b)
        prop = f(u, v)
        assert np.isnan(prop.statistic) and np.isnan(prop.pvalue)
        close(f(u, v, nan_policy="omit").pvalue, g(u, v, nan_policy="omit").pvalue)
        with pytest.raises(ValueError, match="NaN|nan"):
            f(u, v, nan_policy="raise")
    assert np.isnan(ldh.ttest_ind(a, b).confidence_interval().low)
    close(ldh.wilcoxon(a[:11], b, nan_policy="omit").pvalue, ss.wilcoxon(a[:11], b, nan_policy="omit").pvalue)
    with pytest.raises(ldh.LdhParamError, match="nan_policy"):
        ldh.ttest_ind(A, B, nan_policy="ignore")


def test_lyap_r_defaults_are_nolds_ransac_and_debug_data_is_the_curve():
    g = json.loads((LYAP / "ransac.json").read_text())
    for case in g["cases"]:
        x = np.array(json.loads((LYAP / f"{case['series']}.json").read_text())["series"])
        ours = ldh.lyap_r(x, **case["params"])
        # nolds draws random triples: ours is the value nolds gives most often.
        assert ours == pytest.approx(case["most_frequent"], rel=1e-6, abs=1e-9), case["series"]
        assert any(r == pytest.approx(ours, rel=1e-6, abs=1e-9) for r in case["runs"])
        le, (ks, div, poly) = ldh.lyap_r(x, debug_data=True, **case["params"])
        assert le == ours and len(ks) == len(div) and poly.shape == (2,)
        tau = case["params"].get("tau", 1.0)
        assert poly[0] / tau == pytest.approx(le)
    lorenz = json.loads((LYAP / "lorenz.json").read_text())
    case = lorenz["lyap_r"][0]
    x = np.array(lorenz["series"])
    p = {k: v for k, v in case["params"].items() if k in ("emb_dim", "lag", "min_tsep", "trajectory_len")}
    le, (ks, div, poly) = ldh.lyap_r(x, fit="poly", debug_data=True, **p)
    assert le == pytest.approx(case["lyap"], rel=1e-6)
    close(poly, np.polyfit(ks, div, 1))
    with pytest.raises(ldh.LdhParamError, match="fit"):
        ldh.lyap_r(x, fit="lsq")


def test_analyze_returns_dataframes_or_arrays(tmp_path):
    pd = pytest.importorskip("pandas")
    ldh.write_demo(tmp_path)
    res = ldh.analyze(tmp_path / "manifest.csv", compute_sta=False)
    assert isinstance(res, ldh.Result)
    for t in (res.strides, res.recordings, res.events):
        assert isinstance(t, pd.DataFrame)
    ids = [f"H{i:02}" for i in range(1, 11)] + ["L01", "L02", "L03"]
    assert list(res.recordings.subject_id) == [s for s in ids for _ in ("left", "right")]
    assert res.recordings.stride_time_s.dtype == np.float64
    assert len(res.errors) == 0 and set(res.events.event) == {"HS", "TO"}
    plain = ldh.analyze(tmp_path / "manifest.csv", compute_sta=False, as_frame=False)
    assert isinstance(plain.recordings["stride_time_s"], np.ndarray)
    np.testing.assert_array_equal(plain.recordings["stride_time_s"], res.recordings.stride_time_s.to_numpy())
    frames = plain.to_pandas()
    pd.testing.assert_frame_equal(frames["recordings"], res.recordings)
    with pytest.raises(FileNotFoundError, match="no/such/folder"):
        ldh.analyze("no/such/folder")
