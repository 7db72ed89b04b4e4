"""The nolds look-alikes: Lyapunov exponents by Rosenstein et al. and Eckmann et al."""
from __future__ import annotations

from typing import Any, Literal, Optional, Tuple, Union, overload

import numpy as np

from . import _ldh
from ._util import vec as _vec


# The return type follows ``debug_data`` (as nolds'): a float, or the float and the curve.
@overload
def lyap_r(
    data: Any,
    emb_dim: int = 10,
    lag: Optional[int] = None,
    min_tsep: Optional[int] = None,
    tau: float = 1,
    min_neighbors: int = 20,
    trajectory_len: int = 20,
    fit: str = "RANSAC",
    debug_plot: bool = False,
    debug_data: Literal[False] = False,
    plot_file: Optional[str] = None,
    fit_offset: int = 0,
) -> float: ...
@overload
def lyap_r(
    data: Any,
    emb_dim: int = 10,
    lag: Optional[int] = None,
    min_tsep: Optional[int] = None,
    tau: float = 1,
    min_neighbors: int = 20,
    trajectory_len: int = 20,
    fit: str = "RANSAC",
    debug_plot: bool = False,
    *,
    debug_data: Literal[True],
    plot_file: Optional[str] = None,
    fit_offset: int = 0,
) -> Tuple[float, Tuple[np.ndarray, np.ndarray, np.ndarray]]: ...
@overload
def lyap_r(
    data: Any,
    emb_dim: int = 10,
    lag: Optional[int] = None,
    min_tsep: Optional[int] = None,
    tau: float = 1,
    min_neighbors: int = 20,
    trajectory_len: int = 20,
    fit: str = "RANSAC",
    debug_plot: bool = False,
    debug_data: bool = False,
    plot_file: Optional[str] = None,
    fit_offset: int = 0,
) -> Union[float, Tuple[float, Tuple[np.ndarray, np.ndarray, np.ndarray]]]: ...


def lyap_r(
    data: Any,
    emb_dim: int = 10,
    lag: Optional[int] = None,
    min_tsep: Optional[int] = None,
    tau: float = 1,
    min_neighbors: int = 20,
    trajectory_len: int = 20,
    fit: str = "RANSAC",
    debug_plot: bool = False,
    debug_data: bool = False,
    plot_file: Optional[str] = None,
    fit_offset: int = 0,
) -> Union[float, Tuple[float, Tuple[np.ndarray, np.ndarray, np.ndarray]]]:
    """Largest Lyapunov exponent by Rosenstein et al. (1993) with ``nolds.lyap_r``'s
    arguments, defaults and order, so ``import ldh as nolds`` keeps a nolds script's numbers.

    ``fit="RANSAC"`` (nolds' default) fits the divergence curve as nolds does through
    scikit-learn's RANSAC, but deterministically: the same random search is run 101 times with
    fixed seeds and the line found most often is kept, which is the value nolds returns most
    often (nolds' own value varies between runs).
    ``fit="poly"`` is the least-squares line and equals ``nolds.lyap_r(..., fit="poly")`` to
    1e-6. ``lag`` and ``min_tsep`` follow nolds' rules when None. A k-d tree replaces nolds'
    full distance matrix, so long series are fine.

    Size limit: the delay embedding (``len(data) * emb_dim`` values) may hold at most 10**7
    values (``ldh._ldh`` / ``MAX_ORBIT_VALUES`` in the core), i.e. 10**6 samples at the default
    ``emb_dim=10``: memory and time grow with it (10**7 samples took 3.4 GB and more than a
    minute), so a longer series raises :class:`ldh.LdhParamError` at once, naming its size and
    the limit. A negative count (``emb_dim``, ``lag``, ``min_tsep``, ``min_neighbors``,
    ``trajectory_len``, ``fit_offset``) raises :class:`ldh.LdhParamError` naming it.

    Returns the exponent, or with ``debug_data=True`` ``(exponent, (ks, divergence, poly))``
    as nolds does: the steps ``ks``, the mean log divergence at each step and the fitted line
    ``poly = [slope, intercept]``. ``debug_plot=True`` draws that curve and line with
    matplotlib (saved to ``plot_file`` when given, else shown).
    """
    le, ks, div, (slope, intercept) = _ldh.lyap_r(
        _vec(data, "data"), int(emb_dim), lag, min_tsep, float(tau), int(min_neighbors),
        int(trajectory_len), fit, int(fit_offset),
    )
    poly = np.array([slope, intercept])
    if debug_plot:
        _plot_divergence(ks, div, poly, fit_offset, plot_file)
    if debug_data:
        return le, (ks, div, poly)
    return le


def _plot_divergence(ks: np.ndarray, div: np.ndarray, poly: np.ndarray, fit_offset: int, plot_file: Optional[str]) -> None:
    import matplotlib.pyplot as plt  # optional dependency, as in nolds

    plt.figure()
    plt.plot(ks, div, "b+", label="log(divergence)")
    plt.plot(ks[fit_offset:], np.polyval(poly, ks[fit_offset:]), "r-", label="fit")
    plt.xlabel("k")
    plt.ylabel("<log(d(k))>")
    plt.legend(loc="best")
    if plot_file is None:
        plt.show()
    else:
        plt.savefig(plot_file)
    plt.close()


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


