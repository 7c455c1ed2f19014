#!/usr/bin/env python3
"""Functions in src/ longer than a limit (issue 32: no function longer than 120 lines).

    scripts/long_fns.py [--limit N] [--json] [ROOT]

A function's length is the lines from its `fn` line to its closing brace, inclusive, with
comments, string literals and character literals blanked first so that a brace inside them does
not count. Test modules (`#[cfg(test)]` blocks) count like any other code. Prints one line per
function over the limit (`path:line name lines`), longest first, and exits 1 when there is any.
"""
import json
import os
import re
import sys

LIMIT = 120
FN = re.compile(r"\bfn\s+([A-Za-z_][A-Za-z0-9_]*)")


def blank(text):
    """The source with comments, strings and char literals replaced by spaces (newlines kept)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            raw = re.match(r'b?r(#*)"', text[i:i + 260])
            if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
                end = '"' + raw.group(1)
                j = text.find(end, i + raw.end())
                j = n if j < 0 else j + len(end)
                out.append(re.sub(r"[^\n]", " ", text[i:j]))
                i = j
            elif c == '"':
                j = i + 1
                while j < n and text[j] != '"':
                    j += 2 if text[j] == "\\" else 1
                j += 1
                out.append(re.sub(r"[^\n]", " ", text[i:j]))
                i = j
            elif c == "'":
                m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:i + 12])
                if m:
                    out.append(" " * m.end())
                    i += m.end()
                else:
                    out.append(c)
                    i += 1
            else:
                out.append(c)
                i += 1
    return "".join(out)


def functions(path):
    text = blank(open(path, encoding="utf-8").read())
    for m in FN.finditer(text):
        # The body opens at the first `{` after the signature, unless a `;` comes first
        # (a declaration in a trait or an extern block).
        j = m.end()
        while j < len(text) and text[j] not in "{;":
            j += 1
        if j >= len(text) or text[j] == ";":
            continue
        depth, k = 0, j
        while k < len(text):
            if text[k] == "{":
                depth += 1
            elif text[k] == "}":
                depth -= 1
                if depth == 0:
                    break
            k += 1
        first = text.count("\n", 0, m.start()) + 1
        last = text.count("\n", 0, k) + 1
        yield m.group(1), first, last - first + 1


def main(argv):
    limit, as_json, root = LIMIT, False, None
    args = iter(argv)
    for a in args:
        if a == "--limit":
            limit = int(next(args))
        elif a == "--json":
            as_json = True
        else:
            root = a
    root = root or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")
    long = []
    for d, _, files in os.walk(root):
        for f in files:
            if f.endswith(".rs"):
                path = os.path.join(d, f)
                for name, line, lines in functions(path):
                    if lines > limit:
                        long.append({"path": os.path.relpath(path, os.path.join(root, "..")),
                                     "line": line, "name": name, "lines": lines})
    long.sort(key=lambda f: -f["lines"])
    if as_json:
        print(json.dumps({"limit": limit, "long": long}, indent=1))
    else:
        for f in long:
            print(f"{f['path']}:{f['line']} {f['name']} {f['lines']}")
        print(f"{len(long)} function(s) longer than {limit} lines")
    return 1 if long else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
