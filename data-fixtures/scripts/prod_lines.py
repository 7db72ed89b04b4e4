#!/usr/bin/env python3
"""Production lines of ldh-core per module (issue 48's measure): lines of `crates/ldh-core/src`
that are not blank, not comments (`//`, `///`, `//!`) and not tests (files `tests*.rs`,
`*_tests.rs`, `test_*.rs`, `proptests.rs`, anything under a `tests/` folder, and a file's trailing
`#[cfg(test)] mod x { … }`).

Usage: python3 data-fixtures/scripts/prod_lines.py [module …]   (default: every module, and the total)
"""
import pathlib
import re
import sys

SRC = pathlib.Path("crates/ldh-core/src")


def is_test(rel: pathlib.Path) -> bool:
    s = rel.stem
    return (s.startswith("tests") or s.endswith("_tests") or s.startswith("test_")
            or s == "proptests" or "tests" in rel.parts[:-1])


def count(f: pathlib.Path) -> int:
    lines = f.read_text(encoding="utf-8").splitlines()
    n = 0
    for i, line in enumerate(lines):
        s = line.strip()
        if s == "#[cfg(test)]" and i + 1 < len(lines) and re.match(r"\s*(pub(\(crate\))? )?mod \w+ \{", lines[i + 1]):
            break
        if s and not s.startswith("//"):
            n += 1
    return n


def main(modules):
    per = {}
    for f in SRC.rglob("*.rs"):
        rel = f.relative_to(SRC)
        if not is_test(rel):
            per.setdefault(rel.with_suffix("").parts[0], 0)
            per[rel.with_suffix("").parts[0]] += count(f)
    for m in modules or sorted(per):
        print(f"{per.get(m, 0):6d}  {m}")
    if not modules:
        print(f"{sum(per.values()):6d}  total")


if __name__ == "__main__":
    main(sys.argv[1:])
