"""Python tests of the pipeline and Lyapunov functions."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import ldh

ROOT = pathlib.Path(__file__).resolve().parents[3]
LYAP = ROOT / "data-fixtures" / "golden" / "lyapunov"


def _series(g):
    return np.array(g["series"], dtype=np.float64)


@pytest.mark.parametrize("name", ["lorenz", "logistic", "noise", "gait"])
def test_lyap_r_equals_nolds_goldens(name):
    g = json.loads((LYAP / f"{name}.json").read_text())
    x = _series(g)
    for case in g["lyap_r"]:
        p = {k: v for k, v in case["params"].items() if k in
             ("emb_dim", "lag", "min_tsep", "tau", "min_neighbors", "trajectory_len", "fit_offset")}
        ours = ldh.lyap_r(x, fit="poly", **p)
        assert ours == pytest.approx(case["lyap"], rel=1e-6), (name, p)


@pytest.mark.parametrize("name", ["lorenz", "noise", "gait"])
def test_lyap_e_equals_nolds_goldens(name):
    g = json.loads((LYAP / f"{name}.json").read_text())
    x = _series(g)
    for case in g["lyap_e"]:
        p = {k: v for k, v in case["params"].items() if k in ("emb_dim", "matrix_dim", "min_nb", "min_tsep", "tau")}
        np.testing.assert_allclose(ldh.lyap_e(x, **p), case["lyap"], rtol=1e-6, atol=1e-9)


def test_lyapunov_errors():
    with pytest.raises(ldh.LdhDataError, match="at least 40 samples"):
        ldh.lyap_r(np.random.default_rng(0).standard_normal(20))
    with pytest.raises(ldh.LdhParamError, match="fit"):
        ldh.lyap_r(np.zeros(1000), fit="median")
    with pytest.raises(ValueError, match="NaN"):
        ldh.lyap_r(np.full(2000, np.nan))


def _cli():
    """The `ldh` the wheel is compared with: $LDH_CLI (CI: the release archive's binary), else one
    built in this tree."""
    if os.environ.get("LDH_CLI"):
        return pathlib.Path(os.environ["LDH_CLI"])
    for c in ["target/ci/ldh-under-test", "target/debug/ldh-under-test", "target/debug/ldh",
              "target/release/ldh", "target/ci/ldh"]:
        if (ROOT / c).exists():
            return ROOT / c
    return None


def test_analyze_demo_equals_the_cli(tmp_path):
    res = ldh.analyze()
    rec = res["recordings"]
    assert len(rec["subject_id"]) == 26 and set(rec["status"]) == {"ok"}
    assert np.all((rec["stride_time_s"] > 0.9) & (rec["stride_time_s"] < 1.4))
    assert np.all(rec["sta_per_s"] > 0)
    assert set(res["events"]["event"]) == {"HS", "TO"}
    # wall time per stage, as `ldh analyze --timings` (issue 17)
    stages = ["read", "preprocess", "align", "attitude", "events", "strides", "sta", "write"]
    t = res.timings
    assert t["subjects"] == 13 and t["recordings"] == 26 and t["total_s"] > 0
    assert all(t[f"{s}_s"] >= 0 for s in stages) and t["sta_s"] > 0 and t["attitude_s"] > 0
    table = res.timings_table()
    assert list(table["stage"]) == stages
    assert list(table["seconds"]) == [t[f"{s}_s"] for s in stages]
    cli = _cli()
    if cli is None:
        pytest.skip("no ldh binary built (run cargo test or cargo build first)")
    subprocess.run([str(cli), "analyze", "--out", str(tmp_path)], check=True, capture_output=True)
    ref = json.loads((tmp_path / "recordings.json").read_text())
    assert [r["subject_id"] for r in ref] == list(rec["subject_id"])
    for key in ["stride_time_s", "stance_ratio", "stride_length_m", "sta_per_s", "wqk_deg"]:
        np.testing.assert_array_equal(rec[key], np.array([r[key] for r in ref], dtype=float))
    strides = json.loads((tmp_path / "strides.json").read_text())
    assert len(strides) == len(res["strides"]["subject_id"])


def test_analyze_reports_bad_files_without_raising(tmp_path):
    ldh.write_demo(tmp_path)
    (tmp_path / "H01" / "right.csv").write_text("garbage\n")
    res = ldh.analyze(tmp_path, compute_sta=False)
    rec = res["recordings"]
    i = [k for k, (s, side) in enumerate(zip(rec["subject_id"], rec["side"])) if s == "H01" and side == "right"][0]
    assert rec["status"][i] == "error" and "H01/right.csv" in rec["error"][i]
    assert list(rec["status"]).count("ok") == 2 * 13 - 1  # the 13-person demo, one leg broken
    with pytest.raises(ldh.LdhParamError, match="fusion"):
        ldh.analyze(tmp_path, model="kalman")


def test_a_sensor_height_not_given_is_said_in_the_warnings(tmp_path):
    # Issue 20: without a height (a manifest without the column, no sensor_height_m=) each leg's
    # stride length used an assumed 0.10 m and the warnings table says so (``sensor_height_unknown``;
    # a simulated family-a shank hardly turns at mid-stance, so it is a note and the lengths are
    # reported). Given, by the column or by the option, nothing is said.
    ldh.simulate_cohort(tmp_path, healthy=1, ldh=0, seconds=20, seed=3)
    lines = (tmp_path / "manifest.csv").read_text().splitlines()
    col = lines[0].split(",").index("sensor_height_m")
    drop = lambda line: ",".join(c for k, c in enumerate(line.split(",")) if k != col)
    (tmp_path / "no_height.csv").write_text("\n".join(drop(x) for x in lines) + "\n")
    none = ldh.analyze(tmp_path / "no_height.csv", compute_sta=False)
    w = none.warnings
    rows = [k for k, c in enumerate(w["code"]) if c == "sensor_height_unknown"]
    assert sorted(w["side"][k] for k in rows) == ["left", "right"]
    for k in rows:
        assert w["severity"][k] == "note" and list(w["affects"][k]) == []
        assert "0.10 m above the ankle was assumed" in w["message"][k]
    assert np.all(np.isfinite(none["recordings"]["stride_length_m"]))
    for given in (ldh.analyze(tmp_path / "manifest.csv", compute_sta=False),
                  ldh.analyze(tmp_path / "no_height.csv", compute_sta=False, sensor_height_m=0.1)):
        assert "sensor_height_unknown" not in list(given.warnings["code"])
        np.testing.assert_array_equal(given["recordings"]["stride_time_s"], none["recordings"]["stride_time_s"])


def test_path_functions_refuse_data_with_a_typeerror_naming_the_array_functions(tmp_path):
    """``ldh.analyze(df)`` used to read the column names as paths ("time_s: cannot read") and
    ``ldh.analyze(123)`` raised a bare ``'int' object is not iterable`` (issue 51)."""
    data = {"time_s": np.arange(3.0), "acc_x_g": np.ones(3)}
    for bad, kind in ((123, "an int"), (data, "a dict"), (np.zeros((3, 7)), "a numpy ndarray")):
        with pytest.raises(ldh.LdhTypeError, match=rf"ldh\.analyze\(\): inputs must be a path .* got {kind}; .*ldh\.analyze_pair\(left, right, fs_hz\)"):
            ldh.analyze(bad)
    with pytest.raises(TypeError, match=r"ldh\.analyze\(\): inputs\[1\] must be a path .* got a float"):
        ldh.analyze([tmp_path, 1.5])
    with pytest.raises(TypeError, match=r"ldh\.read_recording\(\): path must be a path .*ldh\.analyze_recording"):
        ldh.read_recording(data)
    with pytest.raises(TypeError, match=r"ldh\.analyze_many\(\)"):
        ldh.analyze_many(7)
    pd = pytest.importorskip("pandas")
    with pytest.raises(TypeError, match=r"got a pandas DataFrame; for arrays or DataFrames in memory use ldh\.analyze_pair"):
        ldh.analyze(pd.DataFrame(data))
    # Paths still pass as str, os.PathLike, lists, tuples and other iterables of them.
    with pytest.raises(ldh.LdhFileNotFoundError, match="no such file or folder"):
        ldh.analyze(iter([tmp_path / "a.csv", str(tmp_path / "b.csv")]))
