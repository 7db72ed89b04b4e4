#!/usr/bin/env python3
"""Import cycles between the source files of a crate (issue 40: "no import cycle between files").

A file A depends on file B when A's code (comments and doc links left out) names a path that
resolves to B's module: `use super::x::…`, `crate::a::b::…`, `super::super::x`, `self::x`. A
cycle is a strongly connected set of two or more files. Test files (`tests*.rs`, `*/tests/*`)
are left out: they sit beside what they test and name it, and nothing names them.

Usage: python3 data-fixtures/scripts/file_cycles.py crates/ldh-core/src [more src dirs]
       (every library: crates/ldh-core/src crates/ldh-sim/src crates/ldh-report/src)
Prints each cycle's files; exit status 1 when there is one.
"""
import pathlib
import re
import sys

PATH = re.compile(r"\b((?:crate|super|self)(?:::(?:super|[A-Za-z_][A-Za-z0-9_]*))+)")
BRACES = re.compile(r"\b((?:crate|super|self)(?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{([^{}]*)\}")


def modules(src: pathlib.Path):
    """module path (tuple) -> file, for lib.rs/main.rs, foo.rs, foo/mod.rs."""
    out = {}
    for f in src.rglob("*.rs"):
        rel = f.relative_to(src).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] in ("mod", "lib", "main"):
            parts = parts[:-1]
        out[tuple(parts)] = f
    return out


def is_test(f: pathlib.Path) -> bool:
    return f.stem.startswith("tests") or "tests" in f.parts[:-1] or f.stem.endswith("_tests")


def code_lines(text: str):
    """The code of a file without comments and without its in-file test module (a
    `#[cfg(test)]` followed by `mod name {`, by convention at the end of the file)."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        s = line.strip()
        if s == "#[cfg(test)]" and i + 1 < len(lines) and re.match(r"\s*(pub(\(crate\))? )?mod \w+ \{", lines[i + 1]):
            return
        if s.startswith("//"):
            continue
        yield line.split("//")[0]


def deps(f: pathlib.Path, me: tuple, mods: dict):
    text = "\n".join(code_lines(f.read_text(encoding="utf-8")))
    # `use a::{b, c::d}` names a::b and a::c::d.
    paths = [m.group(1) for m in PATH.finditer(text)]
    for m in BRACES.finditer(text):
        for item in m.group(2).split(","):
            item = item.strip().split(" as ")[0]
            if item and item != "self":
                paths.append(m.group(1) + "::" + item)
    # A file's own module is `me`; `super` of a `foo.rs` or `foo/mod.rs` is its parent.
    out = set()
    for p in paths:
        segs = p.split("::")
        base = []
        if segs[0] == "crate":
            base, rest = [], segs[1:]
        else:
            cur = list(me)
            rest = []
            for i, s in enumerate(segs):
                if s == "super":
                    cur = cur[:-1]
                elif s == "self":
                    pass
                else:
                    rest = segs[i:]
                    break
            base = cur
        full = base + rest
        # The longest prefix that is a file's module.
        for n in range(len(full), 0, -1):
            t = tuple(full[:n])
            if t in mods:
                if mods[t] != f:
                    out.add(mods[t])
                break
    return out


def sccs(graph):
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in list(graph):
        if v not in index:
            visit(v)
    return out


def main(dirs):
    found = 0
    for d in dirs:
        src = pathlib.Path(d)
        mods = modules(src)
        graph = {}
        for me, f in mods.items():
            if is_test(f):
                continue
            graph[f] = {g for g in deps(f, list(me), mods) if not is_test(g)}
        for comp in sccs(graph):
            found += 1
            print(f"{src}: cycle of {len(comp)} files: " + ", ".join(str(c.relative_to(src)) for c in comp))
    print(f"{found} cycle(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:] or ["crates/ldh-core/src"]))
