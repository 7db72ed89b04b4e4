"""ldh.reliability: the test–retest table of repeated trials (issue 38 item 2), from a results
folder or a result in memory, as ``ldh stats --reliability`` computes it."""
import json

import numpy as np
import pytest

import ldh

COLUMNS = ["parameter", "code", "unit", "n_subjects", "k_trials", "icc_2_1", "icc_2_1_ci_low",
           "icc_2_1_ci_high", "icc_3_1", "icc_3_1_ci_low", "icc_3_1_ci_high", "sd_all", "sem",
           "sem_from_mse", "mdc95", "within_subject_cv", "between_subject_var",
           "within_subject_var", "withheld"]


def _weir(x):
    """ICC(2,1) (Shrout & Fleiss), SEM = SD·√(1 − ICC), MDC95 = 1.96·√2·SEM and the one-way
    variances of a people × trials array, written out independently of the core."""
    n, k = x.shape
    grand = x.mean()
    ss_rows = k * ((x.mean(axis=1) - grand) ** 2).sum()
    ss_cols = n * ((x.mean(axis=0) - grand) ** 2).sum()
    ss_err = ((x - grand) ** 2).sum() - ss_rows - ss_cols
    msr, msc, mse = ss_rows / (n - 1), ss_cols / (k - 1), ss_err / ((n - 1) * (k - 1))
    icc = (msr - mse) / (msr + (k - 1) * mse + k * (msc - mse) / n)
    msw = ((x - x.mean(axis=1, keepdims=True)) ** 2).sum() / (n * (k - 1))
    sem = x.std(ddof=1) * np.sqrt(1 - icc)
    return icc, sem, 1.96 * np.sqrt(2) * sem, (msr - msw) / k, msw


def _recording(subject, trial, side, stride_time_s):
    row = {k: None for k in [
        "fs_hz", "strides_total", "strides_valid", "step_time_s", "step_frequency_steps_per_s",
        "stance_ratio", "swing_ratio", "stride_length_m", "speed_mps", "stride_length_cv",
        "stride_time_cv", "sta_per_s", "sta_per_stride", "wqk_deg", "pbi_deg", "bdk_deg", "mirrored",
        "axial_rotation_deg", "outliers_replaced", "clipped_samples", "steady_start_s", "steady_end_s",
        "steady_excluded_start", "steady_excluded_end", "belt_speed_mps"]}
    row.update(subject_id=subject, side=side, model="fusion", group="", affected_side="", side_role="",
               source="", status="ok", error="", warnings=[], withheld={}, duration_s=30.0,
               stride_time_s=stride_time_s, sta_status="", trial_id=trial, setting="", visit="")
    return row


TRUE = np.array([[1.00, 1.04, 0.98], [1.10, 1.12, 1.15], [0.95, 0.93, 0.99], [1.20, 1.16, 1.21]])


@pytest.fixture()
def folder(tmp_path):
    """A hand-made ldh analyze folder: 4 people × 3 trials, left = v − 0.01, right = v + 0.01."""
    rows = []
    for i, person in enumerate(TRUE):
        for t, v in enumerate(person):
            rows.append(_recording(f"P{i}", f"T{t + 1}", "left", v - 0.01))
            rows.append(_recording(f"P{i}", f"T{t + 1}", "right", v + 0.01))
    (tmp_path / "recordings.json").write_text(json.dumps(rows))
    return tmp_path


def test_a_results_folder_gives_the_weir_mdc95_of_the_walk_values(folder):
    df = ldh.reliability(folder)
    assert list(df.columns) == COLUMNS
    assert len(df) == 14
    st = df.set_index("parameter").loc["stride_time_s"]
    assert (st["code"], st["unit"], st["n_subjects"], st["k_trials"], st["withheld"]) == ("ST", "s", 4, 3, "")
    icc, sem, mdc, between, within = _weir(TRUE)
    assert st["icc_2_1"] == pytest.approx(icc, abs=1e-12)
    assert st["sem"] == pytest.approx(sem, abs=1e-12)
    assert st["mdc95"] == pytest.approx(mdc, abs=1e-12)
    assert st["between_subject_var"] == pytest.approx(between, abs=1e-12)
    assert st["within_subject_var"] == pytest.approx(within, abs=1e-12)
    assert st["icc_2_1_ci_low"] < icc < st["icc_2_1_ci_high"]
    sl = df.set_index("parameter").loc["stride_length_m"]
    assert sl["withheld"].startswith("fewer than 2 people") and np.isnan(sl["mdc95"])
    # A wider interval at 99 %.
    st99 = ldh.reliability(folder, confidence_level=0.99).set_index("parameter").loc["stride_time_s"]
    assert st99["icc_2_1_ci_low"] < st["icc_2_1_ci_low"]


def test_a_simulated_retest_cohort_in_memory(tmp_path):
    manifest = ldh.simulate_cohort(tmp_path / "c", healthy=4, ldh=0, seconds=30.0, seed=5, turn=False, trials=3)
    assert manifest.startswith("subject_id,trial_id,group,")
    res = ldh.analyze(tmp_path / "c")
    df = ldh.reliability(res)
    assert len(df) == 14
    st = df.set_index("parameter").loc["stride_time_s"]
    assert (st["n_subjects"], st["k_trials"]) == (4, 3)
    # The walk values from the recordings table, people × trials, and Weir's MDC95 of them.
    rec = res.recordings
    walk = rec.groupby(["subject_id", "trial_id"])["stride_time_s"].mean().unstack().to_numpy()
    assert walk.shape == (4, 3)
    assert st["mdc95"] == pytest.approx(_weir(walk)[2], abs=1e-9)
    # The recordings table alone gives the same table.
    same = ldh.reliability(res.recordings)
    assert same.equals(df)


def test_refusals_are_typed(tmp_path, folder):
    ldh.simulate_cohort(tmp_path / "one", healthy=2, ldh=0, seconds=30.0, seed=5, turn=False)
    with pytest.raises(ldh.LdhDataError, match="no person has two or more trials.*trial_id"):
        ldh.reliability(ldh.analyze(tmp_path / "one"))
    with pytest.raises(ldh.LdhParamError, match="confidence_level"):
        ldh.reliability(folder, confidence_level=1.5)
    with pytest.raises(ldh.LdhFileNotFoundError):
        ldh.reliability(tmp_path / "missing")
    with pytest.raises(ldh.LdhParamError, match="trials"):
        ldh.simulate_cohort(tmp_path / "x", trials=0)
