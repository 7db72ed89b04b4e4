"""Python tests of the foundations: parity with scipy, errors, demo data."""
import json
import pathlib

import numpy as np
import pytest
from scipy import signal

import ldh

ROOT = pathlib.Path(__file__).resolve().parents[3]
GOLDEN = ROOT / "data-fixtures" / "golden" / "preprocess"


@pytest.mark.parametrize("order,cutoff,fs", [(2, 5.0, 100.0), (4, 10.0, 100.0), (6, 20.0, 200.0)])
def test_butter_filtfilt_equals_scipy(order, cutoff, fs):
    x = np.random.default_rng(1).standard_normal(500)
    ref = signal.sosfiltfilt(signal.butter(order, cutoff, output="sos", fs=fs), x)
    ours = ldh.butter_filtfilt(x, cutoff, fs, order)
    np.testing.assert_allclose(ours, ref, rtol=1e-9, atol=1e-12 * np.abs(ref).max())


def test_any_array_like_is_accepted():
    x = np.random.default_rng(2).standard_normal(400)
    ref = ldh.butter_filtfilt(x, 10.0, 100.0)
    np.testing.assert_array_equal(ldh.butter_filtfilt(x.astype(np.float32).astype(np.float64), 10.0, 100.0),
                                  ldh.butter_filtfilt(x.astype(np.float32), 10.0, 100.0))
    np.testing.assert_array_equal(ldh.butter_filtfilt(list(x), 10.0, 100.0), ref)
    np.testing.assert_array_equal(ldh.butter_filtfilt(np.repeat(x, 2)[::2], 10.0, 100.0), ref)


def test_preprocess_matches_the_golden_file():
    rec, report = ldh.read_recording(GOLDEN / "input.csv")
    g = json.loads((GOLDEN / "expected.json").read_text())
    acc = [rec["acc_x_g"], rec["acc_y_g"], rec["acc_z_g"]]
    gyro = [rec["gyro_x_dps"], rec["gyro_y_dps"], rec["gyro_z_dps"]]
    pairs = [("acc_x_g", "acc_x"), ("acc_y_g", "acc_y"), ("gyro_z_dps", "gyro_z")]
    # Default: acceleration-magnitude outliers replaced on the acceleration channels only.
    out = ldh.preprocess(acc, gyro, rec["fs_hz"])
    assert out["replaced"].tolist() == g["outliers"]
    for ours, name in pairs:
        ref = np.asarray(g["filtered_acc_outliers_only"][name])
        np.testing.assert_allclose(out[ours], ref, rtol=1e-9, atol=1e-12 * np.abs(ref).max())
    # The paper read literally: all six channels.
    out = ldh.preprocess(acc, gyro, rec["fs_hz"], outlier_channels="all")
    for ours, name in pairs:
        ref = np.asarray(g["filtered"][name])
        np.testing.assert_allclose(out[ours], ref, rtol=1e-9, atol=1e-12 * np.abs(ref).max())
    assert report["format"] == "ldh" and report["samples"] == 800


def test_errors_are_typed_and_name_the_problem(tmp_path):
    with pytest.raises(FileNotFoundError) as e:
        ldh.read_recording(tmp_path / "missing.csv")
    assert isinstance(e.value, ldh.LdhError) and "missing.csv" in str(e.value)
    # A misspelt input to analyze raises before any work instead of returning error rows.
    with pytest.raises(FileNotFoundError, match="no/such/folder"):
        ldh.analyze("no/such/folder")
    bad = tmp_path / "bad.csv"
    bad.write_text("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n0,1,0,0,0,0,x\n")
    with pytest.raises(ValueError, match=r"bad.csv:2:7.*'x' is not a number"):
        ldh.read_recording(bad)
    with pytest.raises(ldh.LdhParamError, match="cutoff_hz"):
        ldh.butter_filtfilt(np.zeros(100), 60.0, 100.0)
    with pytest.raises(ldh.LdhDataError, match="too short"):
        ldh.butter_filtfilt(np.zeros(10), 10.0, 100.0)
    with pytest.raises(ldh.LdhDataError, match="non-finite"):
        ldh.butter_filtfilt(np.array([1.0, np.nan] * 20), 10.0, 100.0)
    with pytest.raises(ldh.LdhParamError, match="one-dimensional"):
        ldh.butter_filtfilt(np.zeros((10, 10)), 10.0, 100.0)
    with pytest.raises(ldh.LdhParamError, match="gap_policy"):
        ldh.read_recording(bad, gap_policy="maybe")


