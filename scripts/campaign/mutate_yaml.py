"""Shrinking the shipped studies and mutating them.

A study is shrunk to one scenario (the first value of every axis) on a 64² grid of
0.125 mm × 0.125 mm; a mutation then changes one site of its YAML tree (a value, a key, a list
entry) or one line of its text. Every mutation is named so that a report says what was done.
"""

import copy
import math
import re

import yaml

QUANTITY = re.compile(r"^\s*([-+]?[\d.]+(?:[eE][-+]?\d+)?)\s*([A-Za-zµ°][\w/^µ°]*)\s*$")
GRID = [64, 64]
SIZE = ["0.125 mm", "0.125 mm"]
NUMBERS = [
    ("zero", lambda v: 0),
    ("negative", lambda v: -v if v else -1),
    ("1e308", lambda v: 1e308),
    ("1e-300", lambda v: 1e-300),
    ("nan", lambda v: math.nan),
    ("inf", lambda v: math.inf),
    ("-inf", lambda v: -math.inf),
    ("huge_int", lambda v: 10**30),
    ("u64_max", lambda v: 2**64 - 1),
]
WRONG_UNITS = ["MPa", "deg", "um", "N", "s", "kg", "furlong", "m^2", "GPa", "1/m"]
STRINGS = [
    ("long", "x" * 300),
    ("empty", ""),
    ("path_escape", "../../../../etc/passwd"),
    ("device", "/dev/zero"),
    ("unknown_ref", "${nope}"),
    ("double_ref", "${n}${n}"),
    ("nul", "a\x00b"),
    ("spaces", "  a b  "),
]


def load(text):
    return yaml.safe_load(text)


def dump(doc):
    return yaml.safe_dump(doc, sort_keys=False, default_flow_style=None, allow_unicode=True, width=100)


def shrink(doc):
    """One scenario, a 64² grid of 0.125 mm, in place; returns doc."""
    params = doc.get("parameters") or {}
    for axis, values in (params.get("product") or {}).items():
        params["product"][axis] = first_value(axis, values)
    for group in params.get("zip") or []:
        for axis, values in group.items():
            group[axis] = first_value(axis, values)
    for spec in (doc.get("nodes") or {}).values():
        for kind, body in spec.items():
            if kind != "surface" or not isinstance(body, dict):
                continue
            for source, fields in body.items():
                if not isinstance(fields, dict) or source == "twin":
                    continue  # a twin's grid must fit its predicted correlation lengths
                if "grid" in fields and not has_ref(fields["grid"]):
                    fields["grid"] = list(GRID)
                if "size" in fields and not has_ref(fields["size"]) and source != "file":
                    fields["size"] = list(SIZE)
                fields.pop("short_wavelength_cutoff", None)
    return doc


def first_value(axis, values):
    if axis == "n":
        return [GRID[0]]
    if axis == "length":
        return [SIZE[0]]
    if isinstance(values, list):
        return values[:1]
    if isinstance(values, dict) and "range" in values:
        lo = values["range"][0]
        return {"range": [lo, lo]}
    return values


def has_ref(value):
    return "${" in str(value)


