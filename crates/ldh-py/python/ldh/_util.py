"""Argument conversion shared by the ldh modules (no computation)."""
from __future__ import annotations

import os
from typing import Any, Optional, Union

import numpy as np

from ._errors import LdhParamError, LdhTypeError

PathLike = Union[str, "os.PathLike[str]"]


def vec(x: Any, name: str) -> np.ndarray:
    """A one-dimensional contiguous float64 array."""
    a = np.ascontiguousarray(x, dtype=np.float64)
    if a.ndim != 1:
        raise LdhParamError(f"{name} must be one-dimensional, got shape {a.shape}")
    return a


def matrix(x: Any) -> np.ndarray:
    """A two-dimensional contiguous float64 array (rows x features)."""
    a = np.ascontiguousarray(x, dtype=np.float64)
    if a.ndim != 2:
        raise LdhParamError(f"X must be two-dimensional (rows x features), got shape {a.shape}")
    return a


def opt_float(v: Optional[float]) -> Optional[float]:
    return None if v is None else float(v)


def params_dict(params: Any) -> Optional[dict]:
    if params is None:
        return None
    if not isinstance(params, dict):
        raise LdhParamError(f"params must be a dict like docs/parameters.md, got {type(params).__name__}")
    return params


def sample_limit(v: Any) -> int:
    """``max_samples``: an int the core can hold (the core refuses 0 with its own message)."""
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or not 0 <= v < 2**64:
        raise LdhParamError(f"max_samples must be a positive int, got {v!r}")
    return int(v)


def _kind(x: Any) -> str:
    """What ``x`` is, as a message names it: ``a pandas DataFrame``, ``a numpy ndarray``,
    ``an int``."""
    t = type(x)
    mod = t.__module__.split(".")[0]
    name = t.__name__ if mod == "builtins" else f"{mod} {t.__name__}"
    return ("an " if name[0].lower() in "aeiou" else "a ") + name


def path_arg(x: Any, func: str, arg: str, instead: str = "") -> str:
    """A path argument of ``ldh.<func>``: a str or os.PathLike, else :class:`LdhTypeError`
    naming the function and, in ``instead``, what to use for data in memory."""
    if isinstance(x, (str, os.PathLike)):
        return os.fspath(x)
    hint = f"; {instead}" if instead else ""
    raise LdhTypeError(f"ldh.{func}(): {arg} must be a path (str or os.PathLike), got {_kind(x)}{hint}")


def path_list(x: Any, func: str, arg: str, instead: str = "") -> list:
    """A path or a list of paths of ``ldh.<func>`` as a list of str (:func:`path_arg` for each;
    a DataFrame, an array or a dict is never iterated as if it held paths)."""
    if isinstance(x, (str, os.PathLike)):
        return [os.fspath(x)]
    table = isinstance(x, dict) or hasattr(x, "columns") or (isinstance(x, np.ndarray) and x.dtype.kind not in "UO")
    if table or not hasattr(x, "__iter__"):
        path_arg(x, func, arg, instead)
    return [path_arg(p, func, f"{arg}[{i}]", instead) for i, p in enumerate(x)]


#: What to use for recordings in memory, for the messages of the functions that read files.
ARRAYS_INSTEAD = (
    "for arrays or DataFrames in memory use ldh.analyze_pair(left, right, fs_hz) (one person's "
    "two legs, dicts or DataFrames of the channels acc_x_g ... gyro_z_dps) or "
    "ldh.analyze_recording(acc_g, gyro_dps, fs_hz) (one leg)"
)
