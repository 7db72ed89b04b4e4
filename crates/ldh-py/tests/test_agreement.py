"""ldh.agree: an ldh analyze output folder against reference files (issue 38 item 1)."""
import json

import numpy as np
import pytest

import ldh

SUBJECTS = ["H01", "H02", "L01", "L02"]
STRIDE_COLUMNS = ["subject_id", "side", "model", "stride_index", "bout", "hs_time_s", "to_time_s",
                  "next_hs_time_s", "stride_time_s", "stance_ratio", "double_support_ratio",
                  "stride_length_m", "speed_mps",
                  "wqk_deg", "pbi_deg", "bdk_deg", "heading_change_deg", "valid", "reason", "trial_id"]


def _recording(subject, side, stride_time_s):
    row = {k: None for k in [
        "fs_hz", "strides_total", "strides_valid", "step_time_s", "step_frequency_steps_per_s",
        "stance_ratio", "swing_ratio", "stride_length_m", "speed_mps", "stride_length_cv",
        "stride_time_cv", "sta_per_s", "sta_per_stride", "wqk_deg", "pbi_deg", "bdk_deg", "mirrored",
        "axial_rotation_deg", "outliers_replaced", "clipped_samples", "steady_start_s", "steady_end_s",
        "steady_excluded_start", "steady_excluded_end", "belt_speed_mps"]}
    row.update(subject_id=subject, side=side, model="fusion", group="", affected_side="", side_role="",
               source="", status="ok", error="", warnings=[], withheld={}, duration_s=30.0,
               stride_time_s=stride_time_s, sta_status="", trial_id="", setting="", visit="")
    return row


@pytest.fixture()
def results(tmp_path):
    """A hand-made ldh analyze folder: per subject and side, 20 strides of a known time."""
    rng = np.random.default_rng(38)
    recs, strides, events = [], [], ["subject_id,time_s,side,event,order,trial_id"]
    truth = {}
    for i, s in enumerate(SUBJECTS):
        for side in ["left", "right"]:
            st = 0.95 + 0.05 * i + (0.01 if side == "right" else 0.0)
            hs = 1.0 + st * np.arange(21)
            truth[(s, side)] = hs
            for k in range(20):
                strides.append([s, side, "fusion", k, 0, hs[k], hs[k] + 0.6 * st, hs[k + 1], st, 0.6,
                                "", 1.2, 1.2 / st, "", "", "", "", "true", "", ""])
            for t in hs:
                events.append(f"{s},{t},{side},HS,,")
            recs.append(_recording(s, side, st + rng.normal(0, 0.01)))
    d = tmp_path / "res"
    d.mkdir()
    (d / "recordings.json").write_text(json.dumps(recs))
    (d / "strides.csv").write_text(",".join(STRIDE_COLUMNS) + "\n"
                                   + "\n".join(",".join(str(c) for c in r) for r in strides) + "\n")
    (d / "events.csv").write_text("\n".join(events) + "\n")
    return d, truth


def test_agree_estimates_the_offset_matches_events_and_compares_parameters(results, tmp_path):
    d, truth = results
    rng = np.random.default_rng(1)
    ev = ["subject_id,side,event,time_s"]
    for (s, side), hs in truth.items():
        for t in hs:
            ev.append(f"{s},{side},HS,{t + 0.75 + rng.normal(0, 0.005)}")
    (tmp_path / "ev.csv").write_text("\n".join(ev) + "\n")
    rec = ["subject_id,side,stride_time_s"]
    ref_st = {}
    for (s, side), hs in truth.items():
        ref_st[(s, side)] = float(np.diff(hs).mean()) + rng.normal(0, 0.02)
        rec.append(f"{s},{side},{ref_st[(s, side)]}")
    (tmp_path / "rec.csv").write_text("\n".join(rec) + "\n")

    r = ldh.agree(d, [tmp_path / "ev.csv", tmp_path / "rec.csv"], offset_s="estimate")
    assert len(r["offsets"]) == 4
    for o in r["offsets"]:
        assert o["source"] == "estimated"
        assert o["offset_s"] == pytest.approx(-0.75, abs=0.01)
    both = next(e for e in r["events"] if e["event"] == "HS" and e["side"] == "both")
    assert both["summary"]["recall"] == 1.0 and both["summary"]["n_matched"] == 8 * 21
    p = next(p for p in r["parameters"] if p["level"] == "recording" and p["parameter"] == "stride_time_s")
    ldh_v = np.array([q["ldh"] for q in p["pairs"]])
    ref_v = np.array([q["reference"] for q in p["pairs"]])
    assert p["agreement"]["n_pairs"] == 8
    assert p["agreement"]["limits"]["bias"] == pytest.approx(np.mean(ldh_v - ref_v), abs=1e-12)
    assert p["agreement"]["mae"] == pytest.approx(np.mean(np.abs(ldh_v - ref_v)), abs=1e-12)
    rows = {(t["level"], t["quantity"], t["side"]) for t in r["table"]}
    assert ("recording", "stride_time_s", "both") in rows and ("events", "HS", "left") in rows
    pd = pytest.importorskip("pandas")
    frame = pd.DataFrame(r["table"])
    assert len(frame) == len(r["table"]) and {"level", "quantity", "side", "bias", "icc_2_1"} <= set(frame.columns)
    row = frame[(frame.level == "recording") & (frame.quantity == "stride_time_s")].iloc[0]
    assert row["bias"] == pytest.approx(np.mean(ldh_v - ref_v), abs=1e-12)

    # The result object: agreement.csv in its column order, the event errors in s with the unit
    # in their names, the parameters in their own unit.
    assert isinstance(r, ldh.Agreement) and isinstance(r.table, pd.DataFrame)
    assert list(r.table.columns[:8]) == ["level", "quantity", "side", "group", "n_ldh", "n_reference", "n_matched", "n_dropped"]
    assert list(r.table.columns[-1:]) == ["note"] and len(r.table) == len(r["table"])
    hs = r.events[(r.events.quantity == "HS") & (r.events.side == "both")].iloc[0]
    assert {"bias_s", "sd_s", "mae_s", "p95_abs_s"} <= set(r.events.columns)
    assert "icc_2_1" not in r.events.columns and "bias" not in r.events.columns
    assert hs["bias_s"] == pytest.approx(both["summary"]["bias_s"], abs=1e-12)
    st = r.parameters[(r.parameters.level == "recording") & (r.parameters.quantity == "stride_time_s")].iloc[0]
    assert st["bias"] == pytest.approx(np.mean(ldh_v - ref_v), abs=1e-12)
    assert "recall" not in r.parameters.columns
    assert list(r.offsets.columns) == ["subject_id", "trial_id", "offset_s", "source"] and len(r.offsets) == 4
    plain = ldh.agree(d, [tmp_path / "ev.csv", tmp_path / "rec.csv"], offset_s="estimate", as_frame=False)
    assert isinstance(plain.table["bias"], np.ndarray) and list(plain.table)[:3] == ["level", "quantity", "side"]