def test_demo_and_simulation_are_deterministic(tmp_path):
    assert ldh.write_demo(tmp_path / "demo") == 2 * 13 + 2  # two legs of 13 people, manifest, cohort.json
    m1 = ldh.simulate_cohort(tmp_path / "a", healthy=1, ldh=1, seconds=14, seed=5)
    m2 = ldh.simulate_cohort(tmp_path / "b", healthy=1, ldh=1, seconds=14, seed=5)
    assert m1 == m2
    assert (tmp_path / "a" / "L01" / "left.csv").read_bytes() == (tmp_path / "b" / "L01" / "left.csv").read_bytes()
    with pytest.raises(ldh.LdhParamError, match="at least 14 s"):
        ldh.simulate_cohort(tmp_path / "c", seconds=12)
    rec, report = ldh.read_recording(tmp_path / "demo" / "H01" / "left.csv")
    assert abs(rec["fs_hz"] - 100.0) < 1e-9 and len(rec["time_s"]) == 3501


def test_slow_ldh_subjects_come_last_and_leave_the_others_unchanged(tmp_path):
    # as `ldh simulate --slow-ldh`: ids S01…, own random streams, slower strides
    m0 = ldh.simulate_cohort(tmp_path / "a", healthy=1, ldh=1, seconds=30, seed=7, turn=False)
    m1 = ldh.simulate_cohort(tmp_path / "b", healthy=1, ldh=1, seconds=30, seed=7, turn=False, slow_ldh=2)
    assert m0.splitlines() == m1.splitlines()[: len(m0.splitlines())]
    assert [line.split(",")[0] for line in m1.splitlines()[-2:]] == ["S01", "S02"]
    for sid in ("H01", "L01"):
        assert (tmp_path / "a" / sid / "left.csv").read_bytes() == (tmp_path / "b" / sid / "left.csv").read_bytes()
    slow = ldh.analyze(tmp_path / "b" / "S01", as_frame=False).recordings["stride_time_s"]
    normal = ldh.analyze(tmp_path / "b" / "L01", as_frame=False).recordings["stride_time_s"]
    # the CLI gives 1.576 / 1.574 s (S01) and 1.106 / 1.104 s (L01) for this cohort
    assert len(slow) == 2 and np.all((slow >= 1.3) & (slow <= 2.1)), slow
    assert np.all(slow > normal), (slow, normal)
    with pytest.raises(ldh.LdhParamError, match="slow_ldh"):
        ldh.simulate_cohort(tmp_path / "c", slow_ldh=-1)


def test_a_two_g_accelerometer_clips_and_the_stride_length_is_still_reported(tmp_path):
    # as `ldh simulate --acc-range-g 2` (tests/tests/cli_foundations.rs does the same through the CLI)
    m8 = ldh.simulate_cohort(tmp_path / "g8", healthy=1, ldh=0, seconds=20, seed=3)
    m2 = ldh.simulate_cohort(tmp_path / "g2", healthy=1, ldh=0, seconds=20, seed=3, acc_range_g=2.0)
    assert m8 == m2
    _, r8 = ldh.read_recording(tmp_path / "g8" / "H01" / "left.csv")
    _, r2 = ldh.read_recording(tmp_path / "g2" / "H01" / "left.csv")
    assert r8["saturated_samples"] == 0 and r2["saturated_samples"] > 50, (r8, r2)
    rows = ldh.analyze(tmp_path / "g2", as_frame=False).recordings
    assert np.all(np.isfinite(rows["stride_length_m"])), rows["withheld"]
    with pytest.raises(ldh.LdhParamError, match="acc_range_g"):
        ldh.simulate_cohort(tmp_path / "c", acc_range_g=-1.0)


def test_a_belt_start_up_is_simulated_and_left_out_of_the_means(tmp_path):
    # as `ldh simulate --no-turn --ramp-s 10` (issue 36): the start-up strides are excluded as
    # not steady, and recordings say the window
    m = ldh.simulate_cohort(tmp_path / "r", healthy=1, ldh=0, seconds=60, seed=4, turn=False, ramp_s=10.0)
    header, first = (line.split(",") for line in m.splitlines()[:2])
    assert first[header.index("setting")] == "treadmill", m
    assert first[header.index("clocks")] == "one", m  # both legs simulated on one clock
    out = ldh.analyze(tmp_path / "r", as_frame=False)
    rec, st = out.recordings, out.strides
    assert np.all(rec["steady_excluded_start"] >= 2), rec["steady_excluded_start"]
    assert np.all(rec["steady_start_s"] > 3.0), rec["steady_start_s"]
    # one window and one cadence per walk, the same on both legs' rows (issue 50)
    for col in ("steady_start_s", "steady_end_s", "walk_cadence_steps_per_min"):
        assert rec[col][0] == rec[col][1], (col, rec[col])
    reasons = [r for r in st["reason_codes"] if "not_steady" in r.split("; ")]
    assert len(reasons) >= 4, reasons
    with pytest.raises(ldh.LdhParamError, match="ramp_s"):
        ldh.simulate_cohort(tmp_path / "t", ramp_s=10.0)  # with the turn: refused
