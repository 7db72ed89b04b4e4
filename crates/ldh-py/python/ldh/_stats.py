"""The scipy.stats look-alikes: same names, arguments, defaults and numbers as scipy, and
scipy-shaped results.

Each test returns a :class:`TestResult`: ``result.statistic``, ``result.pvalue`` and the extra
fields scipy has (``df`` for the t-tests and Kruskal-Wallis), unpacks as ``stat, p = result``,
and for the t-tests and ``pearsonr`` has ``result.confidence_interval(confidence_level=0.95)``
returning ``ConfidenceInterval(low, high)`` as scipy's does. ``axis`` (default 0, ``None``:
flatten) runs the test along one axis of n-dimensional inputs, giving arrays of statistics and
p-values; ``nan_policy`` is ``"propagate"`` (NaN in, NaN out: scipy's default), ``"omit"``
or ``"raise"``. Every computation is in the Rust core (``ldh._ldh``).
"""
from __future__ import annotations

from typing import Any, Callable, Dict, List, NamedTuple, Optional, Sequence

import numpy as np

from . import _ldh
from ._errors import LdhParamError


class ConfidenceInterval(NamedTuple):
    """``(low, high)``, as scipy's ``ConfidenceInterval``."""

    low: Any
    high: Any


class TestResult:
    """A test's result, shaped like scipy's: ``statistic``, ``pvalue`` (floats, or arrays when
    ``axis`` selected many tests), the test's extra fields as attributes (``df``...), and
    ``stat, p = result`` unpacking."""

    __test__ = False  # not a pytest class

    # Set in __init__ (a float, or an array of the ``axis`` shape); declared for type checkers.
    statistic: Any
    pvalue: Any
    df: Any

    def __init__(self, fields: List[Dict[str, Any]], shape: tuple, kind: Optional[str]):
        self._fields, self._shape, self._kind = fields, shape, kind
        keys = [k for k in fields[0] if isinstance(fields[0][k], (int, float, bool))] if fields else []
        for k in {"statistic", "pvalue"} | set(keys):
            vals = [f.get(k, np.nan) for f in fields]
            setattr(self, k, vals[0] if shape == () else np.asarray(vals, dtype=float).reshape(shape))
        if kind == "ttest" and not hasattr(self, "df"):
            self.df = np.nan if shape == () else np.full(shape, np.nan)

    def __iter__(self):
        return iter((self.statistic, self.pvalue))

    def __len__(self) -> int:
        return 2

    def __getitem__(self, i: int) -> Any:
        return (self.statistic, self.pvalue)[i]

    def __eq__(self, other: Any) -> bool:
        if isinstance(other, (tuple, TestResult)):
            return tuple(self) == tuple(other)
        return NotImplemented

    __hash__ = None  # mutable, like a list

    def __repr__(self) -> str:
        extra = "".join(f", {k}={getattr(self, k)!r}" for k in ("df",) if hasattr(self, k))
        return f"TestResult(statistic={self.statistic!r}, pvalue={self.pvalue!r}{extra})"

    def confidence_interval(self, confidence_level: float = 0.95) -> ConfidenceInterval:
        """Confidence interval at ``confidence_level`` (scipy's, for ``ttest_ind`` /
        ``ttest_rel`` / ``ttest_1samp``: of the mean difference or the mean; for ``pearsonr``:
        of the correlation, by Fisher's transformation). NaN where the test propagated a NaN."""
        if self._kind is None:
            raise AttributeError("confidence_interval exists for the t-tests and pearsonr (as in scipy)")
        lows, highs = [], []
        for f in self._fields:
            if np.isnan(f.get("statistic", np.nan)) or "alternative" not in f:
                lows.append(np.nan)
                highs.append(np.nan)
                continue
            lo, hi = _ldh.confidence_interval(self._kind, f, float(confidence_level))
            lows.append(lo)
            highs.append(hi)
        if self._shape == ():
            return ConfidenceInterval(lows[0], highs[0])
        return ConfidenceInterval(np.reshape(lows, self._shape), np.reshape(highs, self._shape))


def _slices(samples: Sequence[Any], axis: Optional[int]):
    """Each sample as float64 with the test axis last (``axis=None``: flattened), the common
    batch shape, and the 1-D slices per batch index."""
    arrs = [np.asarray(s, dtype=np.float64) for s in samples]
    if axis is None:
        arrs = [a.ravel() for a in arrs]
        return (), [[a for a in arrs]]
    for a in arrs:
        if a.ndim == 0:
            raise LdhParamError("a sample must have at least one dimension")
    arrs = [np.moveaxis(a, axis, -1) for a in arrs]
    try:
        shape = np.broadcast_shapes(*[a.shape[:-1] for a in arrs])
    except ValueError as e:
        raise LdhParamError(f"the samples' shapes do not broadcast apart from axis {axis}: {e}") from None
    arrs = [np.broadcast_to(a, shape + a.shape[-1:]) for a in arrs]
    return shape, [[np.ascontiguousarray(a[i]) for a in arrs] for i in np.ndindex(*shape)] if shape else [arrs]


