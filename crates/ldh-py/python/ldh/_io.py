"""Reading recordings, filters, the demo and the simulator."""
from __future__ import annotations

import os
import warnings
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np

from . import _ldh
from ._errors import LdhParamError, LdhWarning
from ._util import ARRAYS_INSTEAD, PathLike, path_arg, sample_limit, vec as _vec


def read_recording(
    path: PathLike,
    format: Optional[str] = None,
    *,
    max_gap_s: float = 0.2,
    gap_policy: str = "split",
    min_duration_s: float = 4.0,
    check_units: bool = True,
    max_file_size_mb: float = 256.0,
    max_samples: int = 2_500_000,
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
    max_file_size_mb : float, default 256.0
        Largest file read, in MB (10^6 bytes), checked before reading (``ldh inspect
        --max-file-size-mb``): a mistaken multi-gigabyte export or ``/dev/zero`` cannot fill
        the memory.
    max_samples : int, default 2500000
        Most data rows in the recording (6.9 h at 100 Hz; ``--max-samples``), checked while
        it is streamed, before the rows past the limit are stored; the analysis keeps about
        150 bytes per sample.

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
    LdhTypeError
        ``path`` is not a path (also a ``TypeError``); the message names the functions for
        arrays and DataFrames.
    LdhDataError
        The file is not a usable recording (also a ``ValueError``); the message names the
        file, line and column. Also a file above ``max_file_size_mb`` or a recording with
        more rows than ``max_samples`` (the message names the file, its size or row count,
        and the limit).
    LdhParamError
        An invalid option (also a ``ValueError``), e.g. ``max_samples=0``.
    """
    rec, report = _ldh.read_recording(
        path_arg(path, "read_recording", "path", ARRAYS_INSTEAD), format, max_gap_s, gap_policy, min_duration_s, check_units,
        float(max_file_size_mb), sample_limit(max_samples),
    )
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
    return _ldh.write_demo(path_arg(out, "write_demo", "out"))


def simulate_cohort(
    out: PathLike,
    healthy: int = 2,
    ldh: int = 2,
    seconds: float = 25.0,
    seed: int = 1,
    rate_hz: float = 100.0,
    turn: bool = True,
    slow_ldh: int = 0,
    acc_range_g: float = 8.0,
    ramp_s: float = 0.0,
    trials: int = 1,
    day_to_day_sd_fraction: Optional[float] = None,
) -> str:
    """Simulate a cohort into ``out`` exactly as ``ldh simulate`` does (subject folders,
    ``manifest.csv`` and ``cohort.json``); returns the manifest CSV text. The same seed gives
    byte-identical files.

    ``slow_ldh`` adds that many slow, severely affected LDH subjects (0.28–0.75 m/s, strides
    of 1.35–2.0 s; ids ``S01``…, after the others), as ``ldh simulate --slow-ldh``; they need
    ``seconds >= 20``. Each has its own random stream, so adding them leaves the other
    subjects' files unchanged.

    ``acc_range_g`` is the accelerometer's range (±g) as ``ldh simulate --acc-range-g``: 2 makes
    the swing and heel-strike accelerations clip as HuGaDB's ±2 g devices do (the stride length
    then reconstructs the clipped samples, docs/accuracy.md); the default 8 never clips.

    ``ramp_s`` makes each walk a treadmill walk whose belt starts up over that many seconds, as
    ``ldh simulate --ramp-s``: strides 25 % longer at the first step, steady from ``ramp_s`` on
    (needs ``turn=False``; the truth marks those strides ``accelerating``).

    ``trials`` ≥ 2 makes a retest cohort, as ``ldh simulate --trials``: each person walks that
    many times (``<subject>/T1/``…, a ``trial_id`` column in the manifest) with their own gait
    and a day-to-day variation of their mean stride time and stride length whose SD is
    ``day_to_day_sd_fraction`` of their own value (default 0.03 with two or more trials; each
    trial from a fresh random stream; docs/agreement.md). One trial is the plain cohort.

    Sizes beyond the core's declared limits (100 000 subjects; 1 000 000 samples per leg,
    i.e. ``seconds * rate_hz``) raise :class:`LdhParamError` (a ``ValueError``) before any
    work, as do negative or non-integer counts."""
    for name, v in (("healthy", healthy), ("ldh", ldh), ("slow_ldh", slow_ldh), ("seed", seed), ("trials", trials)):
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
            raise LdhParamError(f"{name} must be a non-negative int, got {v!r}")
    if healthy >= 2**64 or ldh >= 2**64 or slow_ldh >= 2**64:
        # Beyond what the core can represent (its own limit, checked there, is far lower).
        raise LdhParamError(
            f"healthy + ldh + slow_ldh = {healthy} + {ldh} + {slow_ldh}: far more subjects than a simulated cohort can hold"
        )
    if seed >= 2**64:
        raise LdhParamError(f"seed must be below 2**64, got {seed!r}")
    return _ldh.simulate_cohort(
        path_arg(out, "simulate_cohort", "out"), int(healthy), int(ldh), float(seconds), int(seed), float(rate_hz), bool(turn),
        int(slow_ldh), float(acc_range_g), float(ramp_s), int(trials),
        None if day_to_day_sd_fraction is None else float(day_to_day_sd_fraction),
    )


