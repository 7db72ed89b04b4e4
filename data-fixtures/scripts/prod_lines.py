#!/usr/bin/env python3
"""Production lines of Rust code per module: no tests, comments or blank lines (issue 48's measure).

A file is test code when its name is tests.rs, tests_*.rs, *_tests.rs, proptests.rs, test_*.rs or it
sits under a `tests/` folder; inside other files, an item after `#[cfg(test)]` is skipped to its
closing brace. Comments (`//`, `///`, `//!`, `/* */`) and blank lines are not counted.

Usage: python3 data-fixtures/scripts/prod_lines.py crates/ldh-core/src [more src dirs]
Prints one line per top-level module (a folder or file directly under src) and the total.
"""
import pathlib
import re
import sys

TEST_FILE = re.compile(r"^(tests?(_.*)?|.*_tests|proptests|test_.*)\.rs$")


def is_test_file(rel: pathlib.PurePath) -> bool:
    return bool(TEST_FILE.match(rel.name)) or "tests" in rel.parts[:-1]


def strip_block_comments(text: str) -> str:
    out, i, depth = [], 0, 0
    in_str = False
    while i < len(text):
        two = text[i : i + 2]
        c = text[i]
        if depth == 0 and not in_str and c == '"' and (i == 0 or text[i - 1] != "\\"):
            in_str = True
            out.append(c)
        elif in_str:
            if c == '"' and text[i - 1] != "\\":
                in_str = False
            out.append(c)
        elif two == "/*":
            depth += 1
            i += 1
        elif two == "*/" and depth:
            depth -= 1
            i += 1
        elif depth == 0:
            out.append(c)
        elif c == "\n":
            out.append(c)
        i += 1
    return "".join(out)


def count(path: pathlib.Path) -> int:
    lines = strip_block_comments(path.read_text(encoding="utf-8")).splitlines()
    n, skip_next_item, depth_at, depth = 0, False, None, 0
    for line in lines:
        s = line.strip()
        if depth_at is None and s.startswith("#[cfg(test)]"):
            skip_next_item = True
            continue
        opens, closes = s.count("{"), s.count("}")
        if skip_next_item:
            if s.endswith(";") and opens == 0:
                skip_next_item = False  # `mod tests;`
                continue
            if opens:
                depth_at = depth
                skip_next_item = False
        depth += opens - closes
        if depth_at is not None:
            if depth <= depth_at:
                depth_at = None
            continue
        if not s or s.startswith("//"):
            continue
        n += 1
    return n


def main() -> None:
    grand = 0
    for src in map(pathlib.Path, sys.argv[1:] or ["crates/ldh-core/src"]):
        per = {}
        for f in sorted(src.rglob("*.rs")):
            rel = f.relative_to(src)
            if is_test_file(rel):
                continue
            top = rel.parts[0].removesuffix(".rs")
            per[top] = per.get(top, 0) + count(f)
        total = sum(per.values())
        grand += total
        for k, v in sorted(per.items(), key=lambda kv: -kv[1]):
            print(f"{src}  {k:<14} {v:6d}")
        print(f"{src}  {'TOTAL':<14} {total:6d}")
    if len(sys.argv) > 2:
        print(f"all  {grand:6d}")


if __name__ == "__main__":
    main()
