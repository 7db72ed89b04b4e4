"""Classifiers from Python: CV parity with scikit-learn on the same folds, train/predict."""
import json
import pathlib

import numpy as np
import pytest

import ldh

ROOT = pathlib.Path(__file__).resolve().parents[3]
ML = ROOT / "data-fixtures" / "ml"
GOLDEN = json.loads((ROOT / "data-fixtures" / "golden" / "ml" / "sklearn_cv.json").read_text())


def _load(task):
    d = np.genfromtxt(ML / f"{task}_dataset.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    names = list(d.dtype.names[4:])
    X = np.vstack([d[n].astype(float) for n in names]).T
    f = np.genfromtxt(ML / f"{task}_folds.csv", delimiter=",", names=True, dtype=None, encoding="utf-8")
    return X, d["label"].astype(int), [str(s) for s in d["subject_id"]], names, f


@pytest.mark.parametrize("task", ["three_class", "binary"])
@pytest.mark.parametrize("kind", ["grouped", "stratified"])
def test_cv_accuracy_within_three_points_of_scikit_learn(task, kind):
    X, y, groups, names, f = _load(task)
    folds = [f[c].astype(int).tolist() for c in f.dtype.names if c.startswith(kind + "_r")]
    for clf in ["rf", "svm", "mlp"]:
        r = ldh.cross_validate(X, y, groups, classifier=clf, task=task.replace("_", "-"), folds=folds)
        ref = GOLDEN["results"][f"{task}/{kind}/{clf}"]["accuracy_mean"]
        assert abs(r["accuracy"]["mean"] - ref) <= 0.03, (clf, r["accuracy"]["mean"], ref)


def test_train_predict_and_model_refusals(tmp_path):
    X, y, groups, names, _ = _load("binary")
    model = ldh.train(X, y, names, classifier="mlp", task="binary", seed=3)
    labels, proba = ldh.predict(model, X, names)
    assert (labels == y).mean() > 0.7
    np.testing.assert_allclose(proba.sum(axis=1), 1.0, atol=1e-9)
    path = tmp_path / "m.json"
    path.write_text(model)
    labels2, _ = ldh.predict(str(path), X)
    np.testing.assert_array_equal(labels, labels2)
    with pytest.raises(ValueError, match="missing"):
        ldh.predict(model, X[:, :-1], names[:-1])
    with pytest.raises(ldh.LdhDataError, match="schema"):
        ldh.predict(model.replace("ldh-model/3", "ldh-model/9"), X)
    svm = ldh.train(X, y, names, classifier="svm", task="binary")
    _, p = ldh.predict(svm, X)
    assert p is None
    r1 = ldh.cross_validate(X, y, groups, classifier="rf", task="binary", k=5, repeats=2)
    r2 = ldh.cross_validate(X, y, groups, classifier="rf", task="binary", k=5, repeats=2)
    assert r1 == r2
    with pytest.raises(ValueError, match="fewer subjects"):
        ldh.cross_validate(X, y, groups, task="binary", k=50)
    with pytest.raises(ValueError, match="only one class"):
        ldh.cross_validate(X, np.ones_like(y), groups, task="binary")
    with pytest.raises(ldh.LdhParamError, match="two-dimensional"):
        ldh.cross_validate(X[:, 0], y)


def test_predict_from_a_path_names_the_file_in_typed_errors(tmp_path):
    """Issue 37: a model read from its path is read as `ldh predict` reads it; an edit re-sealed
    with a recomputed checksum, a FIFO and an oversized file raise typed errors naming it."""
    import os
    import sys

    sys.path.insert(0, str(ROOT / "data-fixtures" / "bad"))
    import edit_model

    X, y, _, names, _ = _load("three_class")
    for clf in ["rf", "svm", "mlp"]:
        path = tmp_path / f"{clf}.json"
        path.write_text(ldh.train(X, y, names, classifier=clf, seed=3))
        labels, _ = ldh.predict(str(path), X, names)
        assert len(labels) == len(y)
    mlp = tmp_path / "mlp.json"
    edit_model.main(["", str(mlp), "mlp-weight-1e200"])
    with pytest.raises(ldh.LdhDataError, match=r"mlp\.json: implausible model: MLP layer 0"):
        ldh.predict(str(mlp), X)
    with pytest.raises(ldh.LdhDataError, match=r"rf\.json: the input's features do not match"):
        ldh.predict(tmp_path / "rf.json", X[:, :-1], names[:-1])
    fifo = tmp_path / "fifo.json"
    os.mkfifo(fifo)
    with pytest.raises(ldh.LdhOSError, match="not a regular file"):
        ldh.predict(str(fifo), X)
    big = tmp_path / "big.json"
    with open(big, "wb") as fh:
        fh.truncate(20_000_000)
    with pytest.raises(ldh.LdhDataError, match=r"big\.json: not a model file: 20\.0 MB"):
        ldh.predict(str(big), X)
