#!/usr/bin/env python3
"""nolds.lyap_r with its default fit="RANSAC" on the series of the Lyapunov goldens
(data-fixtures/golden/lyapunov/<name>.json, first lyap_r case's parameters), repeated with
20 numpy seeds: scikit-learn's RANSAC draws random point triples, so nolds' value varies
between runs. ldh.lyap_r's deterministic RANSAC must give the value nolds gives most often.

Setup: pip install "nolds==0.6.2" "setuptools<81" numpy scikit-learn
Run:   python3 data-fixtures/scripts/gen_lyapunov_ransac_golden.py
Writes data-fixtures/golden/lyapunov/ransac.json.
"""
import collections
import json
import pathlib
import warnings

import nolds
import numpy as np
import sklearn

HERE = pathlib.Path(__file__).resolve().parents[1] / "golden" / "lyapunov"
KEYS = ("emb_dim", "lag", "min_tsep", "tau", "min_neighbors", "trajectory_len", "fit_offset")


def main():
    warnings.simplefilter("ignore")
    out = {"generator": "data-fixtures/scripts/gen_lyapunov_ransac_golden.py",
           "versions": {"nolds": "0.6.2", "numpy": np.__version__, "sklearn": sklearn.__version__},
           "cases": []}
    for name in ["lorenz", "logistic", "noise", "gait"]:
        g = json.loads((HERE / f"{name}.json").read_text())
        x = np.array(g["series"], dtype=np.float64)
        p = {k: v for k, v in g["lyap_r"][0]["params"].items() if k in KEYS}
        runs = []
        for seed in range(20):
            np.random.seed(seed)
            runs.append(float(nolds.lyap_r(x, **p)))
        counts = collections.Counter(round(v, 10) for v in runs)
        mode = max(counts, key=lambda v: counts[v])
        out["cases"].append({"series": name, "params": p, "runs": runs,
                             "most_frequent": mode, "frequency": counts[mode] / len(runs)})
        print(name, p, "most frequent", mode, counts[mode], "/", len(runs))
    (HERE / "ransac.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
