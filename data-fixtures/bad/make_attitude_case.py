#!/usr/bin/env python3
"""The attitude-divergence case of the bad-input corpus: `gyro_bias_drift`.

Usage: python3 data-fixtures/bad/make_attitude_case.py [path/to/ldh]

A 40 s simulated walk at 50 Hz (`ldh simulate`, one healthy subject, no turn, seed 3) with the
quiet standing at both ends cut off (so no bias can be measured at rest, as in HuGaDB), and a
left gyroscope whose bias drifts over the walk from (6, -8, 3) to (12, -14, 3) deg/s on the
device axes: within the ±20 deg/s zero-rate tolerance of consumer MEMS gyroscopes, and 5-10
times the 1-3 deg/s of HuGaDB's shank gyroscopes. Integrated without correction it tilts the
shank by hundreds of degrees over the walk. Plain Python; expected.toml is written by hand.
"""
import math

from make_corpus import HERE, case, simulate, text


def main():
    left, right = simulate(rate_hz=50, seconds=40, seed=3)
    moving = [r[0] for r in left if math.sqrt(sum(g * g for g in r[4:7])) > 30.0]
    t0, t1 = moving[0] - 0.3, moving[-1] + 0.3
    keep = lambda rows: [r for r in rows if t0 <= r[0] <= t1]
    left, right = keep(left), keep(right)
    biased = []
    for r in left:
        u = (r[0] - t0) / (t1 - t0)
        b = (6.0 + 6.0 * u, -8.0 - 6.0 * u, 3.0)
        biased.append(r[:4] + tuple(g + bi for g, bi in zip(r[4:7], b)))
    case("gyro_bias_drift", left_csv=text(biased), right_csv=text(right))
    print(f"gyro_bias_drift: {len(biased)} rows, {t0:.2f}-{t1:.2f} s -> {HERE / 'gyro_bias_drift'}")


if __name__ == "__main__":
    main()
