"""ldh: gait assessment for lumbar disc herniation from two shank-worn IMUs.

All computation happens in the Rust core (``ldh._ldh``) with the GIL released; this package
converts inputs to float64 numpy arrays and documents the API.
"""
from __future__ import annotations

import json
import os
import warnings
from typing import Any, Dict, List, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _ldh
from ._errors import (
    LdhDataError,
    LdhError,
    LdhFileNotFoundError,
    LdhOSError,
    LdhParamError,
    LdhWarning,
)

__version__ = _ldh.__version__
__all__ = [
    "LdhError",
    "LdhDataError",
    "LdhParamError",
    "LdhFileNotFoundError",
    "LdhOSError",
    "LdhWarning",
    "read_recording",
    "butter_filtfilt",
    "preprocess",
    "write_demo",
    "simulate_cohort",
    "analyze",
    "analyze_many",
    "analyze_recording",
    "analyze_pair",
    "lyap_r",
    "lyap_e",
    "shapiro",
    "mannwhitneyu",
    "ttest_ind",
    "ttest_rel",
    "wilcoxon",
    "f_oneway",
    "kruskal",
    "pearsonr",
    "holm",
    "TestResult",
    "cross_validate",
    "train",
    "predict",
]

PathLike = Union[str, "os.PathLike[str]"]


def _vec(x: Any, name: str) -> np.ndarray:
    a = np.ascontiguousarray(x, dtype=np.float64)
    if a.ndim != 1:
        raise LdhParamError(f"{name} must be one-dimensional, got shape {a.shape}")
    return a


def read_recording(
    path: PathLike,
    format: Optional[str] = None,
    *,
    max_gap_s: float = 0.2,
    gap_policy: str = "split",
    min_duration_s: float = 4.0,
    check_units: bool = True,
) -> Tuple[Dict[str, Any], Dict[str, Any]]:
    """Read one sensor CSV export.

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    format : str, optional
        A built-in format name (``ldh``, ``xsens-mtmanager``, ``shimmer-consensys``,
        ``raw-counts``) or a path to a TOML column map. Default: detect a built-in format.
    max_gap_s : float, default 0.2
        Longest gap in the timestamps bridged by interpolation, in seconds.
    gap_policy : {"split", "reject"}, default "split"
        What to do with longer gaps: keep the longest segment, or raise.
    min_duration_s : float, default 4.0
        Shortest usable recording, in seconds.
    check_units : bool, default True
        Refuse data whose magnitudes contradict the declared units.

    Returns
    -------
    recording : dict
        ``fs_hz``, ``t0_s``, ``time_s`` and the channels ``acc_x_g`` ... ``gyro_z_dps`` as
        float64 arrays, plus the boolean ``saturated`` mask.
    report : dict
        What the reader detected and assumed (format, delimiter, rate, gaps, clipping, notes),
        and ``warnings``: problems that did not stop it (data dropped at a gap, a constant or
        frozen channel, too much timestamp jitter). Each warning is also issued as an
        :class:`LdhWarning`.

    Raises
    ------
    LdhFileNotFoundError
        The file does not exist (also a ``FileNotFoundError``).
    LdhDataError
        The file is not a usable recording (also a ``ValueError``); the message names the
        file, line and column.
    """
    rec, report = _ldh.read_recording(
        os.fspath(path), format, max_gap_s, gap_policy, min_duration_s, check_units
    )
    report = json.loads(report)
    for w in report.get("warnings", []):
        warnings.warn(f"{report['file']}: {w}", LdhWarning, stacklevel=2)
    return rec, report


