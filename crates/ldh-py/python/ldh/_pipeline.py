"""The analysis of paths (``analyze``, ``analyze_many``) and arrays (``analyze_pair``,
``analyze_recording``)."""
from __future__ import annotations

import warnings
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np

from . import _ldh
from ._errors import LdhParamError, LdhWarning
from ._result import Result
from ._util import ARRAYS_INSTEAD, PathLike, opt_float, params_dict, path_list, sample_limit, vec

_CHANNELS = ["acc_x_g", "acc_y_g", "acc_z_g", "gyro_x_dps", "gyro_y_dps", "gyro_z_dps"]


def _jobs(n_jobs: Optional[int]) -> int:
    """Rust threads: ``None`` or ``-1`` all cores (0 for the core), else a positive int."""
    if n_jobs is None or (not isinstance(n_jobs, bool) and isinstance(n_jobs, (int, np.integer)) and n_jobs == -1):
        return 0
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, (int, np.integer)) or n_jobs < 1:
        raise LdhParamError(f"n_jobs must be a positive int, -1 or None (all cores), got {n_jobs!r}")
    return int(n_jobs)


def _paths(inputs: Union[None, PathLike, Sequence[PathLike]], func: str = "analyze") -> list:
    if inputs is None:
        return []
    paths = path_list(inputs, func, "inputs", ARRAYS_INSTEAD)
    if not paths:
        # Only ``None`` means the embedded demo: an empty list is a mistake, not a request.
        raise LdhParamError("inputs is an empty list: give paths, or None for the embedded demo cohort")
    return paths


def _setting(setting: Optional[str]) -> Optional[str]:
    if setting is not None and not isinstance(setting, str):
        raise LdhParamError(f"setting must be 'overground', 'treadmill' or None, got {setting!r}")
    return setting


def _clocks(clocks: Optional[str]) -> Optional[str]:
    # Only the type here: the value is read by the core (the manifest's `clocks` column's rule).
    if clocks is not None and not isinstance(clocks, str):
        raise LdhParamError(f"clocks must be 'one', 'two' or None, got {clocks!r}")
    return clocks


def _subject_id(subject_id: Optional[str]) -> Optional[str]:
    if subject_id is not None and not isinstance(subject_id, str):
        raise LdhParamError(f"subject_id must be a str, got {subject_id!r}")
    return subject_id


