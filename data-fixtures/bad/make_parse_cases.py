#!/usr/bin/env python3
"""The tiny parse-level cases of the bad-input corpus (issue 19): each a dozen rows or fewer, so
the reader's verdict on the text itself is what is tested. Plain Python, no dependencies:
`python3 data-fixtures/bad/make_parse_cases.py`. Each case's expected.toml is written by hand.

A case whose text is fine ends in "recording is too short: 0.11 s (12 samples)": that message
proves every row was read (a BOM, CRLF line ends and a quoted header did not hide the header).
"""
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
HEADER = "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z"
ROWS = [f"{i / 100:.2f},1.000,0.010,0.020,0.5,0.6,0.7" for i in range(12)]


def body(rows, header=HEADER):
    return header + "\n" + "\n".join(rows) + "\n"


def edit(i, col, value, rows=ROWS):
    out = list(rows)
    f = out[i].split(",")
    f[col] = value
    out[i] = ",".join(f)
    return out


def case(name, data, fname="data.csv"):
    d = HERE / name
    d.mkdir(exist_ok=True)
    (d / fname).write_bytes(data if isinstance(data, bytes) else data.encode("utf-8"))


def main():
    # A NUL byte inside a number (a damaged copy): named by offset as 0x00, never echoed raw.
    case("nul_byte_in_cell", body(edit(4, 2, "0.0\x0010")))
    # Finite but beyond any sensor: it would overflow the filters and void the recording.
    case("huge_value_1e308", body(edit(4, 3, "1e308")))
    # The logger's clock restarts at 0 in the middle of the file.
    case("clock_reset_to_zero", body(edit(6, 0, "0.00")))
    case("single_row", body(ROWS[:1]))
    case("all_nan_column", body([",".join(r.split(",")[:4] + ["NaN"] + r.split(",")[5:]) for r in ROWS]))
    case("pipe_delimiter", body([r.replace(",", "|") for r in ROWS], HEADER.replace(",", "|")))
    # UTF-8 byte-order mark, Windows line ends and a quoted header: all read.
    quoted = ",".join(f'"{h}"' for h in HEADER.split(","))
    case("bom_crlf_quoted_header", ("\ufeff" + body(ROWS, quoted)).replace("\n", "\r\n"))
    case("utf16_no_bom", body(ROWS).encode("utf-16-le"))
    # A Latin-1 degree sign in a comment line (an old Windows export).
    case("latin1_comment", ("# gyro unit: \xb0/s\n" + body(ROWS)).encode("latin-1"))
    case("duplicate_column_name", body(ROWS, HEADER.replace("gyro_z", "gyro_y")))
    # A row of delimiters only (an exporter's placeholder for a lost sample).
    case("row_of_delimiters", body(ROWS[:5] + [",,,,,,"] + ROWS[6:]))
    # The same recording given as both legs, through a manifest (no copy in git).
    case("same_file_both_legs",
         "subject_id,group,affected_side,left,right\n"
         "S1,healthy,none,../baseline_ok/left.csv,../baseline_ok/left.csv\n", "manifest.csv")


if __name__ == "__main__":
    main()
