"""Statistics vs scipy.stats (golden file and live scipy), array-level analysis, batch and Dask."""
import json
import pathlib

import numpy as np
import pytest
from scipy import stats as ss

import ldh

ROOT = pathlib.Path(__file__).resolve().parents[3]


def _ok(ours, ref):
    assert ours.statistic == pytest.approx(ref.statistic, rel=1e-6, abs=1e-12)
    assert ours.pvalue == pytest.approx(ref.pvalue, rel=1e-6, abs=1e-12)


def test_tests_equal_scipy_on_random_and_tied_data():
    rng = np.random.default_rng(3)
    for n in [3, 8, 25, 60]:
        x, y, z = rng.normal(0, 1, n), rng.normal(0.4, 1.2, n), rng.normal(-0.2, 0.8, n + 3)
        xt = np.round(x * 2) / 2  # ties
        _ok(ldh.shapiro(x), ss.shapiro(x))
        for alt in ["two-sided", "less", "greater"]:
            _ok(ldh.mannwhitneyu(x, z, alternative=alt), ss.mannwhitneyu(x, z, alternative=alt))
            _ok(ldh.mannwhitneyu(xt, np.round(z * 2) / 2, alternative=alt), ss.mannwhitneyu(xt, np.round(z * 2) / 2, alternative=alt))
            _ok(ldh.ttest_ind(x, z, alternative=alt), ss.ttest_ind(x, z, alternative=alt))
            _ok(ldh.ttest_ind(x, z, equal_var=False, alternative=alt), ss.ttest_ind(x, z, equal_var=False, alternative=alt))
            _ok(ldh.ttest_rel(x, y, alternative=alt), ss.ttest_rel(x, y, alternative=alt))
            _ok(ldh.wilcoxon(x, y, alternative=alt), ss.wilcoxon(x, y, alternative=alt))
            _ok(ldh.pearsonr(x, y, alternative=alt), ss.pearsonr(x, y, alternative=alt))
        _ok(ldh.f_oneway(x, y, z), ss.f_oneway(x, y, z))
        _ok(ldh.kruskal(xt, y, z), ss.kruskal(xt, y, z))
    r = ldh.shapiro([1.0, 2.0, 4.0, 7.0])
    assert r == (r.statistic, r.pvalue) and isinstance(r, ldh.TestResult)