def butter_filtfilt(x: Any, cutoff_hz: float, fs_hz: float, order: int = 4) -> np.ndarray:
    """Zero-phase Butterworth low-pass, equal to ``scipy.signal.sosfiltfilt(butter(order,
    cutoff_hz, output="sos", fs=fs_hz), x)`` to 1e-9 relative.

    Parameters
    ----------
    x : array_like
        One-dimensional signal (converted to float64).
    cutoff_hz : float
        Cut-off frequency in Hz, below ``fs_hz / 2``.
    fs_hz : float
        Sampling rate in Hz.
    order : int, default 4
        Even filter order, 2-10.

    Returns
    -------
    numpy.ndarray
        The filtered signal.
    """
    return _ldh.butter_filtfilt(_vec(x, "x"), float(cutoff_hz), float(fs_hz), int(order))


def preprocess(
    acc_g: Sequence[Any],
    gyro_dps: Sequence[Any],
    fs_hz: float,
    *,
    cutoff_hz: float = 10.0,
    filter_order: int = 4,
    outlier_sd: float = 3.0,
    replace_outliers: bool = True,
    outlier_channels: str = "acc",
) -> Dict[str, Any]:
    """Preprocess one sensor (paper section 3.1): magnitude, 3-SD outlier replacement,
    zero-phase Butterworth low-pass on all six channels.

    Parameters
    ----------
    acc_g : sequence of three array_like
        Acceleration x, y, z in g.
    gyro_dps : sequence of three array_like
        Angular velocity x, y, z in deg/s.
    fs_hz : float
        Sampling rate in Hz.
    cutoff_hz : float, default 10.0
        Low-pass cut-off in Hz.
    filter_order : int, default 4
        Butterworth order.
    outlier_sd : float, default 3.0
        Outlier threshold in standard deviations of the acceleration magnitude.
    replace_outliers : bool, default True
        Replace outliers by linear interpolation before filtering.
    outlier_channels : {"acc", "all"}, default "acc"
        Replace acceleration-magnitude outliers on the acceleration channels only, or on all
        six channels (the paper read literally; see docs/pipeline.md).

    Returns
    -------
    dict
        Filtered channels ``acc_x_g`` ... ``gyro_z_dps``, ``acc_norm_g``, the indices in
        ``replaced`` and ``fs_hz``.
    """
    if len(acc_g) != 3 or len(gyro_dps) != 3:
        raise LdhParamError("acc_g and gyro_dps must each hold three channels (x, y, z)")
    acc = [_vec(c, f"acc_g[{i}]") for i, c in enumerate(acc_g)]
    gyro = [_vec(c, f"gyro_dps[{i}]") for i, c in enumerate(gyro_dps)]
    return _ldh.preprocess(
        acc, gyro, float(fs_hz), float(cutoff_hz), int(filter_order), float(outlier_sd),
        bool(replace_outliers), outlier_channels,
    )


def write_demo(out: PathLike) -> int:
    """Write the embedded demo cohort (2 healthy, 2 LDH subjects) to ``out``; returns the
    number of files written."""
    return _ldh.write_demo(os.fspath(out))


def simulate_cohort(
    out: PathLike,
    healthy: int = 2,
    ldh: int = 2,
    seconds: float = 25.0,
    seed: int = 1,
    rate_hz: float = 100.0,
    turn: bool = True,
) -> str:
    """Simulate a cohort into ``out`` exactly as ``ldh simulate`` does; returns the manifest
    CSV text. The same seed gives byte-identical files."""
    return _ldh.simulate_cohort(os.fspath(out), healthy, ldh, seconds, seed, rate_hz, turn)


def _opt_float(v: Optional[float]) -> Optional[float]:
    return None if v is None else float(v)


def _params_json(params: Optional[Dict[str, Any]]) -> Optional[str]:
    if params is None:
        return None
    if not isinstance(params, dict):
        raise LdhParamError(f"params must be a dict like docs/parameters.md, got {type(params).__name__}")
    return json.dumps(params)