def analyze(
    inputs: Union[None, PathLike, Sequence[PathLike]] = None,
    *,
    model: Optional[str] = None,
    detector: Optional[str] = None,
    format: Optional[str] = None,
    compute_sta: Optional[bool] = None,
    sensor_height_m: Optional[float] = None,
    n_jobs: Optional[int] = 1,
    params: Optional[Dict[str, Any]] = None,
    subject_id: Optional[str] = None,
    setting: Optional[str] = None,
    as_frame: Optional[bool] = None,
    max_file_size_mb: float = 256.0,
    max_samples: int = 2_500_000,
    left_sensor_height_m: Optional[float] = None,
    right_sensor_height_m: Optional[float] = None,
) -> Result:
    """Analyse recordings exactly as ``ldh analyze`` does.

    Parameters
    ----------
    inputs : path or sequence of paths, optional
        A manifest CSV, a cohort folder, a subject folder or a subject's two files; ``None``:
        the embedded demo cohort (an empty list raises :class:`LdhParamError`).
    model : {"fusion", "acc"}, optional
        Attitude model (default: from ``params``, else "fusion").
    detector : str, optional
        Event detector (``gyro-bracket`` — the default —, ``gyro-landmarks``,
        ``gyro-zero-crossing``, ``salarian``, ``pitch-peaks``).
    format : str, optional
        Sensor format name or TOML column map; default: detect.
    compute_sta : bool, optional
        Compute the Lyapunov stability STA (default True); with False its ``sta_status``
        reads "not computed: turned off for this run" (``--no-sta`` on the command line).
    sensor_height_m : float, optional
        Sensor height above the ankle when the manifest has none, in metres. Default: not
        given; 0.10 m is then assumed and each leg gets a ``sensor_height_unknown`` finding in
        ``.warnings``: a note when its median stride length moves by at most 15 % over
        0.05-0.35 m, else a warning, and its stride length, speed and their variability are
        withheld (docs/quality.md).
    left_sensor_height_m, right_sensor_height_m : float, optional
        One leg's sensor height, m, for subjects whose manifest gives none for that leg
        (``--left-sensor-height-m``, ``--right-sensor-height-m``): each leg's stride length
        uses its own sensor's height. A leg's own height wins over ``sensor_height_m``; the two
        may not differ (:class:`LdhParamError`), docs/input.md "Sensor height".
    n_jobs : int or None, default 1
        Rust threads for the subjects (the GIL is released); ``None`` or ``-1``: all cores.
        More than the machine's cores is lowered to the cores with an :class:`LdhWarning`
        (as ``ldh analyze -j``). Results are identical whatever the number.
    params : dict, optional
        Any analysis parameter, nested as in docs/parameters.md and with the Rust names and
        defaults, e.g. ``{"attitude": {"smoother": False}, "preprocess": {"cutoff_hz": 8.0}}``;
        unknown names are refused. ``model``, ``detector``, ``sensor_height_m`` and
        ``compute_sta`` are applied on top.
    subject_id : str, optional
        Subject id of two files given directly (``ldh analyze --subject``; default: the common
        stem of their names, or the folder of ``left.csv``/``right.csv``). Refused with a
        manifest or a folder, which name their own subjects.
    setting : {"overground", "treadmill"}, optional
        Setting of every subject whose manifest row does not say (``--setting``); on a
        treadmill no stride is flagged as a turn (docs/input.md "Setting").
    as_frame : bool, optional
        Tables as pandas DataFrames (default when pandas is importable) or, with ``False``, as
        dicts of numpy arrays.
    max_file_size_mb : float, default 256.0
        Largest recording file read, in MB (``--max-file-size-mb``); see
        :func:`read_recording`.
    max_samples : int, default 2500000
        Most data rows per recording (``--max-samples``); see :func:`read_recording`. A
        recording over either limit is that leg's error row naming the file and the limit
        (``.errors``), as every recording that cannot be read; the others are analysed.

    Returns
    -------
    Result
        ``.strides``, ``.recordings``, ``.events`` (DataFrames), ``.warnings``, ``.errors``,
        ``.timings``; see :class:`ldh.Result` and docs/python.md. A recording that failed has
        ``status == "error"`` and its ``error`` (and a row in ``.errors``); the others are
        analysed (``"ok"``, or ``"no_valid_strides"`` when no stride passed the checks and
        every parameter is withheld). Problems that did not stop a recording are in ``.warnings``.

    Raises
    ------
    LdhFileNotFoundError
        An input path does not exist (also a ``FileNotFoundError``), before any work.
    LdhParamError
        An invalid option (also a ``ValueError``).
    LdhDataError
        A manifest that cannot be used, e.g. one with a header and no subject row ("the manifest
        has no subjects"; also a ``ValueError``), before any work.
    LdhTypeError
        ``inputs`` is not a path or a list of paths (also a ``TypeError``): a DataFrame or an
        array is analysed with :func:`analyze_pair` or :func:`analyze_recording`.
    """
    raw = _ldh.analyze(
        _paths(inputs), model, detector, format, compute_sta, opt_float(sensor_height_m),
        _jobs(n_jobs), params_dict(params), _subject_id(subject_id), _setting(setting),
        float(max_file_size_mb), sample_limit(max_samples),
        opt_float(left_sensor_height_m), opt_float(right_sensor_height_m),
    )
    if raw.get("jobs_warning"):
        warnings.warn(raw["jobs_warning"], LdhWarning, stacklevel=_caller_level())
    return Result(raw, as_frame)


