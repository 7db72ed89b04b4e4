"""ldh.monitor on a synthetic hour: the demo walks between still periods (docs/free-living.md)."""
import numpy as np
import pytest

import ldh


def _leg(demo, side, seed):
    rng = np.random.default_rng(seed)
    parts = []

    def still(secs, tilt_deg):
        n = int(secs * 100)
        a = np.zeros((n, 6))
        a[:, 0] = np.cos(np.radians(tilt_deg))
        a[:, 1] = np.sin(np.radians(tilt_deg))
        a[:, :3] += rng.uniform(-0.004, 0.004, (n, 3))
        a[:, 3:] += rng.uniform(-0.5, 0.5, (n, 3))
        parts.append(a)

    still(120, 40)
    for subject in ("H01", "L01", "H02"):
        walk = np.loadtxt(demo / subject / f"{side}.csv", delimiter=",", skiprows=1)
        parts.append(walk[:, 1:])
        still(60, 40)
    x = np.vstack(parts)
    t = np.arange(len(x)) / 100.0
    return np.column_stack([t, x])


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("monitor")
    demo = d / "demo"
    ldh.write_demo(str(demo))
    out = []
    for k, side in enumerate(("left", "right")):
        p = d / f"{side}.csv"
        np.savetxt(p, _leg(demo, side, k), delimiter=",", fmt="%.5f",
                   header="time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z", comments="")
        out.append(str(p))
    return out


def test_monitor_finds_the_walks_and_returns_frames(files):
    r = ldh.monitor(files, subject_id="S1")
    assert isinstance(r, ldh.MonitorResult)
    bouts = r.bouts
    assert len(bouts["bout"]) == 3
    assert list(bouts["legs"]) == ["both"] * 3
    # Level walks: no bout labelled stairs, no median stride rising or falling like a stair
    # (NaN, an empty cell, when no stride's rise was vouched for).
    assert list(bouts["kind"]) == ["walking"] * 3
    assert not any(abs(r) >= 0.15 for r in bouts["stride_rise_m"]), list(bouts["stride_rise_m"])
    assert all(20 < d < 33 for d in bouts["duration_s"]), list(bouts["duration_s"])  # the 35 s demo walks
    assert len(r.days["day"]) == 1 and len(r.summary["subject_id"]) == 1
    # Under 12 h worn: the day's amounts are withheld with the reason.
    assert "not a valid day" in list(r.days["withheld"])[0]
    assert r.errors == [[]]


def test_monitor_bad_inputs_raise_typed_errors(tmp_path, files):
    with pytest.raises(ldh.LdhParamError):
        ldh.monitor(files, params={"no_such_field": 1})
    with pytest.raises(ldh.LdhParamError):
        ldh.monitor([])
    with pytest.raises(FileNotFoundError):
        ldh.monitor([str(tmp_path / "missing_left.csv"), str(tmp_path / "missing_right.csv")])


def test_a_missing_leg_file_is_an_error_row_not_an_exception(tmp_path, files):
    bad = tmp_path / "right.csv"
    bad.write_text("a,b\n1,2\n")
    r = ldh.monitor([files[0], str(bad)], subject_id="S2")
    assert len(r.bouts["bout"]) == 3
    assert any("no column 'time_s'" in e for e in r.errors[0])