def test_bad_reference_and_bad_arguments_raise_typed_errors(results, tmp_path):
    d, _ = results
    bad = tmp_path / "bad.csv"
    bad.write_text("subject_id,side,event,time_s\nH01,left,HS,2\nH01,left,HS,1\n")
    with pytest.raises(ldh.LdhDataError, match=r"bad\.csv:3:4: .*earlier than 2 s on line 2"):
        ldh.agree(d, bad)
    bad.write_text("subject_id,side,event,time_s\nX9,left,HS,2\n")
    with pytest.raises(ValueError, match="X9"):
        ldh.agree(d, bad)
    with pytest.raises(ldh.LdhParamError, match="offset_s"):
        ldh.agree(d, bad, offset_s="soon")
    with pytest.raises(ldh.LdhParamError, match="tolerance_s"):
        ldh.agree(d, bad, tolerance_s=-1.0)
    with pytest.raises(ldh.LdhFileNotFoundError):
        ldh.agree(d, tmp_path / "missing.csv")
    with pytest.raises(TypeError, match=r"ldh\.agree\(\): results_dir must be a path .* got a dict"):
        ldh.agree({"level": []}, bad)


def test_write_params_calibrates_the_events_to_the_reference(results, tmp_path):
    """``write_params`` (``ldh agree --write-params``): the shifts are minus the mean errors, and
    the file is the run's parameters as TOML with ``[events.calibration]``."""
    d, truth = results
    lines = (d / "events.csv").read_text().splitlines()
    for (s, side), hs in truth.items():
        st = hs[1] - hs[0]
        lines += [f"{s},{t + 0.6 * st},{side},TO,," for t in hs[:-1]]
    (d / "events.csv").write_text("\n".join(lines) + "\n")
    ev = ["subject_id,side,event,time_s"]
    for (s, side), hs in truth.items():
        st = hs[1] - hs[0]
        ev += [f"{s},{side},HS,{t + 0.030}" for t in hs]
        ev += [f"{s},{side},TO,{t + 0.6 * st - 0.020}" for t in hs[:-1]]
    (tmp_path / "plates.csv").write_text("\n".join(ev) + "\n")
    out = tmp_path / "calibration.toml"
    ldh.agree(d, tmp_path / "plates.csv", write_params=out, reference_system="force plates")
    text = out.read_text()
    assert text.startswith("# Written by `ldh agree --write-params`. Gait events calibrated against force plates")
    section = text[text.index("[events.calibration]"):]
    values = dict(line.split(" = ", 1) for line in section.splitlines()[1:] if " = " in line)
    assert float(values["hs_shift_s"]) == pytest.approx(0.030, abs=1e-9)
    assert float(values["to_shift_s"]) == pytest.approx(-0.020, abs=1e-9)
    assert values["detector"] == '"gyro-bracket"'
    # Too few matched events: refused, nothing written.
    few = tmp_path / "few.csv"
    few.write_text("subject_id,side,event,time_s\nH01,left,HS,1.03\nH01,left,TO,1.55\n")
    with pytest.raises(ldh.LdhDataError, match="at least 20 matched events"):
        ldh.agree(d, few, write_params=tmp_path / "no.toml")
    assert not (tmp_path / "no.toml").exists()