def _caller_level() -> int:
    """The ``stacklevel`` that points a warning at the user's call of ``analyze`` or
    ``analyze_many`` (not at this module)."""
    import sys

    level, frame = 2, sys._getframe(2)
    while frame is not None and frame.f_globals.get("__name__") == __name__:
        level, frame = level + 1, frame.f_back
    return level


def analyze_many(paths: Sequence[PathLike], n_jobs: Optional[int] = None, **kwargs: Any) -> Result:
    """Analyse many inputs (manifests, cohort or subject folders, pairs of files) in parallel
    on Rust threads; the same as :func:`analyze` with ``n_jobs`` defaulting to all cores
    (every keyword of :func:`analyze` is accepted, ``max_file_size_mb`` and ``max_samples``
    included).

    ``paths`` must name at least one input (``analyze()`` without inputs is the demo); an
    empty list raises :class:`LdhParamError` (a ``ValueError``). The
    function is pure (files in, tables out) and keeps no state, so it runs unchanged in Dask or
    Ray workers: ``client.map(lambda d: ldh.analyze(d, n_jobs=1), subject_dirs)``.
    """
    paths = path_list(paths, "analyze_many", "paths", ARRAYS_INSTEAD)
    if not paths:
        raise LdhParamError("analyze_many needs at least one input path (ldh.analyze() without inputs analyses the demo)")
    return analyze(paths, n_jobs=n_jobs, **kwargs)


def _rate(rec: Dict[str, Any], fs_hz: Optional[float], name: str) -> float:
    if fs_hz is not None:
        return float(fs_hz)
    if rec.get("fs_hz") is None:
        raise LdhParamError(f"fs_hz is needed: {name} does not carry 'fs_hz'")
    return float(rec["fs_hz"])


def analyze_pair(
    left: Dict[str, Any],
    right: Dict[str, Any],
    fs_hz: Optional[float] = None,
    *,
    subject_id: str = "subject",
    model: Optional[str] = None,
    detector: Optional[str] = None,
    sensor_height_m: Optional[float] = None,
    compute_sta: Optional[bool] = None,
    params: Optional[Dict[str, Any]] = None,
    setting: Optional[str] = None,
    as_frame: Optional[bool] = None,
    left_sensor_height_m: Optional[float] = None,
    right_sensor_height_m: Optional[float] = None,
    clocks: Optional[str] = None,
) -> Result:
    """Analyse one subject's two recordings given as arrays, with step time and step frequency
    from both legs — the same tables as :func:`analyze`.

    Parameters
    ----------
    left, right : dict
        Channels ``acc_x_g`` … ``gyro_z_dps`` (array_like, g and deg/s), e.g. the first value
        returned by :func:`read_recording`, and ``fs_hz``.
    fs_hz : float, optional
        Sampling rate of both, when the dicts do not carry ``fs_hz`` (it then overrides
        theirs). Each leg is analysed at its own rate, as ``ldh analyze`` does with two files:
        rates that differ by more than 0.5 % give a warning, not an error.
    subject_id : str, default "subject"
        The subject's id in the tables.
    sensor_height_m : float, optional
        Sensor height above the ankle, m; not given: 0.10 m assumed and checked, as in
        :func:`analyze` (``sensor_height_unknown`` in ``.warnings``).
    setting : {"overground", "treadmill"}, optional
        Where the walk happened (default: not said, analysed as overground); on a treadmill
        no stride is flagged as a turn.
    left_sensor_height_m, right_sensor_height_m : float, optional
        One leg's sensor height, m (each wins over ``sensor_height_m`` for its leg; the two may
        not differ), as in :func:`analyze`.
    clocks : {"one", "two"}, optional
        Whether the two arrays share one clock: ``"one"`` when one device recorded both legs
        (e.g. both shanks read from one HuGaDB file) or the two sensors were synchronised;
        ``"two"`` for two separately recorded sensors. Default (None): ``"two"``, as for two
        files given to :func:`analyze` — arrays carry nothing that shows one clock, and two
        clocks only withhold a step-time asymmetry the legs' own swing times do not back
        (``two_clocks`` in ``.warnings``: step time, its asymmetry, step frequency and double
        support not measured), where one clock taken on trust would report a clock offset as
        the walker's asymmetry. The manifest's ``clocks`` column; anything else raises
        ``ldh.LdhParamError`` naming the value.

    Returns
    -------
    Result
        As :func:`analyze`.
    """
    for name, rec in (("left", left), ("right", right)):
        missing = [c for c in _CHANNELS if c not in rec]
        if missing:
            raise LdhParamError(f"{name} lacks the channels {missing}")
    lv = [vec(left[c], f"left[{c}]") for c in _CHANNELS]
    rv = [vec(right[c], f"right[{c}]") for c in _CHANNELS]
    raw = _ldh.analyze_pair(
        lv, rv, _rate(left, fs_hz, "left"), _rate(right, fs_hz, "right"), _subject_id(subject_id),
        model, detector, opt_float(sensor_height_m), compute_sta, params_dict(params),
        _setting(setting), opt_float(left_sensor_height_m), opt_float(right_sensor_height_m),
        _clocks(clocks),
    )
    return Result(raw, as_frame)