def sites(node, path=()):
    """Every (path, value) of the tree, the root excluded; a path is a tuple of keys/indices."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append((path + (k,), v))
            out += sites(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append((path + (i,), v))
            out += sites(v, path + (i,))
    return out


def get(doc, path):
    for p in path:
        doc = doc[p]
    return doc


def put(doc, path, value):
    get(doc, path[:-1])[path[-1]] = value


def value_mutations(value):
    """(name, new value) pairs for one value."""
    out = []
    if isinstance(value, bool):
        out += [("bool_as_string", "yes"), ("bool_as_int", 2), ("null", None)]
    elif isinstance(value, (int, float)):
        out += [(name, f(value)) for name, f in NUMBERS]
        out += [("number_as_string", f"{value} apples"), ("number_as_list", [value])]
    elif isinstance(value, str):
        m = QUANTITY.match(value)
        if m:
            number, unit = float(m.group(1)), m.group(2)
            for name, f in NUMBERS[:7]:
                out.append((f"quantity_{name}", f"{fmt(f(number))} {unit}"))
            out += [(f"unit_{u}", f"{m.group(1)} {u}") for u in WRONG_UNITS if u != unit]
            out += [("unit_dropped", number)]
        out += [(f"string_{name}", s) for name, s in STRINGS]
        out += [("string_as_list", [value]), ("string_as_map", {"a": value})]
    elif isinstance(value, list):
        if value:
            out += [("list_dup_entry", value + value[-1:]), ("list_drop_entry", value[:-1])]
        out += [("list_empty", []), ("list_as_scalar", 1), ("list_as_map", {"a": value})]
    elif isinstance(value, dict):
        out += [("map_empty", {}), ("map_as_scalar", 1), ("map_as_list", [value])]
    elif value is None:
        out += [("null_as_number", 1)]
    return out


def fmt(x):
    if isinstance(x, float) and math.isnan(x):
        return "NaN"
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(x)


def tree_mutations(doc):
    """Every (name, mutated doc text) of one study: values, keys, list entries."""
    out = []
    for path, value in sites(doc):
        where = "/".join(str(p) for p in path)
        for name, new in value_mutations(value):
            d = copy.deepcopy(doc)
            put(d, path, new)
            out.append((f"{where}: {name}", d))
        if isinstance(path[-1], str):
            for name, new_key in (("key_deleted", None), ("key_renamed", path[-1] + "x"),
                                  ("key_typo", typo(path[-1]))):
                d = copy.deepcopy(doc)
                parent = get(d, path[:-1])
                items = list(parent.items())
                parent.clear()
                for k, v in items:
                    if k != path[-1]:
                        parent[k] = v
                    elif new_key is not None:
                        parent[new_key] = v
                out.append((f"{where}: {name}", d))
    return [(name, dump(d)) for name, d in out]


def typo(key):
    """Two letters swapped (`sutdy`), or one dropped where the swap changes nothing (`sed`)."""
    if len(key) < 3:
        return key + key
    swapped = key[0] + key[2] + key[1] + key[3:]
    return swapped if swapped != key else key[0] + key[2:]


def line_mutations(text, rng, count):
    """Text-level mutations: a duplicated key line, a tab, a truncation, a non-UTF-8 byte."""
    lines = text.splitlines(keepends=True)
    keyed = [i for i, line in enumerate(lines) if re.match(r"^\s*[\w-]+:\s*\S", line)]
    out = []
    for _ in range(count):
        i = rng.choice(keyed)
        out.append((f"line {i + 1}: key_duplicated", "".join(lines[: i + 1] + [lines[i]] + lines[i + 1 :])))
    cut = rng.randrange(1, len(text))
    out.append((f"text: truncated at {cut}", text[:cut]))
    i = rng.choice(keyed)
    out.append((f"line {i + 1}: tab_indent", "".join(lines[:i] + ["\t" + lines[i]] + lines[i + 1 :])))
    return [(n, t.encode()) for n, t in out] + [
        ("text: invalid_utf8", text.encode()[:cut] + b"\xff\xfe" + text.encode()[cut:]),
        ("text: bom", b"\xef\xbb\xbf" + text.encode()),
        ("text: anchor_bomb", billion_laughs().encode()),
    ]


def billion_laughs():
    lines = ['a: &a ["x","x","x","x","x","x","x","x","x"]']
    for i in range(1, 9):
        prev = chr(ord("a") + i - 1)
        cur = chr(ord("a") + i)
        lines.append(f"{cur}: &{cur} [*{prev},*{prev},*{prev},*{prev},*{prev},*{prev},*{prev},*{prev},*{prev}]")
    return "study: laughs\n" + "\n".join(lines) + "\nnodes: {}\n"
