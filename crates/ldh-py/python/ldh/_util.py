"""Argument conversion shared by the ldh modules (no computation)."""
from __future__ import annotations

import os
from typing import Any, Optional, Union

import numpy as np

from ._errors import LdhParamError

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
