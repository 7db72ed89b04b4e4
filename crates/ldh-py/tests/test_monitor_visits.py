"""ldh.monitor on a manifest of two people and two visits (issue 52): the tables, and the change
of daily walking between the visits as a DataFrame (``changes``, as changes.csv). The
recordings are the demo's lab walks between still periods, two calendar days a visit for P1
(one for P2), every walk played slower at the second visit: the cadence falls, beyond the
day-to-day noise for P1; P2's change is withheld with the reason (one valid day a visit)."""
import pathlib

import numpy as np
import pytest

import ldh

pd = pytest.importorskip("pandas")

FS_HZ = 100.0
# Each visit plays the demo walks this much slower (stride time x factor): 1.2 keeps every
# walk over 30 s (the daily cadence is of walks over 30 s), 1.5 is 20 % fewer steps a minute.
FACTORS = {"pre": 1.2, "post": 1.5}
# The day's walks (one day: three demo people's walks, each followed by a minute still).
DAY_WALKS = (("H01", "H02", "H03"), ("H04", "H05", "H06"))
PARAMS = {"min_wear_h": 0.05, "min_valid_days": 2, "min_long_bouts": 1}


def _slower(walk, factor):
    """A walk played `factor` times slower: resampled in time, angular rates divided."""
    n = len(walk)
    at = np.arange(int(round(n * factor))) / factor
    out = np.column_stack([np.interp(at, np.arange(n), walk[:, k]) for k in range(6)])
    out[:, 3:] /= factor
    return out


def _leg(demo, side, days, factor, rng):
    rows = []
    for d in range(days):
        parts = []

        def still(secs):
            a = np.zeros((int(secs * FS_HZ), 6))
            a[:, 0] = np.cos(np.radians(40.0))
            a[:, 1] = np.sin(np.radians(40.0))
            a[:, :3] += rng.uniform(-0.004, 0.004, (len(a), 3))
            a[:, 3:] += rng.uniform(-0.5, 0.5, (len(a), 3))
            parts.append(a)

        still(120)
        for who in DAY_WALKS[d]:
            walk = np.loadtxt(demo / who / f"{side}.csv", delimiter=",", skiprows=1)[:, 1:]
            parts.append(_slower(walk, factor))
            still(60)
        x = np.vstack(parts)
        # Day d starts 24 h after day 0 (the device recorded a few minutes a day).
        t = d * 86400.0 + np.arange(len(x)) / FS_HZ
        rows.append(np.column_stack([t, x]))
    return np.vstack(rows)


@pytest.fixture(scope="module")
def manifest(tmp_path_factory):
    d = tmp_path_factory.mktemp("visits")
    demo = d / "demo"
    ldh.write_demo(str(demo))
    rng = np.random.default_rng(7)
    lines = ["subject_id,trial_id,visit,left,right"]
    for person, days in (("P1", 2), ("P2", 1)):
        for visit, factor in FACTORS.items():
            names = []
            for side in ("left", "right"):
                name = f"{person}_{visit}_{side}.csv"
                np.savetxt(d / name, _leg(demo, side, days, factor, rng), delimiter=",",
                           fmt="%.5f", comments="",
                           header="# start: 2024-03-05T10:00:00\n"
                                  "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z")
                names.append(name)
            lines.append(f"{person},{visit},{visit},{names[0]},{names[1]}")
    m = d / "manifest.csv"
    m.write_text("\n".join(lines) + "\n")
    return str(m)


@pytest.fixture(scope="module")
def result(manifest):
    return ldh.monitor(manifest, params=PARAMS, n_jobs=2)


def test_the_tables_have_every_person_and_visit(result):
    r = result
    assert r.errors == [[], [], [], []]
    pairs = list(zip(r.summary["subject_id"], r.summary["visit"]))
    assert pairs == [("P1", "pre"), ("P1", "post"), ("P2", "pre"), ("P2", "post")]
    assert list(r.summary["valid_days"]) == [2, 2, 1, 1]
    assert list(r.summary["valid"]) == [True, True, False, False]
    # Three walks a day.
    assert list(r.summary["bouts_total"]) == [6, 6, 3, 3]
    assert set(r.days["date"]) == {"2024-03-05", "2024-03-06"}
    assert r.days["valid"].all()


def test_the_visit_change_is_a_frame_with_the_slower_walking_found(result):
    c = result.changes
    assert isinstance(c, pd.DataFrame)
    assert list(c.columns) == [
        "subject_id", "from_visit", "to_visit", "measure", "unit", "days_from", "days_to",
        "mean_from", "mean_to", "change", "noise", "beyond_noise", "withheld",
    ]
    assert len(c) == 8
    cad = c[c["measure"] == "cadence_steps_per_min"].set_index("subject_id")
    for who in ("P1", "P2"):
        row = cad.loc[who]
        assert (row["from_visit"], row["to_visit"]) == ("pre", "post")
        # 1.2 / 1.5: the cadence falls by about 20 %.
        ratio = row["mean_to"] / row["mean_from"]
        assert 0.72 < ratio < 0.86, (who, row["mean_from"], row["mean_to"])
        assert row["change"] < 0
    assert cad.loc["P1", "beyond_noise"] == True  # noqa: E712 (an object column: True, False or None)
    assert cad.loc["P1", "noise"] > 0 and cad.loc["P1", "withheld"] == ""
    # P2: one valid day a visit, no day-to-day noise: not judged, with the reason.
    assert cad.loc["P2", "beyond_noise"] is None
    assert np.isnan(cad.loc["P2", "noise"])
    assert "1 and 1 valid day(s)" in cad.loc["P2", "withheld"]
    # Walking time per day grows with the slower walks (the same walks take longer).
    walk = c[(c["measure"] == "walking_min") & (c["subject_id"] == "P1")].iloc[0]
    assert walk["change"] > 0


def test_one_period_gives_an_empty_change_frame(manifest, tmp_path):
    folder = pathlib.Path(manifest).parent
    head, first = open(manifest).read().splitlines()[:2]
    cells = [str(folder / x) if x.endswith(".csv") else x for x in first.split(",")]
    one = tmp_path / "one.csv"
    one.write_text(head + "\n" + ",".join(cells) + "\n")
    r = ldh.monitor(str(one), params=PARAMS)
    assert len(r.changes) == 0
    assert "measure" in r.changes.columns
