"""Agreement of an ``ldh analyze`` run with a laboratory's reference system (``ldh agree``), and
the test–retest reliability of repeated trials (``ldh stats --reliability``)."""
from __future__ import annotations

import os
from typing import Any, Dict, Optional, Sequence, Union

from . import _ldh
from ._result import _table, have_pandas
from ._util import PathLike


def agree(
    results_dir: PathLike,
    reference: Union[PathLike, Sequence[PathLike]],
    tolerance_s: float = 0.2,
    offset_s: Optional[Union[float, str]] = None,
    write_params: Optional[PathLike] = None,
    reference_system: Optional[str] = None,
) -> Dict[str, Any]:
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

    Returns
    -------
    dict
        ``offsets``, ``events`` (per event kind and side: rates and timing errors, s),
        ``unmatched_events``, ``parameters`` (per parameter and level: ``agreement`` with bias,
        limits, ICCs…, or ``not_computed``; ``pairs``), and ``table``: the rows of
        ``agreement.csv`` (``pandas.DataFrame(result["table"])``).

    Raises
    ------
    LdhDataError
        A bad reference file (the message names file, line and column), an ambiguous clock
        offset, or a results folder that is not a finished ``ldh analyze`` run.
    LdhParamError
        A bad ``tolerance_s`` or ``offset_s``.
    LdhFileNotFoundError
        A missing file.
    """
    refs = [reference] if isinstance(reference, (str, os.PathLike)) else list(reference)
    return _ldh.agree(
        os.fspath(results_dir),
        [os.fspath(r) for r in refs],
        tolerance_s=float(tolerance_s),
        offset_s=offset_s,
        write_params=None if write_params is None else os.fspath(write_params),
        reference_system=reference_system,
    )


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
