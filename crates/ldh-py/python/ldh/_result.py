"""The result of an analysis: the three tables as pandas DataFrames (or dicts of numpy arrays
without pandas), the warnings and the errors as tables, and the timings."""
from __future__ import annotations

from typing import Any, Dict, Iterator, Optional

import numpy as np

TABLES = ("strides", "recordings", "events")


def have_pandas() -> bool:
    try:
        import pandas  # noqa: F401
    except ImportError:
        return False
    return True


def _objects(v: Any) -> np.ndarray:
    """A 1-D object array (elements may themselves be lists or dicts)."""
    out = np.empty(len(v), dtype=object)
    for i, x in enumerate(v):
        out[i] = x
    return out


def _as_arrays(cols: Dict[str, Any]) -> Dict[str, np.ndarray]:
    """Columns from the core (numpy arrays, or lists for text and structured cells) as numpy
    arrays (object arrays for those, ``None`` where a value is missing)."""
    return {k: v if isinstance(v, np.ndarray) else _objects(v) for k, v in cols.items()}


def _table(cols: Dict[str, Any], as_frame: bool) -> Any:
    if as_frame:
        import pandas as pd

        return pd.DataFrame({k: (v if isinstance(v, np.ndarray) else list(v)) for k, v in cols.items()})
    return _as_arrays(cols)


WARNING_COLUMNS = ("subject_id", "side", "code", "severity", "message", "affects")


def _warning_rows(recordings: Dict[str, Any]) -> Dict[str, list]:
    """One row per structured warning of a recording (docs/quality.md: ``code``, ``severity``
    note/warning/fault, ``message``, ``affects``: the columns it concerns). The recordings
    table keeps each recording's list in its ``warnings`` cell; this is the only place they are
    unfolded."""
    out: Dict[str, list] = {k: [] for k in WARNING_COLUMNS}
    for s, side, ws in zip(recordings.get("subject_id", []), recordings.get("side", []), recordings.get("warnings", [])):
        for w in ws or []:
            if isinstance(w, str):  # a free-text warning
                w = {"code": "", "severity": "warning", "message": w, "affects": []}
            out["subject_id"].append(s)
            out["side"].append(side)
            for k in WARNING_COLUMNS[2:]:
                out[k].append(w.get(k))
    return out


def _error_rows(recordings: Dict[str, Any]) -> Dict[str, list]:
    """One row per recording that failed, with its error."""
    out: Dict[str, list] = {"subject_id": [], "side": [], "error": []}
    for s, side, status, err in zip(recordings.get("subject_id", []), recordings.get("side", []), recordings.get("status", []), recordings.get("error", [])):
        if status == "error":
            out["subject_id"].append(s)
            out["side"].append(side)
            out["error"].append(err)
    return out


class Result:
    """What :func:`ldh.analyze` returns.

    Attributes
    ----------
    strides, recordings, events : pandas.DataFrame or dict of numpy.ndarray
        The tables ``ldh analyze`` writes (``strides.csv``, ``recordings.csv``,
        ``events.csv``), one row per stride / recording (leg) / gait event. DataFrames when
        pandas is importable (or ``as_frame=True``); otherwise dicts of columns: float64 arrays
        with NaN for missing values, bool arrays, object arrays for text.
    warnings : table
        One row per structured warning of a recording that was analysed: ``subject_id``,
        ``side``, ``code``, ``severity`` (``note``, ``warning``, ``fault``), ``message``,
        ``affects`` (the parameters it concerns; docs/quality.md). The recordings table keeps
        each recording's list in its ``warnings`` cell and the withheld parameters (column ->
        reason; the value is NaN) in its ``withheld`` cell.
    errors : table
        One row per recording that failed: ``subject_id``, ``side``, ``error`` (a file that
        cannot be read, too few strides...); the other recordings are analysed.
    timings : dict
        ``total_s`` (wall-clock seconds of the analysis), ``subjects``, ``recordings`` and the
        wall time of each stage summed over the recordings (and threads), as
        ``ldh analyze --timings`` prints it: ``read_s``, ``preprocess_s``, ``align_s``,
        ``attitude_s``, ``events_s``, ``strides_s``, ``sta_s``, ``write_s`` (building the
        tables). :meth:`timings_table` gives them one row per stage.

    ``result["strides"]`` is ``result.strides``, and ``keys()``, ``items()`` and iteration
    work as on the dict of tables that earlier versions returned.
    """

    def __init__(self, raw: Dict[str, Any], as_frame: Optional[bool] = None):
        self._raw = {k: raw[k] for k in TABLES}
        self.as_frame = have_pandas() if as_frame is None else bool(as_frame)
        if self.as_frame and not have_pandas():
            raise ImportError("as_frame=True needs pandas (pip install pandas)")
        self.strides = _table(raw["strides"], self.as_frame)
        self.recordings = _table(raw["recordings"], self.as_frame)
        self.events = _table(raw["events"], self.as_frame)
        self.warnings = _table(_warning_rows(raw["recordings"]), self.as_frame)
        self.errors = _table(_error_rows(raw["recordings"]), self.as_frame)
        self.timings: Dict[str, Any] = dict(raw.get("timings", {}))

    def timings_table(self) -> Any:
        """The stage timings one row per stage (``stage``, ``seconds``), in pipeline order: a
        DataFrame when ``as_frame``, else a dict of arrays."""
        stages = [k[: -len("_s")] for k in self.timings if k.endswith("_s") and k != "total_s"]
        cols = {"stage": stages, "seconds": np.array([float(self.timings[s + "_s"]) for s in stages])}
        return _table(cols, self.as_frame)

    def to_pandas(self) -> Dict[str, Any]:
        """The tables as pandas DataFrames: ``{"strides", "recordings", "events", "warnings",
        "errors"}`` (needs pandas)."""
        import pandas  # noqa: F401  (a clear ImportError when missing)

        out = {k: _table(self._raw[k], True) for k in TABLES}
        out["warnings"] = _table(_warning_rows(self._raw["recordings"]), True)
        out["errors"] = _table(_error_rows(self._raw["recordings"]), True)
        return out

    def to_dict(self) -> Dict[str, Dict[str, np.ndarray]]:
        """The three tables as dicts of numpy arrays, whatever ``as_frame`` is."""
        return {k: _as_arrays(self._raw[k]) for k in TABLES}

    def __getitem__(self, key: str) -> Any:
        if key not in TABLES:
            raise KeyError(f"{key!r}: a Result has the tables {TABLES}")
        return getattr(self, key)

    def keys(self):
        return TABLES

    def items(self):
        return [(k, getattr(self, k)) for k in TABLES]

    def __iter__(self) -> Iterator[str]:
        return iter(TABLES)

    def __len__(self) -> int:
        return len(TABLES)

    def __repr__(self) -> str:
        n = {k: len(next(iter(self._raw[k].values()), [])) for k in TABLES}
        return (f"<ldh.Result: {n['recordings']} recordings ({len(_error_rows(self._raw['recordings'])['error'])} failed), "
                f"{n['strides']} strides, {n['events']} events>")