def _columns(rows: Sequence[Dict[str, Any]]) -> Dict[str, Any]:
    """Rows (dicts) to columns: numeric columns as float64 arrays with NaN for missing values,
    the others as lists. ``pandas.DataFrame(result)`` takes it as it is."""
    if not rows:
        return {}
    out: Dict[str, Any] = {}
    for key in rows[0]:
        vals = [r[key] for r in rows]
        if all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in vals):
            out[key] = np.array([np.nan if v is None else v for v in vals], dtype=np.float64)
        else:
            out[key] = vals
    return out


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
) -> Dict[str, Dict[str, Any]]:
    """Analyse recordings exactly as ``ldh analyze`` does.

    Parameters
    ----------
    inputs : path or sequence of paths, optional
        A manifest CSV, a cohort folder, a subject folder or a subject's two files; ``None``:
        the embedded demo cohort.
    model : {"fusion", "acc"}, optional
        Attitude model (default: from ``params``, else "fusion").
    detector : str, optional
        Event detector (``gyro-landmarks`` — the default —, ``gyro-zero-crossing``,
        ``salarian``, ``pitch-peaks``).
    format : str, optional
        Sensor format name or TOML column map; default: detect.
    compute_sta : bool, optional
        Compute the Lyapunov stability STA (default True).
    sensor_height_m : float, optional
        Sensor height above the ankle when the manifest has none, in metres (default 0.10).
    n_jobs : int or None, default 1
        Rust threads for the subjects (the GIL is released); ``None`` or ``-1``: all cores.
        Results are identical whatever the number.
    params : dict, optional
        Any analysis parameter, nested as in docs/parameters.md and with the Rust names and
        defaults, e.g. ``{"attitude": {"smoother": False}, "preprocess": {"cutoff_hz": 8.0}}``;
        unknown names are refused. ``model``, ``detector``, ``sensor_height_m`` and
        ``compute_sta`` are applied on top.
    subject_id : str, optional
        Subject id of two files given directly (``ldh analyze --subject``; default: the common
        stem of their names).
    setting : {"overground", "treadmill"}, optional
        Setting of every subject whose manifest row does not say (``--setting``); on a
        treadmill no stride is flagged as a turn (docs/input.md).

    Returns
    -------
    dict
        ``{"strides": ..., "recordings": ..., "events": ...}``, each a dict of columns
        (float64 arrays with NaN for missing values, lists for text) that
        ``pandas.DataFrame`` accepts as it is. A recording that failed has ``status ==
        "error"`` and its ``error``; nothing is raised for it. Problems that did not stop a
        recording (different clocks of the two files, upside-down mounting, running, a frozen
        channel...) are in the ``warnings`` column (``"; "``-separated, empty when none).
    """
    if inputs is None:
        paths: list = []
    elif isinstance(inputs, (str, os.PathLike)):
        paths = [os.fspath(inputs)]
    else:
        paths = [os.fspath(p) for p in inputs]
        if not paths:
            # Only ``None`` means the embedded demo: an empty list is a mistake, not a request.
            raise LdhParamError("inputs is an empty list: give paths, or None for the embedded demo cohort")
    if n_jobs is not None and n_jobs != -1 and int(n_jobs) < 1:
        raise LdhParamError(f"n_jobs must be a positive number, -1 or None (all cores), got {n_jobs}")
    jobs = 0 if n_jobs in (None, -1) else int(n_jobs)
    raw = json.loads(
        _ldh.analyze(
            paths, model, detector, format, compute_sta, _opt_float(sensor_height_m), jobs, _params_json(params),
            subject_id, setting,
        )
    )
    return {k: _columns(v) for k, v in raw.items()}


def analyze_many(paths: Sequence[PathLike], n_jobs: Optional[int] = None, **kwargs: Any) -> Dict[str, Dict[str, Any]]:
    """Analyse many inputs (manifests, cohort or subject folders, pairs of files) in parallel
    on Rust threads; the same as :func:`analyze` with ``n_jobs`` defaulting to all cores.

    The function is pure (files in, columns out) and keeps no state, so it runs unchanged in
    Dask or Ray workers: ``client.map(lambda d: ldh.analyze(d, n_jobs=1), subject_dirs)``.
    An empty ``paths`` raises :class:`LdhParamError` (a ``ValueError``).
    """
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    paths = list(paths)
    if not paths:
        raise LdhParamError("analyze_many() got no paths")
    return analyze(paths, n_jobs=n_jobs, **kwargs)


