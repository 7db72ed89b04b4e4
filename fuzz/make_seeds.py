#!/usr/bin/env python3
"""Write the fuzz seeds (fuzz/seeds/<target>/) from data-fixtures/cohort/H01/left.csv.gz (the demo cohort).

Run from the repository root: python3 fuzz/make_seeds.py. The seeds are committed; this
script only documents how they were made. Each CSV seed is a real recording of just over 4 s
(the reader's minimum) in one format, padded with trailing newlines so that its length selects
that format for the target's second, explicit-format read (ldh_fuzz::read_csv:
format = len % 7, reader parameters = (len / 7) % 4).
"""
import math
import gzip
import os
import struct

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
G = 9.80665
# Order of ldh_fuzz::read_formats(): built-ins, then the fuzz-only formats.
FORMATS = ["ldh", "xsens-mtmanager", "shimmer-consensys", "raw-counts", "fuzz-iso", "fuzz-ms", "fuzz-us"]


def rows(n, step=1):
    with gzip.open(os.path.join(ROOT, "data-fixtures/cohort/H01/left.csv.gz"), "rt") as f:
        lines = f.read().splitlines()[1:]
    out = []
    for line in lines[: n * step : step]:
        out.append([float(x) for x in line.split(",")])
    return out


def pad(text, fmt, variant=0):
    data = text.encode()
    k = FORMATS.index(fmt)
    while not (len(data) % 7 == k and (len(data) // 7) % 4 == variant):
        data += b"\n"
    return data


def write(target, name, data):
    with open(os.path.join(ROOT, "fuzz/seeds", target, name), "wb") as f:
        f.write(data)


def csv_seeds():
    r50 = rows(212, 2)  # 50 Hz, 4.22 s
    r100 = rows(412)  # 100 Hz, 4.11 s
    t = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n"
    t += "".join(
        f"{(i * 0.02):.2f},{a:.3f},{b:.3f},{c:.3f},{d:.1f},{e:.1f},{f:.1f}\n"
        for i, (_, a, b, c, d, e, f) in enumerate(r50)
    )
    write("read_csv", "ldh.csv", pad(t, "ldh"))
    # BOM, comment lines, tab, CRLF, a gap of 0.5 s (split) and a trailing delimiter.
    t = "\ufeff# exported by fuzz seeds\r\n# subject H01\r\ntime_s\tacc_x\tacc_y\tacc_z\tgyro_x\tgyro_y\tgyro_z\r\n"
    for i, (_, a, b, c, d, e, f) in enumerate(r50):
        ts = i * 0.02 + (0.5 if i >= 206 else 0.0)
        t += f"{ts:.3f}\t{a:.3f}\t{b:.3f}\t{c:.3f}\t{d:.1f}\t{e:.1f}\t{f:.1f}\t\r\n"
    write("read_csv", "ldh-bom-tab-crlf.csv", pad(t, "ldh", 2))
    # Xsens: counter near its 16-bit wrap, m/s2, rad/s.
    t = "// General information:\n//  MT Manager version: 2022.0.0\n//  Update rate: 100.00Hz\n"
    t += "PacketCounter\tAcc_X\tAcc_Y\tAcc_Z\tGyr_X\tGyr_Y\tGyr_Z\n"
    for i, (_, a, b, c, d, e, f) in enumerate(r100):
        r = math.pi / 180
        t += f"{(65400 + i) % 65536}\t{a*G:.2f}\t{b*G:.2f}\t{c*G:.2f}\t{d*r:.3f}\t{e*r:.3f}\t{f*r:.3f}\n"
    write("read_csv", "xsens.txt", pad(t, "xsens-mtmanager"))
    # Shimmer: sep= line, units row, Unix ms, axis map (-x, +y, -z).
    names = ["Shimmer_Timestamp_Unix_CAL", "Shimmer_Accel_LN_X_CAL", "Shimmer_Accel_LN_Y_CAL",
             "Shimmer_Accel_LN_Z_CAL", "Shimmer_Gyro_X_CAL", "Shimmer_Gyro_Y_CAL", "Shimmer_Gyro_Z_CAL"]
    t = '"sep=,"\n' + ",".join(names) + "\nms,m/s^2,m/s^2,m/s^2,deg/s,deg/s,deg/s\n"
    for i, (_, a, b, c, d, e, f) in enumerate(r50):
        t += f"{1709288100000 + 20 * i:.1f},{-a*G:.2f},{b*G:.2f},{-c*G:.2f},{-d:.1f},{e:.1f},{-f:.1f}\n"
    write("read_csv", "shimmer.csv", pad(t, "shimmer-consensys"))
    # Raw counts: no time, ';', 4096 LSB/g, 32.8 LSB/(deg/s).
    t = "ax;ay;az;gx;gy;gz\n"
    for (_, a, b, c, d, e, f) in r100:
        t += f"{round(a*4096)};{round(b*4096)};{round(c*4096)};{round(d*32.8)};{round(e*32.8)};{round(f*32.8)}\n"
    write("read_csv", "raw-counts.csv", pad(t, "raw-counts"))
    # fuzz-iso: ISO 8601 time, ';', decimal comma.
    t = "time;acc_x;acc_y;acc_z;gyro_x;gyro_y;gyro_z\n"
    for i, (_, a, b, c, d, e, f) in enumerate(r50):
        values = ";".join(f"{v:.3f}" for v in (a, b, c)) + ";" + ";".join(f"{v:.1f}" for v in (d, e, f))
        t += f"2024-03-01T10:15:{2.0 + i * 0.02:06.3f};" + values.replace(".", ",") + "\n"
    write("read_csv", "fuzz-iso.csv", pad(t, "fuzz-iso"))
    # fuzz-ms: tab, units row, ms, m/s2, rad/s, axes ldh (x, y, z) = (-y, +x, +z).
    t = "t_ms\tax\tay\taz\tgx\tgy\tgz\nms\tm/s2\tm/s2\tm/s2\trad/s\trad/s\trad/s\n"
    r = math.pi / 180
    for i, (_, a, b, c, d, e, f) in enumerate(r50):
        t += f"{20 * i + 7}\t{b*G:.2f}\t{-a*G:.2f}\t{c*G:.2f}\t{e*r:.3f}\t{-d*r:.3f}\t{f*r:.3f}\n"
    write("read_csv", "fuzz-ms.tsv", pad(t, "fuzz-ms"))
    # fuzz-us: ',', us, integer counts (2048 LSB/g, 16.384 LSB/(deg/s)), jittered timestamps.
    t = "t_us,ax,ay,az,gx,gy,gz\n"
    for i, (_, a, b, c, d, e, f) in enumerate(r50):
        jitter = (37 * i) % 11 - 5
        t += f"{20000 * i + 100 * jitter},{round(a*2048)},{round(b*2048)},{round(c*2048)},{round(d*16.384)},{round(e*16.384)},{round(f*16.384)}\n"
    write("read_csv", "fuzz-us.csv", pad(t, "fuzz-us"))
    # Small malformed ones.
    write("read_csv", "header-only.csv", b"time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n")
    write("read_csv", "two-rows.csv", b"time_s;acc_x;acc_y;acc_z;gyro_x;gyro_y;gyro_z\n0;1;0;0;0;0;0\n0.01;1;0;0;NaN;0;0\n")


def pipeline_seeds():
    def case(flags, sel=0, n=3000, height=None, hand=None, base=0, offset=0, gains=(128,) * 6,
             specials=(), sat=0, noise=b"", raw=None):
        b = bytes([flags, sel])
        if sel >= 240:
            b += struct.pack("<d", 100.0)
        b += struct.pack("<H", (n - 2) % 4000)
        if flags & 0x40:
            b += bytes([height])
        if flags & 0x20:
            t0, which, delta = hand
            b += struct.pack("<d", t0) + bytes([which, delta & 0xFF])
        if flags & 0x80:
            return b + b"".join(struct.pack("<d", v) for v in raw)
        b += bytes([base]) + struct.pack("<H", offset) + bytes(gains) + bytes([len(specials)])
        for at, ch, k in specials:
            b += struct.pack("<H", at) + bytes([ch, k])
        return b + bytes([sat]) + noise

    write("pipeline", "gait-sta", case(0x01))
    write("pipeline", "gait-right-acc-zero-crossing", case(0x02 | 0x04 | 0x08, base=1, offset=500))
    write("pipeline", "gait-salarian-height", case(0x10 | 0x40, height=85, base=2, n=2500))
    write("pipeline", "gait-pitch-peaks-noise", case(0x18, base=3, noise=bytes([3, 250, 7, 1, 0, 255, 9])))
    write("pipeline", "gait-50hz-specials", case(0x00, sel=1, specials=[(100, 4, 10), (1200, 0, 9)], sat=7,
                                                  noise=bytes(range(0, 256, 17))))
    write("pipeline", "gait-hand-built-mismatch", case(0x20, hand=(12.5, 4, -3)))
    write("pipeline", "gait-any-rate", case(0x01, sel=250, n=1500))
    write("pipeline", "raw-values", case(0x80, n=600, raw=[1.0, 0.0, 0.0, 0.0, 250.0, 0.0, 0.98, 0.1, -0.05, 3.0, -120.0, 1.0]))


if __name__ == "__main__":
    csv_seeds()
    pipeline_seeds()
