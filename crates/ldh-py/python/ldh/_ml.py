"""Cross-validation, training and prediction on arrays."""
from __future__ import annotations

import os
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np

from . import _ldh
from ._util import matrix as _matrix


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
    return _ldh.cross_validate(_matrix(X), [int(v) for v in y], g, classifier, task, int(k), int(repeats), int(seed), kind, f, top_k)


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
    features, naming them. A path is read as ``ldh predict --model`` reads it (a regular file of
    at most 16 MB, checked for damage and plausibility); every error is an ``LdhError`` naming
    the file."""
    names = None if feature_names is None else [str(n) for n in feature_names]
    if isinstance(model, (os.PathLike,)) or (isinstance(model, str) and not model.lstrip().startswith("{")):
        labels, proba = _ldh.predict("", _matrix(X), names, os.fspath(model))
    else:
        labels, proba = _ldh.predict(model, _matrix(X), names)
    return np.asarray(labels, dtype=np.int64), proba