_CHANNELS = ["acc_x_g", "acc_y_g", "acc_z_g", "gyro_x_dps", "gyro_y_dps", "gyro_z_dps"]


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
) -> Dict[str, Dict[str, Any]]:
    """Analyse one subject's two recordings given as arrays, with step time and step frequency
    from both legs — the same tables as :func:`analyze`.

    Parameters
    ----------
    left, right : dict
        Channels ``acc_x_g`` … ``gyro_z_dps`` (array_like, g and deg/s), e.g. the first value
        returned by :func:`read_recording`; ``fs_hz`` is taken from them when present.
    fs_hz : float, optional
        Sampling rate of both (both sensors share one clock).

    Returns
    -------
    dict
        ``{"strides", "recordings", "events"}`` as columns.
    """
    for name, rec in (("left", left), ("right", right)):
        missing = [c for c in _CHANNELS if c not in rec]
        if missing:
            raise LdhParamError(f"{name} lacks the channels {missing}")
    rates = {float(r["fs_hz"]) for r in (left, right) if r.get("fs_hz") is not None}
    if fs_hz is None and len(rates) > 1:
        raise LdhDataError(f"the two recordings have different sampling rates {sorted(rates)} Hz; resample one or pass fs_hz")
    rate = fs_hz if fs_hz is not None else (rates.pop() if rates else None)
    if rate is None:
        raise LdhParamError("fs_hz is needed when the dicts do not carry it")
    lv = [_vec(left[c], f"left[{c}]") for c in _CHANNELS]
    rv = [_vec(right[c], f"right[{c}]") for c in _CHANNELS]
    raw = json.loads(_ldh.analyze_pair(lv, rv, float(rate), subject_id, model, detector, _opt_float(sensor_height_m), compute_sta, _params_json(params)))
    return {k: _columns(v) for k, v in raw.items()}


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
        Event detector.
    sensor_height_m : float
        Sensor height above the ankle, m.
    compute_sta : bool
        Compute the Lyapunov stability STA.

    Returns
    -------
    dict
        ``alignment`` (dict), ``events`` (``hs_s``, ``to_s``, ``midswing_s`` arrays),
        ``strides`` (columns), ``parameters`` (dict), ``attitude`` (``pitch_deg``,
        ``roll_deg``, ``yaw_deg`` arrays), ``outliers_replaced``, ``warnings`` (list of str:
        problems that did not stop the analysis, e.g. an upside-down mounting or too few
        valid strides).
    """
    acc = [_vec(c, f"acc_g[{i}]") for i, c in enumerate(acc_g)]
    gyro = [_vec(c, f"gyro_dps[{i}]") for i, c in enumerate(gyro_dps)]
    if len(acc) != 3 or len(gyro) != 3:
        raise LdhParamError("acc_g and gyro_dps must each hold three channels (x, y, z)")
    text, pitch, roll, yaw = _ldh.analyze_recording(
        acc, gyro, float(fs_hz), side, model, detector, _opt_float(sensor_height_m), compute_sta, _params_json(params)
    )
    raw = json.loads(text)
    raw["strides"] = _columns(raw["strides"])
    raw["events"] = {k: np.asarray(v, dtype=np.float64) if isinstance(v, list) else v for k, v in raw["events"].items()}
    raw["attitude"] = {"pitch_deg": pitch, "roll_deg": roll, "yaw_deg": yaw}
    raw["parameters"] = {k: (np.nan if v is None else v) for k, v in raw["parameters"].items()}
    return raw


def lyap_r(
    data: Any,
    emb_dim: int = 10,
    lag: Optional[int] = None,
    min_tsep: Optional[int] = None,
    tau: float = 1,
    min_neighbors: int = 20,
    trajectory_len: int = 20,
    fit: str = "poly",
    debug_data: bool = False,
    fit_offset: int = 0,
) -> Union[float, Tuple[float, Tuple[np.ndarray, np.ndarray, np.ndarray]]]:
    """Largest Lyapunov exponent by Rosenstein et al. (1993), equal to
    ``nolds.lyap_r(..., fit="poly")`` to 1e-6 with the same arguments (nolds' names and
    defaults; lag and min_tsep from nolds' rules when None). A k-d tree replaces nolds' full
    distance matrix, so long series are fine.

    Returns the exponent, or with ``debug_data=True`` ``(exponent, (ks, divergence, poly))`` as
    nolds does.
    """
    le, ks, div, (slope, intercept) = _ldh.lyap_r(
        _vec(data, "data"), int(emb_dim), lag, min_tsep, float(tau), int(min_neighbors),
        int(trajectory_len), fit, int(fit_offset),
    )
    if debug_data:
        return le, (ks, div, np.array([slope, intercept]))
    return le


def lyap_e(
    data: Any,
    emb_dim: int = 10,
    matrix_dim: int = 4,
    min_nb: Optional[int] = None,
    min_tsep: int = 0,
    tau: float = 1,
) -> np.ndarray:
    """Lyapunov spectrum (``matrix_dim`` exponents) by Eckmann et al. (1986), equal to
    ``nolds.lyap_e`` with the same arguments (nolds' names and defaults)."""
    return _ldh.lyap_e(_vec(data, "data"), int(emb_dim), int(matrix_dim), min_nb, int(min_tsep), float(tau))


class TestResult(NamedTuple):
    """(statistic, pvalue), like scipy.stats' result objects."""

    statistic: float
    pvalue: float


def _test(name: str, samples: Sequence[Any], alternative: str = "two-sided", equal_var: bool = True) -> TestResult:
    arrs = [_vec(x, f"sample {i}").tolist() for i, x in enumerate(samples)]
    return TestResult(*_ldh.stats_test(name, arrs, alternative, bool(equal_var)))


def shapiro(x: Any) -> TestResult:
    """Shapiro-Wilk normality test; equals ``scipy.stats.shapiro`` to 1e-6."""
    return _test("shapiro", [x])


def mannwhitneyu(x: Any, y: Any, alternative: str = "two-sided") -> TestResult:
    """Mann-Whitney U (statistic: U of ``x``); equals ``scipy.stats.mannwhitneyu`` with its
    defaults (``use_continuity=True``, ``method="auto"``)."""
    return _test("mannwhitneyu", [x, y], alternative)


def ttest_ind(a: Any, b: Any, equal_var: bool = True, alternative: str = "two-sided") -> TestResult:
    """Student (``equal_var=True``) or Welch t-test; equals ``scipy.stats.ttest_ind``."""
    return _test("ttest_ind", [a, b], alternative, equal_var)


def ttest_rel(a: Any, b: Any, alternative: str = "two-sided") -> TestResult:
    """Paired t-test; equals ``scipy.stats.ttest_rel``."""
    return _test("ttest_rel", [a, b], alternative)


def wilcoxon(x: Any, y: Any = None, alternative: str = "two-sided") -> TestResult:
    """Wilcoxon signed-rank test of ``x`` (differences) or of ``x - y``; equals
    ``scipy.stats.wilcoxon`` with its defaults."""
    return _test("wilcoxon", [x] if y is None else [x, y], alternative)


def f_oneway(*groups: Any) -> TestResult:
    """One-way ANOVA; equals ``scipy.stats.f_oneway``."""
    return _test("f_oneway", groups)


def kruskal(*groups: Any) -> TestResult:
    """Kruskal-Wallis H test with tie correction; equals ``scipy.stats.kruskal``."""
    return _test("kruskal", groups)


def pearsonr(x: Any, y: Any, alternative: str = "two-sided") -> TestResult:
    """Pearson correlation and its exact p-value; equals ``scipy.stats.pearsonr``."""
    return _test("pearsonr", [x, y], alternative)


def holm(pvalues: Sequence[float]) -> np.ndarray:
    """Holm-adjusted p-values (as ``statsmodels.stats.multitest.multipletests(method="holm")``)."""
    return np.asarray(_ldh.holm([float(p) for p in pvalues]), dtype=np.float64)


def _matrix(x: Any) -> np.ndarray:
    a = np.ascontiguousarray(x, dtype=np.float64)
    if a.ndim != 2:
        raise LdhParamError(f"X must be two-dimensional (rows x features), got shape {a.shape}")
    return a


def cross_validate(
    X: Any,
    y: Sequence[int],
    groups: Optional[Sequence[str]] = None,
    *,
    classifier: str = "rf",
    task: str = "three-class",
    k: int = 10,
    repeats: int = 10,
    seed: int = 1,
    kind: str = "grouped",
    folds: Optional[Sequence[Sequence[int]]] = None,
    top_k: Optional[int] = None,
) -> Dict[str, Any]:
    """Repeated k-fold cross-validation of ``rf``, ``svm`` or ``mlp`` as ``ldh train`` runs it.

    Parameters
    ----------
    X : array_like, shape (n, p)
        Features (min-max scaled inside each training fold).
    y : sequence of int
        Labels: three-class 0 LDHH, 1 LDHE, 2 H; binary 0 H, 1 LDHE.
    groups : sequence of str, optional
        Subject of each row, for ``kind="grouped"`` (default: every row its own subject).
    classifier : {"rf", "svm", "mlp"}
    task : {"three-class", "binary"}
    k, repeats, seed : int
        Folds, repeats of the split, seed of folds and models.
    kind : {"grouped", "stratified"}
        Subject-grouped (default) or stratified folds.
    folds : sequence of sequences of int, optional
        Fold id of every row for every repeat, to reuse another tool's folds.
    top_k : int, optional
        Keep the top-k features by |Pearson r| inside each training fold.

    Returns
    -------
    dict
        accuracy, precision_macro, recall_macro, f1_macro ({"mean", "sd"}), per_class,
        confusion, permutation_importance, accuracy_per_repeat.
    """
    f = None if folds is None else [[int(v) for v in r] for r in folds]
    g = None if groups is None else [str(v) for v in groups]
    return json.loads(_ldh.cross_validate(_matrix(X), [int(v) for v in y], g, classifier, task, int(k), int(repeats), int(seed), kind, f, top_k))


def train(
    X: Any,
    y: Sequence[int],
    feature_names: Sequence[str],
    *,
    classifier: str = "rf",
    task: str = "three-class",
    seed: int = 1,
    attitude_model: str = "fusion",
) -> str:
    """Train on all rows and return the model file (JSON text) that ``ldh predict`` and
    :func:`predict` read. Save it with ``open(path, "w").write(model)``."""
    return _ldh.train(_matrix(X), [int(v) for v in y], [str(n) for n in feature_names], classifier, task, int(seed), attitude_model)


def predict(model: str, X: Any, feature_names: Optional[Sequence[str]] = None) -> Tuple[np.ndarray, Optional[np.ndarray]]:
    """Predict with a model file's JSON text (or a path to it). Returns (labels, probabilities
    or None for models without them). With ``feature_names`` the model refuses mismatched
    features, naming them."""
    if isinstance(model, (os.PathLike,)) or (isinstance(model, str) and not model.lstrip().startswith("{")):
        with open(model, encoding="utf-8") as fh:
            model = fh.read()
    names = None if feature_names is None else [str(n) for n in feature_names]
    labels, proba = _ldh.predict(model, _matrix(X), names)
    return np.asarray(labels, dtype=np.int64), proba