def analyze_recording(
    acc_g: Sequence[Any],
    gyro_dps: Sequence[Any],
    fs_hz: float,
    *,
    side: str = "left",
    model: Optional[str] = None,
    detector: Optional[str] = None,
    sensor_height_m: Optional[float] = None,
    compute_sta: Optional[bool] = None,
    params: Optional[Dict[str, Any]] = None,
    setting: Optional[str] = None,
) -> Dict[str, Any]:
    """Run the per-recording pipeline on arrays: preprocessing, alignment, attitude, events,
    strides and the per-side parameters (without the other leg: no step time).

    Parameters
    ----------
    acc_g, gyro_dps : sequence of three array_like
        Acceleration in g and angular velocity in deg/s, sensor axes x, y, z.
    fs_hz : float
        Sampling rate in Hz.
    side : {"left", "right"}
        The leg.
    model : {"fusion", "acc"}
        Attitude model.
    detector : str
        Event detector. With the default ``gyro-bracket`` a leg analysed alone places
        every toe off at the same fraction of its bracket (0.389): the step that moves
        the stiffer leg's toe offs later needs the other leg, so :func:`analyze_pair` or
        :func:`analyze` may give this leg's stance slightly differently.
    sensor_height_m : float
        Sensor height above the ankle, m; when not given, 0.10 m is assumed and checked
        (``sensor_height_unknown`` in ``warnings``, as for :func:`analyze`).
    compute_sta : bool
        Compute the Lyapunov stability STA; with False its status reads "not computed:
        turned off for this run".
    setting : {"overground", "treadmill"}, optional
        Where the walk happened; on a treadmill no stride is flagged as a turn.

    Returns
    -------
    dict
        ``alignment`` (dict), ``events`` (``hs_s``, ``to_s``, ``midswing_s`` arrays),
        ``strides`` (columns), ``parameters`` (dict), ``attitude`` (``pitch_deg``,
        ``roll_deg``, ``yaw_deg`` arrays), ``outliers_replaced``, ``warnings`` (list of str:
        problems that did not stop the analysis, e.g. an upside-down mounting or too few
        valid strides).
    """
    acc = [vec(c, f"acc_g[{i}]") for i, c in enumerate(acc_g)]
    gyro = [vec(c, f"gyro_dps[{i}]") for i, c in enumerate(gyro_dps)]
    if len(acc) != 3 or len(gyro) != 3:
        raise LdhParamError("acc_g and gyro_dps must each hold three channels (x, y, z)")
    return _ldh.analyze_recording(
        acc, gyro, float(fs_hz), side, model, detector, opt_float(sensor_height_m), compute_sta,
        params_dict(params), _setting(setting),
    )
