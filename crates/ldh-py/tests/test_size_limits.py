"""The reader's size limits through the Python API (issue 19): ``max_file_size_mb=`` and
``max_samples=`` of ``read_recording``, ``analyze`` and ``analyze_many`` are the CLI's
``--max-file-size-mb`` / ``--max-samples`` with the core's defaults and meaning: over a limit,
the file is refused with a message naming it (an exception from ``read_recording``, that
recording's error row in a batch); the defaults accept the demo data."""
import math
import pathlib

import numpy as np
import pytest

import ldh


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    d = tmp_path_factory.mktemp("demo")
    ldh.write_demo(d)
    return d


def _rows(path):
    """Data rows of a demo CSV (one header line, no comments)."""
    lines = pathlib.Path(path).read_text().splitlines()
    assert not any(l.startswith("#") for l in lines)
    return len([l for l in lines[1:] if l.strip()])


def _first_recording(demo):
    return sorted(demo.glob("*/left.csv"))[0]


def test_the_defaults_accept_the_demo_data(demo):
    rec, report = ldh.read_recording(_first_recording(demo))
    assert len(rec["acc_x_g"]) == _rows(_first_recording(demo))
    res = ldh.analyze(demo, as_frame=False)
    assert set(res.recordings["status"]) == {"ok"} and len(res.recordings["status"]) == 26
    assert len(res.errors["error"]) == 0
    many = ldh.analyze_many([demo], n_jobs=1, as_frame=False)
    assert set(many.recordings["status"]) == {"ok"}


def test_the_python_defaults_are_the_core_defaults():
    core = ldh._ldh.defaults()
    assert core["read_limits"] == {"max_file_size_mb": 256.0, "max_samples": 2_500_000}
    assert {k: core["read_recording"][k] for k in core["read_limits"]} == core["read_limits"]


def test_a_recording_at_the_sample_limit_is_read_and_one_row_more_is_refused(demo):
    path = _first_recording(demo)
    n = _rows(path)
    rec, _ = ldh.read_recording(path, max_samples=n)
    assert len(rec["gyro_z_dps"]) == n
    with pytest.raises(ldh.LdhDataError) as e:
        ldh.read_recording(path, max_samples=n - 1)
    msg = str(e.value)
    assert str(path) in msg and f"{n} data rows" in msg and f"limit of {n - 1} samples" in msg, msg
    assert "max_samples" in msg
    assert isinstance(e.value, ValueError)


def test_a_small_file_size_limit_refuses_the_file_naming_it(demo):
    path = _first_recording(demo)
    size_mb = path.stat().st_size / 1e6
    with pytest.raises(ldh.LdhDataError) as e:
        ldh.read_recording(path, max_file_size_mb=size_mb / 2)
    msg = str(e.value)
    assert str(path) in msg and "above the limit" in msg and "max_file_size_mb" in msg, msg
    rec, _ = ldh.read_recording(path, max_file_size_mb=size_mb * 1.01)
    assert len(rec["acc_x_g"]) == _rows(path)


@pytest.mark.parametrize("fn", [ldh.analyze, ldh.analyze_many], ids=["analyze", "analyze_many"])
@pytest.mark.parametrize("limit", [{"max_samples": 100}, {"max_file_size_mb": 0.01}], ids=["samples", "size"])
def test_in_a_batch_each_recording_over_a_limit_is_an_error_row_naming_its_file(demo, fn, limit):
    res = fn([demo], n_jobs=1, as_frame=False, **limit)
    rec = res.recordings
    assert len(rec["status"]) == 26 and set(rec["status"]) == {"error"}
    errors = list(res.errors["error"])
    assert len(errors) == 26
    files = sorted(str(p) for p in demo.glob("*/*.csv"))
    for f in files:
        assert sum(f in e for e in errors) == 1, (f, errors)
    assert all("above the limit" in e for e in errors), errors


def test_only_the_recordings_over_the_limit_fail(demo, tmp_path):
    # Two subjects: a demo subject as written (3501 rows a leg) and one cut to 1500 rows a leg;
    # with max_samples=2000 only the first one's legs are error rows.
    long_dir, short_dir = tmp_path / "LONG", tmp_path / "SHORT"
    long_dir.mkdir()
    short_dir.mkdir()
    for side in ("left.csv", "right.csv"):
        lines = (demo / "H01" / side).read_text().splitlines(keepends=True)
        (long_dir / side).write_text("".join(lines))
        (short_dir / side).write_text("".join(lines[:1501]))
    res = ldh.analyze([long_dir, short_dir], n_jobs=1, as_frame=False, max_samples=2000)
    status = dict(zip(zip(res.recordings["subject_id"], res.recordings["side"]), res.recordings["status"]))
    assert status == {("LONG", "left"): "error", ("LONG", "right"): "error",
                      ("SHORT", "left"): "ok", ("SHORT", "right"): "ok"}, status
    errors = sorted(res.errors["error"])
    assert len(errors) == 2
    for side, e in zip(("left.csv", "right.csv"), errors):
        assert str(long_dir / side) in e and "3501 data rows" in e and "limit of 2000" in e, e


@pytest.mark.parametrize(
    "kwargs",
    [
        {"max_samples": 0},
        {"max_samples": -1},
        {"max_samples": True},
        {"max_samples": 1.5},
        {"max_samples": 2**64},
        {"max_file_size_mb": 0},
        {"max_file_size_mb": -3.0},
        {"max_file_size_mb": math.nan},
        {"max_file_size_mb": math.inf},
    ],
    ids=str,
)
def test_bad_limits_raise_a_parameter_error(demo, kwargs):
    with pytest.raises(ldh.LdhParamError):
        ldh.read_recording(_first_recording(demo), **kwargs)
    with pytest.raises(ldh.LdhParamError):
        ldh.analyze([demo], n_jobs=1, **kwargs)


def test_numpy_integers_are_accepted(demo):
    path = _first_recording(demo)
    rec, _ = ldh.read_recording(path, max_samples=np.int64(_rows(path)), max_file_size_mb=np.float32(1.0))
    assert len(rec["acc_x_g"]) == _rows(path)
