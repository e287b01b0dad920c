"""Reading and changing OpenFOAM dictionary text the way `foamDictionary -entry A/B -set V`
does: the entry is found by its slash-separated path of keywords, its value replaced in
place, and every other character (comments, layout) kept.

    set_entry(text, "subModels/pairCollisionCoeffs/pairSpringSliderDashpotCoeffs/alpha", "0.2")

Also the ascii list readers of OpenFOAM's field files (`N ( ... )`, `N{v}`, `uniform v`) that
the cross-check reads DPMFoam's output with.
"""
import re

import numpy as np

_TOKEN = re.compile(r"""
    (?P<comment>//[^\n]*|/\*.*?\*/)
  | (?P<string>"(?:[^"\\]|\\.)*")
  | (?P<open>[{(\[])
  | (?P<close>[})\]])
  | (?P<semi>;)
  | (?P<word>[^\s{}()\[\];"/]+(?:/(?![/*])[^\s{}()\[\];"/]*)*)
  | (?P<space>\s+)
  | (?P<other>.)
""", re.S | re.X)


def _tokens(text):
    for m in _TOKEN.finditer(text):
        kind = m.lastgroup
        if kind not in ("space", "comment"):
            yield kind, m.group(), m.start(), m.end()


def _find(text, keys, start=0, end=None):
    """The span of entry `keys[0]` at the top level of text[start:end]: for a dictionary
    entry the span inside its braces, for a value entry the span of the value (between the
    keyword and its `;`). Raises KeyError when there is none."""
    end = len(text) if end is None else end
    depth = 0
    expect_key = True
    tokens = list(_tokens(text[start:end]))
    i = 0
    while i < len(tokens):
        kind, value, a, b = tokens[i]
        if kind == "open":
            depth += 1
        elif kind == "close":
            depth -= 1
            expect_key = depth == 0
        elif kind == "semi":
            expect_key = depth == 0
        elif depth == 0 and expect_key and kind == "word" and value.startswith("#"):
            # A directive (`#include "file"`, `#inputMode merge`) and its one argument end
            # without a `;`: the next word is a keyword again.
            if i + 1 < len(tokens) and tokens[i + 1][0] in ("word", "string"):
                i += 1
        elif depth == 0 and expect_key and kind in ("word", "string"):
            expect_key = False
            if value.strip('"') == keys[0]:
                return _entry_span(text, tokens, i, start, keys)
        i += 1
    raise KeyError(keys[0])


def _scan(tokens, j, stop):
    """The index of the first token from `j` on where `stop(kind, depth)` holds, `depth`
    counting the brackets opened since `j` (len(tokens) when none does)."""
    depth = 0
    while j < len(tokens):
        kind = tokens[j][0]
        depth += (kind == "open") - (kind == "close")
        if stop(kind, depth):
            return j
        j += 1
    return j


def _entry_span(text, tokens, i, offset, keys):
    """The entry whose keyword is tokens[i]."""
    if i + 1 < len(tokens) and tokens[i + 1][0] == "open" and tokens[i + 1][1] == "{":
        j = _scan(tokens, i + 1, lambda kind, depth: kind == "close" and depth == 0)
        if j == len(tokens):
            raise KeyError(keys[0])
        inner = (offset + tokens[i + 1][3], offset + tokens[j][2])
        if len(keys) == 1:
            return ("dict", inner)
        return _find(text, keys[1:], *inner)
    if len(keys) > 1:
        raise KeyError("/".join(keys[1:]))
    j = _scan(tokens, i + 1, lambda kind, depth: kind == "semi" and depth == 0)
    if j == len(tokens) or j == i + 1:
        raise KeyError(keys[0])
    return ("value", (offset + tokens[i + 1][2], offset + tokens[j - 1][3]))


def get_entry(text, path):
    """The text of the value of the entry at `path` (`a/b/c`); KeyError if absent."""
    kind, (a, b) = _find(text, path.split("/"))
    return text[a:b].strip()


def set_entry(text, path, value):
    """`text` with the value of the entry at `path` replaced by `value` (a value entry), or
    the entry added at the end of its parent dictionary when it is absent. An added entry
    whose value is a dictionary, `{ … }`, is written without the `;` (as foamDictionary
    writes one). Comments and layout elsewhere are kept."""
    keys = path.split("/")
    end = "" if value.lstrip().startswith("{") else ";"
    try:
        kind, (a, b) = _find(text, keys)
    except KeyError:
        if len(keys) == 1:
            return text.rstrip("\n") + f"\n{keys[0]} {value}{end}\n"
        kind, (a, b) = _find(text, keys[:-1])
        if kind != "dict":
            raise
        head = text[:b].rstrip(" ")
        indent = text[len(head):b]  # the closing brace's indentation, kept
        return head + f"{indent}    {keys[-1]} {value}{end}\n{indent}" + text[b:]
    if kind == "dict":
        raise ValueError(f"'{path}' is a dictionary, not a value")
    return text[:a] + value + text[b:]


# ----- OpenFOAM ascii lists -----------------------------------------------------------

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def body(text):
    """The text after the FoamFile header."""
    m = re.search(r"FoamFile\s*\{.*?\}", text, re.S)
    return text[m.end():] if m else text


def read_list(text, width):
    """The values of an ascii OpenFOAM list file (`N ( v ... )` or `N{v}`) as an array of
    shape (N, width) (width 1: shape (N,)). Positions' `(x y z) celli` rows: width 3 reads
    the coordinates and skips the cell."""
    rest = re.sub(r"//[^\n]*|/\*.*?\*/", " ", body(text), flags=re.S)
    m = re.search(r"(\d+)\s*\{\s*(" + _NUMBER + r"|\([^)]*\))\s*\}", rest)
    head = re.search(r"(\d+)\s*\(", rest)
    if m and (not head or m.start() < head.start()):
        n = int(m.group(1))
        values = [float(v) for v in re.findall(_NUMBER, m.group(2))]
        return _shaped(np.tile(values, (n, 1)), width)
    if not head:
        raise ValueError("no list")
    n = int(head.group(1))
    rest = rest[head.end():]
    if width == 1:
        values = np.array(re.findall(_NUMBER, rest)[:n], dtype=float)
        rows = values.reshape(-1, 1)
    else:
        rows = np.array([[float(v) for v in re.findall(_NUMBER, g)]
                         for g in re.findall(r"\(([^()]*)\)", rest)[:n]])
        rows = rows[:, :width] if n else np.zeros((0, width))
    if len(rows) != n:
        raise ValueError(f"list of {n} entries holds {len(rows)}")
    return _shaped(rows, width)


def _shaped(rows, width):
    return rows[:, 0] if width == 1 else rows


def read_internal_field(text, cells):
    """The internalField of an ascii volume field: shape (cells,) or (cells, 3)."""
    text = body(text)
    m = re.search(r"internalField\s+uniform\s+(\([^)]*\)|" + _NUMBER + r")\s*;", text)
    if m:
        values = [float(v) for v in re.findall(_NUMBER, m.group(1))]
        return _shaped(np.tile(values, (cells, 1)), len(values))
    m = re.search(r"internalField\s+nonuniform\s+List<(\w+)>", text)
    if not m:
        raise ValueError("no internalField")
    width = 3 if m.group(1) == "vector" else 1
    end = text.index("boundaryField") if "boundaryField" in text else len(text)
    return read_list(text[m.end():end], width)
