"""The quality-check cases of the bad-input corpus (docs/quality.md), made from `baseline_ok`.

Plain Python, no dependencies: `python3 data-fixtures/bad/make_quality_cases.py`. Each case's
expected.toml is written by hand. Cases:

- gyro_scale_fault: the left gyroscope amplified x10 and clipped at +-2000 deg/s (HuGaDB's fault);
- gyro_clipped_250: the left gyroscope clipped at +-250 deg/s (a range below a shank's swing);
- rate_58_8_declared_100: both legs resampled to 58.8 Hz, time column stamped at 100 Hz
  (a 58.8 Hz device read as 100 Hz: every stride looks 1.7x faster);
- axial_rotation_60: both devices turned 60 deg about the shank axis (device x), right one still
  mirrored: not a swap.
"""
import math
import pathlib

HERE = pathlib.Path(__file__).parent
BASE = HERE / "baseline_ok"


def read(side):
    lines = (BASE / f"{side}.csv").read_text().splitlines()
    rows = [[float(x) for x in l.split(",")] for l in lines[1:]]
    return lines[0], rows


def write(case, side, header, rows, tdec=2):
    d = HERE / case
    d.mkdir(exist_ok=True)
    out = [header]
    for r in rows:
        out.append(",".join([f"{r[0]:.{tdec}f}"] + [f"{x:.3f}" for x in r[1:4]] + [f"{x:.1f}" for x in r[4:7]]))
    (d / f"{side}.csv").write_text("\n".join(out) + "\n")


def main():
    for side in ["left", "right"]:
        header, rows = read(side)
        if side == "left":
            write("gyro_scale_fault", side, header,
                  [r[:4] + [max(-2000.0, min(2000.0, 10 * g)) for g in r[4:7]] for r in rows])
            write("gyro_clipped_250", side, header,
                  [r[:4] + [max(-250.0, min(250.0, g)) for g in r[4:7]] for r in rows])
        # (their right leg is baseline_ok's, named in expected.toml rather than copied)
        # 58.8 Hz resampling (linear), stamped at 100 Hz.
        t0, t1 = rows[0][0], rows[-1][0]
        n = int((t1 - t0) * 58.8)
        res = []
        for k in range(n):
            t = t0 + k / 58.8
            i = min(int((t - t0) * 100), len(rows) - 2)
            f = (t - rows[i][0]) / (rows[i + 1][0] - rows[i][0])
            res.append([k / 100.0] + [a + f * (b - a) for a, b in zip(rows[i][1:], rows[i + 1][1:])])
        write("rate_58_8_declared_100", side, header, res)
        c, s = math.cos(math.radians(60)), math.sin(math.radians(60))
        rot = []
        for r in rows:
            ax, ay, az, gx, gy, gz = r[1:7]
            rot.append([r[0], ax, c * ay - s * az, s * ay + c * az, gx, c * gy - s * gz, s * gy + c * gz])
        write("axial_rotation_60", side, header, rot)


if __name__ == "__main__":
    main()
