#!/usr/bin/env python3
"""scikit-learn on the same feature tables and the same folds as ldh's cross-validation.

The tables in data-fixtures/ml/ were written by
    ldh simulate --out COHORT --healthy 15 --ldh 20 --seconds 30 --seed 11 --ldh-severity-min 0
    ldh train COHORT --task three-class|binary --out OUT     (dataset.csv, folds.csv)
and copied here. For every task, fold kind (subject-grouped, stratified) and repeat, each
classifier is fitted in a Pipeline(MinMaxScaler, clf) on the training folds and predicts the test
fold; the accuracy of a repeat is over all its test predictions. The randomised classifiers (RF,
MLP) are run with 3 model seeds and their accuracy averaged over seeds and repeats: a single seed
moves a forest's mean accuracy by about ±2 points, too close to the 3-point parity margin. The
means are recorded in data-fixtures/golden/ml/sklearn_cv.json with the library versions.

Classifiers (ldh's defaults): RandomForestClassifier(n_estimators=100, max_features="sqrt"),
SVC(kernel="rbf", C=1, gamma="scale"), MLPClassifier() (hidden layer 100, Adam, max_iter 200).

Run from the repository root:  python3 data-fixtures/scripts/sklearn_cv.py
For timing against `ldh train` (one model seed, as ldh fits): --seeds 1 --no-write.
"""
import json
import platform
import warnings
from pathlib import Path

import numpy as np
import sklearn
from sklearn.ensemble import RandomForestClassifier
from sklearn.exceptions import ConvergenceWarning
from sklearn.neural_network import MLPClassifier
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import MinMaxScaler
from sklearn.svm import SVC

ROOT = Path(__file__).resolve().parents[2]
ML = ROOT / "data-fixtures" / "ml"
OUT = ROOT / "data-fixtures" / "golden" / "ml" / "sklearn_cv.json"
SEEDS = [0, 1, 2]


def load(task):
    d = np.genfromtxt(ML / f"{task}_dataset.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    names = d.dtype.names[4:]
    x = np.vstack([d[n].astype(float) for n in names]).T
    y = d["label"].astype(int)
    f = np.genfromtxt(ML / f"{task}_folds.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    return x, y, f


def make(name, seed):
    if name == "rf":
        return RandomForestClassifier(n_estimators=100, max_features="sqrt", random_state=seed)
    if name == "svm":
        return SVC(kernel="rbf", C=1.0, gamma="scale")
    return MLPClassifier(random_state=seed)


def main():
    import argparse
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=len(SEEDS), help="model seeds of RF and MLP (default 3)")
    ap.add_argument("--no-write", action="store_true", help="do not rewrite the golden JSON (timing runs)")
    a = ap.parse_args()
    seeds = list(range(a.seeds))
    warnings.simplefilter("ignore", ConvergenceWarning)
    out = {"versions": {"python": platform.python_version(), "numpy": np.__version__, "sklearn": sklearn.__version__}, "results": {}}
    for task in ["three_class", "binary"]:
        x, y, folds = load(task)
        for kind in ["grouped", "stratified"]:
            cols = [c for c in folds.dtype.names if c.startswith(kind + "_r")]
            for name in ["rf", "svm", "mlp"]:
                accs = []
                for seed in (seeds if name != "svm" else seeds[:1]):
                    for r, col in enumerate(cols):
                        fid = folds[col].astype(int)
                        pred = np.empty_like(y)
                        for k in np.unique(fid):
                            tr, te = fid != k, fid == k
                            model = make_pipeline(MinMaxScaler(), make(name, 100000 * seed + 1000 * r + int(k)))
                            model.fit(x[tr], y[tr])
                            pred[te] = model.predict(x[te])
                        accs.append(float(np.mean(pred == y)))
                key = f"{task}/{kind}/{name}"
                out["results"][key] = {"accuracy_mean": float(np.mean(accs)), "accuracy_sd": float(np.std(accs, ddof=1)), "per_repeat": accs}
                print(f"{key}: {np.mean(accs):.3f} ± {np.std(accs, ddof=1):.3f}")
    if not a.no_write:
        OUT.parent.mkdir(parents=True, exist_ok=True)
        OUT.write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
