#!/usr/bin/env python3
"""Edit a model file written by `ldh train` and re-seal it with a recomputed checksum (the
bad-input corpus's model cases, issue 37): what a careful tamperer would do, so that the
plausibility rules, not the checksum, must refuse it.

    python3 edit_model.py MODEL EDIT [OUT]

EDIT is one of the names in EDITS below; OUT defaults to MODEL. `big-forest` writes a
100 MB forest (not re-sealed: it must be refused by its size before anything is parsed).

The checksum (crates/ldh-core/src/ml/model_check.rs): CRC-32 of a canonical text of every field
but the top-level `checksum`: null `n`, booleans `t`/`f`, integers `i<digits>`, floats `f` and
the 16 hex digits of their IEEE-754 bits, strings `s<utf-8 length>:<text>`, arrays
`[<length>` items `]`, objects `{<length>` then `<key length>:<key><value>` in sorted key order
`}`.
"""
import json
import struct
import sys
import zlib


def _canon(v, out, top=False):
    if v is None:
        out.append(b"n")
    elif isinstance(v, bool):
        out.append(b"t" if v else b"f")
    elif isinstance(v, int):
        out.append(b"i%d" % v)
    elif isinstance(v, float):
        out.append(b"f%016x" % struct.unpack("<Q", struct.pack("<d", v))[0])
    elif isinstance(v, str):
        b = v.encode("utf-8")
        out.append(b"s%d:" % len(b) + b)
    elif isinstance(v, list):
        out.append(b"[%d" % len(v))
        for x in v:
            _canon(x, out)
        out.append(b"]")
    else:
        keys = sorted(k for k in v if not (top and k == "checksum"))
        out.append(b"{%d" % len(keys))
        for k in keys:
            b = k.encode("utf-8")
            out.append(b"%d:" % len(b) + b)
            _canon(v[k], out)
        out.append(b"}")


def checksum(model):
    """The `crc32:xxxxxxxx` checksum of a parsed model file."""
    out = []
    _canon(model, out, top=True)
    return "crc32:%08x" % (zlib.crc32(b"".join(out)) & 0xFFFFFFFF)


def seal(model):
    model["checksum"] = checksum(model)
    return model


def _leaves(node, f):
    if "Leaf" in node:
        node["Leaf"] = f(node["Leaf"])
    else:
        _leaves(node["Split"]["left"], f)
        _leaves(node["Split"]["right"], f)


def _permute_leaves(m):
    for t in m["model"]["trees"]:
        _leaves(t, lambda c: c[-1:] + c[:-1])


def _swap(m):
    n = m["feature_names"]
    n[0], n[1] = n[1], n[0]


EDITS = {
    "scale-range-1e300": lambda m: m["scaling"]["range"].__setitem__(0, 1e300),
    "scale-range-1e-300": lambda m: m["scaling"]["range"].__setitem__(0, 1e-300),
    "mlp-weight-1e200": lambda m: m["model"]["coefs"][0]["data"].__setitem__(0, 1e200),
    "svm-gamma-1e300": lambda m: m["model"].__setitem__("gamma", 1e300),
    "swap-features": _swap,
    "permute-leaf-counts": _permute_leaves,
    "rename-feature": lambda m: m["feature_names"].__setitem__(len(m["feature_names"]) - 1, "shoe_size"),
    "none": lambda m: None,
}


def big_forest(model, out, mb=100):
    """A forest of copies of the first tree, `mb` MB of JSON."""
    tree = json.dumps(model["model"]["trees"][0])
    n = mb * 1_000_000 // (len(tree) + 1) + 1
    head = dict(model)
    head["model"] = dict(model["model"], trees=[])
    text = json.dumps(head)
    i = text.index('"trees": []') + len('"trees": [')
    with open(out, "w", encoding="utf-8") as fh:
        fh.write(text[:i])
        for k in range(n):
            fh.write(("," if k else "") + tree)
        fh.write(text[i:])


def main(argv):
    path, edit = argv[1], argv[2]
    out = argv[3] if len(argv) > 3 else path
    with open(path, encoding="utf-8") as fh:
        model = json.load(fh)
    if edit == "big-forest":
        big_forest(model, out)
        return
    EDITS[edit](model)
    with open(out, "w", encoding="utf-8") as fh:
        json.dump(seal(model), fh)


if __name__ == "__main__":
    main(sys.argv)
