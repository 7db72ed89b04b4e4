"""Every fenced ```python block of README.md runs verbatim (issue 18 item 4), each as its own
script in a fresh folder, as a new user would paste it. The Dask recipe starts a LocalCluster
with 2 workers; its recordings table must equal `ldh analyze` on the same manifest (checked in
the block against ldh.analyze, and here against the CLI's recordings.csv when a binary is
built). The third block is the lab workflow's Python half: it runs in the folder its shell
half (the ```sh block starting `ldh simulate -o lab`) made, with the built binary."""
import importlib.util
import os
import pathlib
import re
import subprocess
import sys

import pytest

import ldh

ROOT = pathlib.Path(__file__).resolve().parents[3]
BLOCKS = re.findall(r"^```python\n(.*?)^```", (ROOT / "README.md").read_text(encoding="utf-8"), re.S | re.M)


README = (ROOT / "README.md").read_text(encoding="utf-8")
# The lab workflow (issue 38): the shell block that starts with the simulated lab.
WORKFLOW_SH = re.findall(r"^```sh\n(ldh simulate -o lab .*?)^```", README, re.S | re.M)


def test_the_readme_has_the_python_the_dask_and_the_workflow_blocks():
    assert len(BLOCKS) == 3 and "LocalCluster(n_workers=2" in BLOCKS[1]
    assert 'if __name__ == "__main__":' in BLOCKS[1]
    assert "ldh.reliability" in BLOCKS[2] and len(WORKFLOW_SH) == 1
    # The whole workflow in at most 10 lines of shell and 10 of Python (issue 38).
    assert len(WORKFLOW_SH[0].strip().splitlines()) <= 10
    assert len(BLOCKS[2].strip().splitlines()) <= 10


def _run(block, cwd):
    script = cwd / "readme_block.py"
    script.write_text(block, encoding="utf-8")
    p = subprocess.run([sys.executable, str(script)], cwd=cwd, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}"
    return p.stdout


def test_python_block_runs_as_printed(tmp_path):
    pytest.importorskip("pandas")
    out = _run(BLOCKS[0], tmp_path)
    assert "<ldh.Result: 26 recordings (0 failed)" in out


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


def test_dask_block_runs_as_printed_and_equals_ldh_analyze(tmp_path):
    for mod in ("pandas", "dask.distributed"):
        if importlib.util.find_spec(mod.split(".")[0]) is None:
            pytest.skip(f"{mod} not installed")
    pytest.importorskip("dask.distributed")
    import pandas as pd

    _run(BLOCKS[1], tmp_path)
    dask = pd.read_csv(tmp_path / "recordings-dask.csv", keep_default_na=False, na_values=[""])
    assert len(dask) == 26 and set(dask.group) == {"healthy", "ldh"}
    cli = _cli()
    if cli is None:
        print("skipped CLI comparison: no ldh binary built")
        return
    out = tmp_path / "cli-out"
    subprocess.run([str(cli), "analyze", str(tmp_path / "ldh-demo" / "manifest.csv"), "-o", str(out)],
                   check=True, capture_output=True)
    ref = pd.read_csv(out / "recordings.csv", keep_default_na=False, na_values=[""])
    # Structured cells (warnings, withheld: lists and dicts in Python, one joined text cell in
    # the CSV) are compared by their number of entries; every other column by value.
    flat = [c for c in ref.columns if c not in ("warnings", "withheld")]
    pd.testing.assert_frame_equal(dask[flat], ref[flat], check_dtype=False, rtol=1e-12)
    whole = ldh.analyze(tmp_path / "ldh-demo" / "manifest.csv").recordings
    for col in ("warnings", "withheld"):
        ours = [len(v) for v in whole[col]]
        theirs = [0 if pd.isna(v) or v == "" else len(str(v).split(" | ")) for v in ref[col]]
        assert ours == theirs, col


def test_readme_blocks_pass_mypy_strict(tmp_path):
    """The README's code type-checks against the wheel's stubs (issue 39): `mypy --strict` on the
    first block; on the Dask recipe too, with `--allow-untyped-calls` because dask itself ships
    no type hints (pandas' come from pandas-stubs)."""
    api = pytest.importorskip("mypy.api")
    for i, (block, extra) in enumerate(zip(BLOCKS, ([], ["--allow-untyped-calls"], []))):
        script = tmp_path / f"readme_block_{i}.py"
        script.write_text(block, encoding="utf-8")
        out, err, status = api.run(["--strict", "--no-incremental", *extra, str(script)])
        assert status == 0, f"block {i}:\n{out}{err}"


def test_lab_workflow_runs_as_printed(tmp_path):
    """The README's lab workflow (issue 38): the shell block with the built `ldh` on PATH, then
    the Python block in the same folder; the agreement, calibration and reliability table exist
    and the calibrated run's report says so."""
    pytest.importorskip("pandas")
    cli = _cli()
    if cli is None:
        print("skipped the README lab workflow: no ldh binary built")
        return
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "ldh").symlink_to(cli)
    work = tmp_path / "work"
    work.mkdir()
    env = dict(os.environ, PATH=f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}")
    p = subprocess.run(["bash", "-e", "-c", WORKFLOW_SH[0]], cwd=work, env=env, capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}"
    assert "| HS | both |" in p.stdout and "| stride time (ST, s) | 10 × 3 |" in p.stdout, p.stdout
    assert "[events.calibration]" in (work / "calibration.toml").read_text()
    index = (work / "res2" / "reports" / "index.html").read_text(encoding="utf-8")
    assert "Gait events calibrated against force plates" in index
    out = _run(BLOCKS[2], work)
    assert "stride_time_s" in out and "mdc95" in out, out
