"""Agreement of an ``ldh analyze`` run with a laboratory's reference system (``ldh agree``), and
the test–retest reliability of repeated trials (``ldh stats --reliability``)."""
from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any, Dict, Iterator, Optional, Sequence, Union

import numpy as np

from . import _ldh
from ._result import _table, have_pandas
from ._util import PathLike, path_arg, path_list

#: The columns of an event row in seconds, and their names with the unit.
_EVENT_SECONDS = {"bias": "bias_s", "sd": "sd_s", "mae": "mae_s", "p95_abs": "p95_abs_s"}
#: Columns of agreement.csv that only event rows fill, and only parameter rows.
_EVENT_ONLY = ("n_ldh", "n_reference", "recall", "precision", "f1", "p95_abs")
_PARAMETER_ONLY = (
    "n_dropped", "bias_ci_low", "bias_ci_high", "loa_lower", "loa_lower_ci_low", "loa_lower_ci_high",
    "loa_upper", "loa_upper_ci_low", "loa_upper_ci_high", "proportional_bias_slope",
    "proportional_bias_pvalue", "relative_mae", "icc_2_1", "icc_2_1_ci_low", "icc_2_1_ci_high",
    "icc_3_1", "icc_3_1_ci_low", "icc_3_1_ci_high", "pearson_r", "note",
)


def _rows(cols: Dict[str, Any], keep: np.ndarray, drop: Sequence[str], rename: Dict[str, str]) -> Dict[str, Any]:
    """The rows ``keep`` of a table given as columns, without the columns ``drop`` and with
    the columns ``rename`` renamed, in the table's order."""
    out: Dict[str, Any] = {}
    for k, v in cols.items():
        if k in drop:
            continue
        a = v if isinstance(v, np.ndarray) else np.array(v, dtype=object)
        out[rename.get(k, k)] = a[keep]
    return out


class Agreement(Mapping):
    """What :func:`ldh.agree` returns: the tables of ``ldh agree`` and its whole report.

    Attributes
    ----------
    table : pandas.DataFrame or dict of numpy.ndarray
        ``agreement.csv``: its rows and its columns in the file's order, with its values and
        units (``bias``, ``sd``, ``mae``, the limits: seconds for event rows, the parameter's
        unit for parameter rows — the unit its name ends in, ``stride_time_s``).
    events : table
        The event rows (``level == "events"``) with the columns that concern events, the
        timing errors named with their unit: ``bias_s``, ``sd_s``, ``mae_s``, ``p95_abs_s``.
    parameters : table
        The parameter rows (``level`` ``stride`` or ``recording``) with the columns that
        concern parameters (``bias`` in the unit of the parameter named in ``quantity``).
    offsets : table
        The clock offset of each trial: ``subject_id``, ``trial_id``, ``offset_s``,
        ``source``.
    report : dict
        Everything ``agreement.json`` holds (pairs and unmatched events included) and
        ``table``, the rows of ``agreement.csv`` as dicts.

    ``result["events"]`` and the other keys of the dict that earlier versions returned
    (``report``'s keys) still work: an ``Agreement`` is a read-only mapping over ``report``.
    """

    def __init__(self, raw: Dict[str, Any], as_frame: Optional[bool] = None):
        cols = raw.pop("table_columns")
        self.report: Dict[str, Any] = raw
        self.as_frame = have_pandas() if as_frame is None else bool(as_frame)
        if self.as_frame and not have_pandas():
            raise ImportError("as_frame=True needs pandas (pip install pandas)")
        level = np.array(cols.get("level", []), dtype=object)
        ev = level == "events"
        self.table = _table(cols, self.as_frame)
        self.events = _table(_rows(cols, ev, _PARAMETER_ONLY, _EVENT_SECONDS), self.as_frame)
        self.parameters = _table(_rows(cols, ~ev, _EVENT_ONLY, {}), self.as_frame)
        offs = raw.get("offsets", [])
        keys = ("subject_id", "trial_id", "offset_s", "source")
        self.offsets = _table({k: [o.get(k) for o in offs] for k in keys}, self.as_frame)

    def __getitem__(self, key: str) -> Any:
        return self.report[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.report)

    def __len__(self) -> int:
        return len(self.report)

    def __repr__(self) -> str:
        n_ev = len(self.report.get("events", []))
        n_par = len(self.report.get("parameters", []))
        return f"<ldh.Agreement: {n_ev} event rows, {n_par} parameter rows>"


