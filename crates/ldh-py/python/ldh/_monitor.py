"""Walking in daily life (``ldh.monitor``): days of two shank recordings streamed by the Rust
core (GIL released), the tables as pandas DataFrames (dicts of lists without pandas)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Union

from . import _ldh
from ._pipeline import _jobs, _subject_id
from ._result import have_pandas
from ._util import PathLike, params_dict, path_list

# Text columns; every other column is numeric (an empty cell is NaN: a value withheld, with its
# reason in the row's ``withheld`` cell).
_TEXT = {
    "subject_id", "visit", "legs", "kind", "withheld", "errors", "date", "state", "valid",
    "from_visit", "to_visit", "measure", "unit", "beyond_noise",
}
# Yes/no columns: "true"/"false"; ``beyond_noise`` may be empty (not judged): None.
_BOOL = {"valid", "beyond_noise"}


def _frame(columns: List[str], rows: List[List[str]]) -> Any:
    cols: Dict[str, list] = {c: [r[i] for r in rows] for i, c in enumerate(columns)}
    for c, v in cols.items():
        if c in _BOOL:
            cols[c] = [None if x == "" else x == "true" for x in v]
        elif c not in _TEXT:
            cols[c] = [float(x) if x != "" else float("nan") for x in v]
    if have_pandas():
        import pandas as pd

        return pd.DataFrame(cols, columns=columns)
    return cols


@dataclass
class MonitorResult:
    """The result of :func:`monitor`.

    Attributes
    ----------
    bouts, days, summary, periods : pandas.DataFrame
        ``bouts.csv`` (one row per walking bout), ``days.csv`` (per day), ``summary.csv`` (per
        person and monitoring period) and ``periods.csv`` (wear and rest periods), as
        ``ldh monitor`` writes them (docs/free-living.md).
    changes : pandas.DataFrame
        ``changes.csv``: per person, later period and daily measure, the change from the first
        period judged against the day-to-day noise (``beyond_noise`` True/False, or None with
        the reason in ``withheld``); no rows when no person has two periods.
    notes, errors : list of list of str
        Per person and period: what the reader and the pairing found; errors that lost a leg.
    """

    bouts: Any
    days: Any
    summary: Any
    periods: Any
    changes: Any = None
    notes: List[List[str]] = field(default_factory=list)
    errors: List[List[str]] = field(default_factory=list)


def monitor(
    inputs: Union[PathLike, Sequence[PathLike]],
    *,
    subject_id: Optional[str] = None,
    params: Optional[Dict[str, Any]] = None,
    n_jobs: Optional[int] = 1,
) -> MonitorResult:
    """Free-living monitoring of one or more people, as ``ldh monitor INPUT... -o DIR``.

    Parameters
    ----------
    inputs : path or list of paths
        Two recordings (left, then right), a subject folder, or a manifest with one row per
        person and monitoring period (``visit``); ldh's CSV, streamed.
    subject_id : str, optional
        The id of two files given directly.
    params : dict, optional
        ``MonitorParams`` fields (docs/free-living.md); unknown names raise LdhParamError.
    n_jobs : int, optional
        Worker threads (``-1`` or ``None``: all cores).

    Raises
    ------
    LdhParamError, LdhFileNotFoundError, LdhDataError
        Bad parameters, missing inputs. A person whose files cannot be read is a summary row
        with its error (``errors``), never an exception for the others.
    """
    paths = path_list(inputs, "monitor", "inputs")
    if not paths:
        from ._errors import LdhParamError

        raise LdhParamError("inputs is an empty list: give two recordings, a folder or a manifest")
    out = _ldh.monitor(paths, _subject_id(subject_id), params_dict(params), _jobs(n_jobs))
    return MonitorResult(
        bouts=_frame(*out["bouts"]),
        days=_frame(*out["days"]),
        summary=_frame(*out["summary"]),
        periods=_frame(*out["periods"]),
        changes=_frame(*out["changes"]),
        notes=out["notes"],
        errors=out["errors"],
    )
