#!/usr/bin/env python3
"""Generate the sklearn reference for `ldh_core::ml::mlp` (MLP classifier parity).

Usage (from the repository root):

    python3 data-fixtures/scripts/gen_mlp_reference.py

Writes `data-fixtures/golden/ml/mlp_reference.json` with:

* `x`: sklearn's `load_iris()` features, min-max scaled to [0, 1] per column
  over the whole data set (`MinMaxScaler`), `y`: the class labels 0/1/2;
* `folds`: the test indices of `StratifiedKFold(n_splits=5, shuffle=True,
  random_state=0)`, so the Rust test uses exactly the same folds;
* `sklearn_fold_accuracy` / `sklearn_mean_accuracy`: test accuracy of
  `MLPClassifier(hidden_layer_sizes=(32,), max_iter=500, random_state=0)`
  (every other option at sklearn's default: relu, adam, lr 1e-3, alpha 1e-4,
  batch_size min(200, n), tol 1e-4, n_iter_no_change 10) on each fold;
* the python / numpy / scikit-learn versions.

The Rust test fits `Mlp` with the same hyper-parameters on the same folds and
asserts that its mean accuracy is within 5 percentage points of sklearn's.
Bit-for-bit agreement is not expected: the random streams differ.
"""

import json
import os
import platform
import warnings

import numpy as np
import sklearn
from sklearn.datasets import load_iris
from sklearn.exceptions import ConvergenceWarning
from sklearn.model_selection import StratifiedKFold
from sklearn.neural_network import MLPClassifier
from sklearn.preprocessing import MinMaxScaler

OUT = os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "golden", "ml", "mlp_reference.json"
)


def main():
    iris = load_iris()
    x = MinMaxScaler().fit_transform(iris.data)
    y = iris.target.astype(int)
    skf = StratifiedKFold(n_splits=5, shuffle=True, random_state=0)
    folds, accs, n_iters = [], [], []
    for train, test in skf.split(x, y):
        clf = MLPClassifier(hidden_layer_sizes=(32,), max_iter=500, random_state=0)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            clf.fit(x[train], y[train])
        accs.append(float(clf.score(x[test], y[test])))
        n_iters.append(int(clf.n_iter_))
        folds.append([int(i) for i in test])
    out = {
        "meta": {
            "python": platform.python_version(),
            "numpy": np.__version__,
            "sklearn": sklearn.__version__,
            "generator": "data-fixtures/scripts/gen_mlp_reference.py",
            "dataset": "sklearn.datasets.load_iris, MinMaxScaler over all 150 rows",
            "model": "MLPClassifier(hidden_layer_sizes=(32,), max_iter=500, random_state=0)",
            "cv": "StratifiedKFold(n_splits=5, shuffle=True, random_state=0)",
        },
        "hidden_layer_sizes": [32],
        "max_iter": 500,
        "x": [[float(v) for v in row] for row in x],
        "y": [int(v) for v in y],
        "folds": folds,
        "sklearn_fold_accuracy": accs,
        "sklearn_fold_n_iter": n_iters,
        "sklearn_mean_accuracy": float(np.mean(accs)),
    }
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")
    print(f"sklearn mean 5-fold accuracy {out['sklearn_mean_accuracy']:.4f} folds {accs} n_iter {n_iters}")


if __name__ == "__main__":
    main()