def agree(
    results_dir: PathLike,
    reference: Union[PathLike, Sequence[PathLike]],
    tolerance_s: float = 0.2,
    offset_s: Optional[Union[float, str]] = None,
    write_params: Optional[PathLike] = None,
    reference_system: Optional[str] = None,
    as_frame: Optional[bool] = None,
) -> Agreement:
    """Compare an ``ldh analyze`` output folder with reference files (docs/agreement.md).

    Parameters
    ----------
    results_dir : str or path-like
        The output folder of ``ldh analyze`` (recordings.json, strides.csv, events.csv).
    reference : str, path-like, or a list of them
        Reference CSV files: events (``subject_id[,trial_id],side,event,time_s``) and/or
        parameters (``subject_id[,trial_id],side`` and columns such as ``stride_time_s``;
        per stride with ``time_s`` or ``stride``, else per recording).
    tolerance_s : float, default 0.2
        Largest |ldh − reference| time of two matched events, in seconds.
    offset_s : float, "estimate" or None
        Clock offset ldh − reference (s) of the trials whose file gives no ``offset_s``;
        ``"estimate"`` estimates it per trial (refused when ambiguous); None: the clocks agree.
    write_params : str or path-like, optional
        Also write there the run's analysis parameters with its events calibrated to this
        reference (``ldh agree --write-params``; ``ldh.analyze(..., params=...)`` or
        ``ldh analyze --params`` use it). Needs at least 20 matched events of each kind.
    reference_system : str, optional
        What the reference system is ("force plates"), for the calibration's description.

    as_frame : bool, optional
        Tables as pandas DataFrames (default when pandas is importable) or, with ``False``, as
        dicts of numpy arrays.

    Returns
    -------
    Agreement
        ``.table`` (``agreement.csv``, its columns in the file's order), ``.events`` (timing
        errors in s: ``bias_s``, ``sd_s``, ``mae_s``, ``p95_abs_s``), ``.parameters`` (bias,
        limits, ICCs… in each parameter's unit), ``.offsets``, and ``.report``: the whole
        report as ``agreement.json`` holds it (``offsets``, ``events``,
        ``unmatched_events``, ``parameters`` with their ``pairs``, ``table``), which
        ``result[key]`` also reads, as on the dict earlier versions returned.

    Raises
    ------
    LdhDataError
        A bad reference file (the message names file, line and column), an ambiguous clock
        offset, or a results folder that is not a finished ``ldh analyze`` run.
    LdhParamError
        A bad ``tolerance_s`` or ``offset_s``.
    LdhFileNotFoundError
        A missing file.
    LdhTypeError
        ``results_dir`` or ``reference`` is not a path (also a ``TypeError``): ldh.agree reads
        an ``ldh analyze`` folder and reference files.
    """
    raw = _ldh.agree(
        path_arg(results_dir, "agree", "results_dir", "give the output folder of ldh.analyze or ldh analyze"),
        path_list(reference, "agree", "reference", "write the reference table to a CSV file first"),
        tolerance_s=float(tolerance_s),
        offset_s=offset_s,
        write_params=None if write_params is None else path_arg(write_params, "agree", "write_params"),
        reference_system=reference_system,
    )
    return Agreement(raw, as_frame)


def reliability(results: Any, confidence_level: float = 0.95) -> Any:
    """Test–retest reliability of every parameter from repeated trials (``ldh stats --reliability``).

    Per parameter: ICC(2,1) and ICC(3,1) with confidence intervals, the SD of all values, SEM,
    MDC95, the within-subject CV and the between- and within-subject variances, from each
    person's trials (manifest ``trial_id``) of their first visit; the value of a trial is the
    mean of both legs (docs/agreement.md, "Reliability table").

    Parameters
    ----------
    results : str, path-like, ldh.Result, pandas.DataFrame or dict of columns
        An ``ldh analyze`` output folder, the result of ``ldh.analyze``/``ldh.analyze_many``, or
        its ``recordings`` table.
    confidence_level : float, default 0.95
        Level of the ICCs' intervals.

    Returns
    -------
    pandas.DataFrame (dict of numpy arrays without pandas)
        One row per parameter, the columns of ``reliability.csv`` in order; a parameter that
        cannot be computed has its reason in ``withheld`` and NaN numbers.

    Raises
    ------
    LdhDataError
        No person has two or more trials, or a results folder that cannot be read.
    LdhParamError
        A bad ``confidence_level``.
    LdhFileNotFoundError
        A missing folder or file.
    """
    level = float(confidence_level)
    if isinstance(results, (str, os.PathLike)):
        cols = _ldh.reliability(os.fspath(results), None, confidence_level=level)
    else:
        rec = results.recordings if hasattr(results, "recordings") else results
        if hasattr(rec, "columns") and hasattr(rec, "to_dict"):  # a pandas DataFrame
            table = {str(k): rec[k].tolist() for k in rec.columns}
        else:
            table = {str(k): list(v) for k, v in dict(rec).items()}
        cols = _ldh.reliability(None, table, confidence_level=level)
    as_frame = have_pandas()
    out = _table(cols, as_frame)
    if as_frame:
        out = out.astype({"n_subjects": int, "k_trials": int})
    return out
