#!/usr/bin/env python3
"""No module of ldh-core imports one above it in the layer list of docs/architecture.md
(issue 48: "a check in CI that no module imports one above it").

The list is the fenced block tagged `layers` in docs/architecture.md, bottom first: one layer
per line, the modules of a layer separated by spaces (modules of one layer may use each
other; `file_cycles.py` keeps their files free of cycles). A file's module is the first
component of its path under `crates/ldh-core/src` (`events.rs` and `events/matching.rs` are
both `events`). A file depends on a module when its code names a path into it (the rules of
`file_cycles.py`: `use`, `crate::…`, `super::…`, comments and doc links left out). Test files
are left out: `tests*.rs`, `*_tests.rs`, `*/tests/*` and any file declared under `#[cfg(test)]`.

Every upward dependency is an error unless the block tagged `layer-exceptions` lists it, one
per line: `FILE -> MODULE  # why` (FILE relative to `crates/ldh-core/src`). An exception that
no longer occurs is an error too, so the list only shrinks with the code.

Usage: python3 data-fixtures/scripts/layers.py [docs/architecture.md] [crates/ldh-core/src]
Prints each violation; exit status 1 when there is one.
"""
import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import file_cycles  # noqa: E402  (the same dependency rules)


def block(text: str, tag: str):
    """The lines of the fenced block tagged `tag`, comments (`# …`) and blanks dropped."""
    m = re.search(r"^```" + re.escape(tag) + r"\s*\n(.*?)^```", text, re.S | re.M)
    if not m:
        sys.exit(f"no ```{tag} block in the architecture document")
    out = []
    for line in m.group(1).splitlines():
        line = line.split("#")[0].strip()
        if line:
            out.append(line)
    return out


def test_children(src: pathlib.Path, mods: dict):
    """Files declared with `#[cfg(test)] mod x;` (and everything below them)."""
    tests = set()
    for parts, f in mods.items():
        lines = f.read_text(encoding="utf-8").splitlines()
        for i, line in enumerate(lines[:-1]):
            if line.strip() != "#[cfg(test)]":
                continue
            m = re.match(r"\s*(?:pub(?:\([a-z]+\))? )?mod (\w+);", lines[i + 1])
            if m:
                child = tuple(parts) + (m.group(1),)
                tests.update(g for p, g in mods.items() if p[: len(child)] == child)
    return tests


def main(doc="docs/architecture.md", src_dir="crates/ldh-core/src"):
    text = pathlib.Path(doc).read_text(encoding="utf-8")
    rank = {}
    for i, line in enumerate(block(text, "layers")):
        for module in line.split():
            if module in rank:
                sys.exit(f"{doc}: module '{module}' is in two layers")
            rank[module] = i
    allowed = {}
    for line in block(text, "layer-exceptions"):
        f, arrow, module = line.partition("->")
        if not arrow:
            sys.exit(f"{doc}: an exception is `FILE -> MODULE`, not '{line}'")
        allowed[(f.strip(), module.strip())] = False

    src = pathlib.Path(src_dir)
    mods = file_cycles.modules(src)
    tests = test_children(src, mods)
    module_of = lambda f: f.relative_to(src).with_suffix("").parts[0]  # noqa: E731
    found = 0
    for me, f in sorted(mods.items(), key=lambda kv: str(kv[1])):
        if file_cycles.is_test(f) or f in tests or f.name in ("lib.rs", "main.rs"):
            continue
        a = module_of(f)
        if a not in rank:
            print(f"{f.relative_to(src)}: module '{a}' is in no layer of {doc}")
            found += 1
            continue
        used = {
            module_of(d)
            for d in file_cycles.deps(f, list(me), mods)
            if not (file_cycles.is_test(d) or d in tests or d.name == "lib.rs")
        }
        for b in sorted(used):
            if b == a or rank.get(b, -1) <= rank[a]:
                continue
            key = (str(f.relative_to(src)), b)
            if key in allowed:
                allowed[key] = True
                continue
            print(f"{key[0]}: module '{a}' (layer {rank[a]}) uses '{b}' (layer {rank[b]}), above it")
            found += 1
    for (f, b), used in allowed.items():
        if not used:
            print(f"{doc}: exception '{f} -> {b}' no longer occurs: remove it")
            found += 1
    print(f"{found} layer violation(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