def test_holm_and_undefined_tests():
    np.testing.assert_allclose(ldh.holm([0.01, 0.04, 0.03]), [0.03, 0.06, 0.06])
    with pytest.raises(ValueError, match="constant"):
        ldh.ttest_ind([1.0, 1.0, 1.0], [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="at least 3"):
        ldh.shapiro([1.0, 2.0])
    with pytest.raises(ldh.LdhParamError, match="alternative"):
        ldh.ttest_rel([1.0, 2.0, 3.0], [1.0, 2.5, 3.5], alternative="bigger")


def test_analyze_recording_from_arrays(tmp_path):
    ldh.write_demo(tmp_path)
    rec, _ = ldh.read_recording(tmp_path / "L01" / "right.csv")
    acc = [rec["acc_x_g"], rec["acc_y_g"], rec["acc_z_g"]]
    gyro = [rec["gyro_x_dps"], rec["gyro_y_dps"], rec["gyro_z_dps"]]
    out = ldh.analyze_recording(acc, gyro, rec["fs_hz"], side="right")
    assert len(out["attitude"]["pitch_deg"]) == len(rec["time_s"])
    assert out["alignment"]["mirrored"] is True
    assert 0.55 < out["parameters"]["stance_ratio"] < 0.7
    assert len(out["events"]["hs_s"]) > 10
    assert np.isnan(out["parameters"]["step_time_s"])  # one leg: no step time
    # No sensor height given: the note that 0.10 m was assumed (the demo's shank hardly turns at
    # mid-stance, so the length is reported; issue 20). The 35 s demo walk has enough steady
    # strides for the stride-time CV; one leg alone cannot check its stride length variability
    # against the other leg's, so that CV is withheld (sv_unchecked).
    codes = [(w["code"], w["severity"]) for w in out["warnings"]]
    assert ("sv_unchecked", "warning") in codes, codes
    assert ("sensor_height_unknown", "note") in codes, codes
    assert "too_little_steady" not in [c for c, _ in codes], codes
    assert np.isnan(out["parameters"]["stride_length_cv"]) and np.isfinite(out["parameters"]["stride_time_cv"])
    assert "stride_length_cv" in out["parameters"]["withheld"]
    given = ldh.analyze_recording(acc, gyro, rec["fs_hz"], side="right", sensor_height_m=0.1, compute_sta=False)
    given_codes = [w["code"] for w in given["warnings"]]
    assert "sv_unchecked" in given_codes and "sensor_height_unknown" not in given_codes, given_codes
    assert given["parameters"]["stride_length_m"] == out["parameters"]["stride_length_m"]
    # The device turned upside down (180 deg about its y axis): analysed, with a note.
    flip = lambda ch: [-ch[0], ch[1], -ch[2]]
    up = ldh.analyze_recording(flip(acc), flip(gyro), rec["fs_hz"], side="right", compute_sta=False)
    assert any(w["code"] == "upside_down" and w["severity"] == "note" for w in up["warnings"]), up["warnings"]
    assert abs(up["parameters"]["stance_ratio"] - out["parameters"]["stance_ratio"]) < 0.02
    acc_only = ldh.analyze_recording(acc, gyro, rec["fs_hz"], side="right", model="acc", compute_sta=False)
    # The ACC-only attitude cannot separate gravity from motion: its stride length is never
    # reported (NaN + reason), whatever the per-stride checks say (issue 20).
    assert np.isnan(acc_only["parameters"]["stride_length_m"])
    assert "ACC-only" in acc_only["parameters"]["withheld"]["stride_length_m"]
    assert np.isfinite(out["parameters"]["stride_length_m"])
    with pytest.raises(ldh.LdhParamError, match="side"):
        ldh.analyze_recording(acc, gyro, rec["fs_hz"], side="middle")
    with pytest.raises(ValueError, match="non-finite"):
        bad = [a.copy() for a in acc]
        bad[0][10] = np.nan
        ldh.analyze_recording(bad, gyro, rec["fs_hz"])


def test_analyze_many_is_identical_whatever_n_jobs(tmp_path):
    ldh.write_demo(tmp_path)
    dirs = [tmp_path / s for s in ["H01", "H02", "L01", "L02"]]
    one = ldh.analyze_many(dirs, n_jobs=1, compute_sta=False)
    two = ldh.analyze_many(dirs, n_jobs=2, compute_sta=False)
    assert list(one["recordings"]["subject_id"]) == list(two["recordings"]["subject_id"])
    np.testing.assert_array_equal(one["strides"]["stride_length_m"], two["strides"]["stride_length_m"])
    with pytest.raises(ldh.LdhParamError, match="n_jobs"):
        ldh.analyze(tmp_path, n_jobs=-3)
    with pytest.raises(ldh.LdhParamError, match="n_jobs"):
        ldh.analyze(tmp_path, n_jobs=0)


def test_dask_workers_give_the_cli_results(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    ldh.write_demo(tmp_path)
    subjects = ["H01", "H02", "L01", "L02"]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        futures = client.map(lambda s: ldh.analyze(str(tmp_path / s), n_jobs=1), subjects)
        parts = client.gather(futures)
    # The same inputs analysed in this process (ldh.analyze equals the CLI: test_pipeline.py).
    # Subject folders carry no manifest, so the default sensor height applies in both.
    local = ldh.analyze([tmp_path / s for s in subjects])
    for s, part in zip(subjects, parts):
        idx = [i for i, x in enumerate(local["recordings"]["subject_id"]) if x == s]
        for key in ["stride_time_s", "stance_ratio", "stride_length_m", "sta_per_s"]:
            np.testing.assert_array_equal(part["recordings"][key], local["recordings"][key][idx])


def test_pair_from_arrays_equals_the_files(tmp_path):
    ldh.write_demo(tmp_path)
    left, _ = ldh.read_recording(tmp_path / "L02" / "left.csv")
    right, _ = ldh.read_recording(tmp_path / "L02" / "right.csv")
    pair = ldh.analyze_pair(left, right, subject_id="L02", compute_sta=False)
    files = ldh.analyze([tmp_path / "L02" / "left.csv", tmp_path / "L02" / "right.csv"], compute_sta=False)
    for key in ["stride_time_s", "step_time_s", "stance_ratio", "stride_length_m"]:
        np.testing.assert_array_equal(pair["recordings"][key], files["recordings"][key])
    assert set(pair["events"]["side"]) == {"left", "right"}
    with pytest.raises(ldh.LdhParamError, match="lacks the channels"):
        ldh.analyze_pair({"acc_x_g": [1.0]}, right)


def test_empty_and_bad_arrays_raise_value_errors():
    with pytest.raises(ValueError, match="too short"):
        ldh.butter_filtfilt(np.array([]), 10.0, 100.0)
    with pytest.raises(ValueError):
        ldh.preprocess([[], [], []], [[], [], []], 100.0)
    with pytest.raises(ValueError):
        ldh.analyze_recording([[], [], []], [[], [], []], 100.0)
    with pytest.raises(ValueError):
        ldh.shapiro([])
    with pytest.raises(ValueError):
        ldh.lyap_r(np.array([]))
    with pytest.raises(ValueError):
        ldh.butter_filtfilt(np.array(["a", "b"]), 10.0, 100.0)
    with pytest.raises(ValueError):
        ldh.cross_validate(np.zeros((0, 3)), [])


def test_every_analysis_parameter_can_be_set_from_python(tmp_path):
    ldh.write_demo(tmp_path)
    rec, _ = ldh.read_recording(tmp_path / "H01" / "left.csv")
    acc = [rec["acc_x_g"], rec["acc_y_g"], rec["acc_z_g"]]
    gyro = [rec["gyro_x_dps"], rec["gyro_y_dps"], rec["gyro_z_dps"]]
    a = ldh.analyze_recording(acc, gyro, rec["fs_hz"], compute_sta=False)
    b = ldh.analyze_recording(acc, gyro, rec["fs_hz"], compute_sta=False, params={"attitude": {"smoother": False}})
    assert not np.array_equal(a["attitude"]["pitch_deg"], b["attitude"]["pitch_deg"])
    c = ldh.analyze(tmp_path / "H01", compute_sta=False, params={"events": {"detector": "pitch-peaks"}})
    d = ldh.analyze(tmp_path / "H01", compute_sta=False)
    assert not np.array_equal(c["recordings"]["stance_ratio"], d["recordings"]["stance_ratio"])
    with pytest.raises(ldh.LdhParamError, match="unknown field"):
        ldh.analyze(tmp_path / "H01", params={"attitude": {"smoothing": True}})
    with pytest.raises(ldh.LdhParamError, match="params must be a dict"):
        ldh.analyze(tmp_path / "H01", params="fast")


def test_empty_input_lists_raise_value_error(tmp_path):
    # Only None means the embedded demo: an empty list is a mistake, not a request (issue 19).
    for call in (lambda: ldh.analyze_many([]), lambda: ldh.analyze([]), lambda: ldh.analyze(())):
        with pytest.raises(ValueError, match="empty list|at least one input"):
            call()


def test_subject_id_and_setting_from_python_as_on_the_command_line(tmp_path):
    ldh.write_demo(tmp_path)
    files = [tmp_path / "L02" / "left.csv", tmp_path / "L02" / "right.csv"]
    # The demo walks there and back: overground, the turn's strides are flagged.
    over = ldh.analyze(files, compute_sta=False, as_frame=False)
    assert list(over["recordings"]["subject_id"]) == ["L02", "L02"]
    assert list(over["recordings"]["setting"]) == ["", ""], "not said"
    assert any("turn" in r.split("; ") for r in over["strides"]["reason_codes"])
    out = ldh.analyze(files, compute_sta=False, subject_id="patient-7", setting="treadmill", as_frame=False)
    assert list(out["recordings"]["subject_id"]) == ["patient-7", "patient-7"]
    assert list(out["recordings"]["setting"]) == ["treadmill", "treadmill"]
    assert not any("turn" in r.split("; ") for r in out["strides"]["reason_codes"])
    with pytest.raises(ldh.LdhParamError, match="setting"):
        ldh.analyze(files, setting="stairs")
    with pytest.raises(ldh.LdhParamError, match="setting"):
        ldh.analyze(files, setting=1)
    # A folder names its own subjects: subject_id is refused for it, as --subject is.
    with pytest.raises(ValueError, match="names its own subjects"):
        ldh.analyze(tmp_path / "L02", subject_id="x")

    # The same for arrays: a pair and one recording.
    left, _ = ldh.read_recording(files[0])
    right, _ = ldh.read_recording(files[1])
    pair = ldh.analyze_pair(left, right, subject_id="P9", setting="treadmill", compute_sta=False, as_frame=False)
    assert list(pair["recordings"]["subject_id"]) == ["P9", "P9"]
    assert list(pair["recordings"]["setting"]) == ["treadmill", "treadmill"]
    assert not any("turn" in r.split("; ") for r in pair["strides"]["reason_codes"])
    pair_over = ldh.analyze_pair(left, right, subject_id="P9", compute_sta=False, as_frame=False)
    assert any("turn" in r.split("; ") for r in pair_over["strides"]["reason_codes"])
    with pytest.raises(ldh.LdhParamError, match="setting"):
        ldh.analyze_pair(left, right, setting="stairs")
    acc = [left[c] for c in ("acc_x_g", "acc_y_g", "acc_z_g")]
    gyro = [left[c] for c in ("gyro_x_dps", "gyro_y_dps", "gyro_z_dps")]
    one = ldh.analyze_recording(acc, gyro, left["fs_hz"], compute_sta=False)
    belt = ldh.analyze_recording(acc, gyro, left["fs_hz"], compute_sta=False, setting="treadmill")
    assert any("turn" in r.split("; ") for r in one["strides"]["reason_codes"])
    assert not any("turn" in r.split("; ") for r in belt["strides"]["reason_codes"])
    assert len(belt["strides"]["reason"]) == len(one["strides"]["reason"])
    with pytest.raises(ldh.LdhParamError, match="setting"):
        ldh.analyze_recording(acc, gyro, left["fs_hz"], setting="stairs")


def test_n_jobs_is_bounded_by_the_cores_with_a_warning(tmp_path):
    import os
    import warnings

    ldh.write_demo(tmp_path)
    dirs = [tmp_path / "H01", tmp_path / "L01"]
    cores = os.cpu_count()
    # 10**6 threads would thrash the machine for minutes (issue 19): lowered to the cores.
    with pytest.warns(ldh.LdhWarning, match=r"1000000 worker threads requested, this machine has \d+ cores") as rec:
        big = ldh.analyze_many(dirs, n_jobs=10**6, compute_sta=False)
    assert rec[0].filename == __file__, "the warning points at the caller's line"
    one = ldh.analyze_many(dirs, n_jobs=1, compute_sta=False)
    np.testing.assert_array_equal(big["strides"]["stride_length_m"], one["strides"]["stride_length_m"])
    # Within the cores: no warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error", ldh.LdhWarning)
        ldh.analyze(dirs, n_jobs=max(1, min(2, cores or 1)), compute_sta=False)


def test_impossible_simulation_sizes_raise_value_error(tmp_path):
    out = tmp_path / "sim"
    cases = [
        (dict(seconds=86400, rate_hz=2000), "at most 1000000 samples (500 s at 2000.0 Hz)"),
        (dict(seconds=1e308), "at most 1000000 samples"),
        (dict(healthy=10**6, ldh=0), "at most 100000 subjects"),
        (dict(healthy=2**64 - 1, ldh=1), "at most 100000 subjects"),
        (dict(healthy=10**6, seed=2**64 - 1), "at most 100000 subjects"),
        (dict(healthy=10**30), "far more subjects"),
        (dict(healthy=-1), "non-negative int"),
        (dict(seed=-5), "non-negative int"),
    ]
    for kwargs, msg in cases:
        with pytest.raises(ValueError, match=msg.replace("(", r"\(").replace(")", r"\)")):
            ldh.simulate_cohort(out, **kwargs)
        assert not out.exists(), kwargs
