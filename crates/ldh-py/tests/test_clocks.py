"""Whether two arrays share one clock (``analyze_pair(clocks=...)``): the core's rule for two
files (docs/quality.md ``two_clocks``), read by the core's own ``Clocks``; the default for
arrays is two clocks (docs/python.md)."""

import numpy as np
import pytest

import ldh

CHANNELS = ("acc_x_g", "acc_y_g", "acc_z_g", "gyro_x_dps", "gyro_y_dps", "gyro_z_dps")


def _pair(tmp_path, late_s):
    """The demo's healthy H01 (one clock), the right sensor's clock ``late_s`` late: each
    right channel resampled at t - late_s, so its events fall ``late_s`` later."""
    ldh.write_demo(tmp_path)
    left, _ = ldh.read_recording(tmp_path / "H01" / "left.csv")
    right, _ = ldh.read_recording(tmp_path / "H01" / "right.csv")
    t = np.arange(len(right["acc_x_g"])) / right["fs_hz"]
    late = dict(right)
    for c in CHANNELS:
        late[c] = np.interp(t - late_s, t, np.asarray(right[c], dtype=float))
    return left, late


def _codes(res):
    return set(res.warnings["code"])


def test_a_55_ms_offset_is_withheld_from_two_clocks_and_kept_from_one(tmp_path):
    left, right = _pair(tmp_path, 0.055)
    run = lambda clocks: ldh.analyze_pair(left, right, subject_id="H01", compute_sta=False, clocks=clocks, as_frame=False)
    two, one, default = run("two"), run("one"), run(None)
    assert "two_clocks" in _codes(two)
    steps = two.recordings["step_time_s"]
    assert len(steps) == 2 and np.all(np.isnan(steps)), steps
    assert "two_clocks" not in _codes(one)
    assert np.all(np.isfinite(one.recordings["step_time_s"])), one.recordings["step_time_s"]
    # Arrays say nothing of their clocks: two, as two files would be.
    assert "two_clocks" in _codes(default)
    np.testing.assert_array_equal(default.recordings["stride_time_s"], two.recordings["stride_time_s"])
    # Each leg's own timings do not depend on the clocks.
    np.testing.assert_array_equal(one.recordings["stride_time_s"], two.recordings["stride_time_s"])
    # Case as the manifest's column: read by the same rule.
    assert "two_clocks" not in _codes(run("One"))


def test_a_bad_clocks_value_raises_naming_it(tmp_path):
    left, right = _pair(tmp_path, 0.0)
    with pytest.raises(ldh.LdhParamError, match="clocks.*three|three.*clocks"):
        ldh.analyze_pair(left, right, clocks="three")
    with pytest.raises(ldh.LdhParamError, match="clocks"):
        ldh.analyze_pair(left, right, clocks=2)
