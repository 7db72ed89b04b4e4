"""The Dask recipe of docs/free-living.md ("Beyond one machine"): one task per person-week
gives the same tables as running ldh.monitor person by person. Skipped without dask or
without ldh.monitor (issue 52)."""

import shutil
import subprocess

import pytest

dask = pytest.importorskip("dask")
pd = pytest.importorskip("pandas")
ldh = pytest.importorskip("ldh")

if not hasattr(ldh, "monitor"):
    pytest.skip("ldh.monitor is not in this build", allow_module_level=True)


def _simulate(tmp_path):
    exe = shutil.which("ldh")
    if exe is None:
        pytest.skip("the ldh command is needed to simulate free-living days")
    out = tmp_path / "fl"
    subprocess.run(
        [exe, "simulate", "--free-living", "--hours", "1", "--healthy", "2",
         "--seed", "5", "--rate-hz", "50", "-o", str(out)],
        check=True,
    )
    return out, pd.read_csv(out / "manifest.csv")


def test_dask_person_weeks_equal_the_serial_run(tmp_path):
    out, manifest = _simulate(tmp_path)

    def one(row):
        res = ldh.monitor(str(out / row.left), str(out / row.right))
        return res.bouts.assign(subject_id=row.subject_id)

    serial = pd.concat([one(r) for r in manifest.itertuples()], ignore_index=True)
    tasks = [dask.delayed(one)(r) for r in manifest.itertuples()]
    parts = dask.compute(*tasks, scheduler="threads", num_workers=2)
    parallel = pd.concat(parts, ignore_index=True)
    pd.testing.assert_frame_equal(serial, parallel)