def _run(call: Callable[..., Dict[str, Any]], samples: Sequence[Any], axis: Optional[int], kind: Optional[str] = None) -> TestResult:
    shape, per = _slices(samples, axis)
    fields = [call(*[s.tolist() for s in ss]) for ss in per]
    return TestResult(fields, shape, kind)


def shapiro(x: Any, *, axis: Optional[int] = None, nan_policy: str = "propagate") -> TestResult:
    """Shapiro-Wilk normality test; equals ``scipy.stats.shapiro`` to 1e-6 (scipy's default
    ``axis=None``: the whole array)."""
    return _run(lambda a: _ldh.shapiro(a, nan_policy), [x], axis)


def mannwhitneyu(x: Any, y: Any, alternative: str = "two-sided", *, axis: Optional[int] = 0, nan_policy: str = "propagate") -> TestResult:
    """Mann-Whitney U (statistic: U of ``x``); equals ``scipy.stats.mannwhitneyu`` with its
    defaults (``use_continuity=True``, ``method="auto"``)."""
    return _run(lambda a, b: _ldh.mannwhitneyu(a, b, alternative, nan_policy), [x, y], axis)


def ttest_ind(a: Any, b: Any, *, axis: Optional[int] = 0, equal_var: bool = True, nan_policy: str = "propagate", alternative: str = "two-sided") -> TestResult:
    """Student (``equal_var=True``) or Welch t-test; equals ``scipy.stats.ttest_ind``
    (``statistic``, ``pvalue``, ``df``, ``confidence_interval()`` of the difference of the
    means)."""
    return _run(lambda u, v: _ldh.ttest_ind(u, v, bool(equal_var), alternative, nan_policy), [a, b], axis, "ttest")


def ttest_rel(a: Any, b: Any, *, axis: Optional[int] = 0, nan_policy: str = "propagate", alternative: str = "two-sided") -> TestResult:
    """Paired t-test; equals ``scipy.stats.ttest_rel`` (``confidence_interval()`` of the mean
    difference). ``"omit"`` drops a pair where either value is NaN."""
    return _run(lambda u, v: _ldh.ttest_rel(u, v, alternative, nan_policy), [a, b], axis, "ttest")


def ttest_1samp(a: Any, popmean: float, *, axis: Optional[int] = 0, nan_policy: str = "propagate", alternative: str = "two-sided") -> TestResult:
    """One-sample t-test; equals ``scipy.stats.ttest_1samp`` (``confidence_interval()`` of the
    mean)."""
    return _run(lambda u: _ldh.ttest_1samp(u, float(popmean), alternative, nan_policy), [a], axis, "ttest")


def wilcoxon(x: Any, y: Any = None, alternative: str = "two-sided", *, axis: Optional[int] = 0, nan_policy: str = "propagate") -> TestResult:
    """Wilcoxon signed-rank test of ``x`` (differences) or of ``x - y``; equals
    ``scipy.stats.wilcoxon`` with its defaults."""
    if y is None:
        return _run(lambda u: _ldh.wilcoxon(u, None, alternative, nan_policy), [x], axis)
    return _run(lambda u, v: _ldh.wilcoxon(u, v, alternative, nan_policy), [x, y], axis)


def f_oneway(*samples: Any, axis: Optional[int] = 0, nan_policy: str = "propagate") -> TestResult:
    """One-way ANOVA; equals ``scipy.stats.f_oneway``."""
    return _run(lambda *g: _ldh.f_oneway(list(g), nan_policy), samples, axis)


def kruskal(*samples: Any, axis: Optional[int] = 0, nan_policy: str = "propagate") -> TestResult:
    """Kruskal-Wallis H test with tie correction; equals ``scipy.stats.kruskal``."""
    return _run(lambda *g: _ldh.kruskal(list(g), nan_policy), samples, axis)


def pearsonr(x: Any, y: Any, *, alternative: str = "two-sided", axis: Optional[int] = 0) -> TestResult:
    """Pearson correlation and its exact p-value; equals ``scipy.stats.pearsonr``
    (``confidence_interval()`` by Fisher's transformation, as scipy's default)."""
    return _run(lambda u, v: _ldh.pearsonr(u, v, alternative), [x, y], axis, "pearsonr")


def holm(pvalues: Sequence[float]) -> np.ndarray:
    """Holm-adjusted p-values (as ``statsmodels.stats.multitest.multipletests(method="holm")``)."""
    return np.asarray(_ldh.holm([float(p) for p in pvalues]), dtype=np.float64)
