#!/usr/bin/env python3
"""The dependencies between dlw's top-level modules, from the `crate::` paths in src/.

    scripts/deps.py [--dot FILE] [--json]

A module is a top-level folder or file of src/ (`fit`, `stats`, ...). An edge A -> B means a
file of A names `crate::B` (in a `use` or a path; `dlw::B` in the binary's `cli`), tests
included. Prints the modules by level (a module's
level is one above the highest level it uses; the floors are level 0), the edge count, and
every pair of modules that use each other or cycle. With --dot, writes a Graphviz file of the
graph, grouped by level (docs/architecture.md shows it). Comments and doc comments do not count
(an intra-doc link is not an import); `//` inside a string literal is rare enough to ignore.
"""
import json
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")
SKIP = {"main.rs", "lib.rs"}
PATH = re.compile(r"\b(?:crate|dlw)::([a-z_][a-z0-9_]*)")
# `use crate::{a::X, b::Y}` groups: every first segment inside the braces.
GROUP = re.compile(r"\b(?:crate|dlw)::\{([^;]*?)\};", re.S)


def modules():
    out = {}
    for name in sorted(os.listdir(ROOT)):
        path = os.path.join(ROOT, name)
        if name in SKIP:
            continue
        if os.path.isdir(path):
            files = [os.path.join(d, f) for d, _, fs in os.walk(path) for f in fs if f.endswith(".rs")]
            out[name] = files
        elif name.endswith(".rs"):
            out[name[:-3]] = [path]
    return out


def strip_comments(text):
    """The code without its comments: a doc link is not an import."""
    return "\n".join(line.split("//", 1)[0] for line in text.splitlines())


def edges(mods):
    deps = {m: set() for m in mods}
    for m, files in mods.items():
        for f in files:
            text = strip_comments(open(f, encoding="utf-8").read())
            used = set(PATH.findall(text))
            for group in GROUP.findall(text):
                for item in re.split(r",(?![^{]*\})", group):
                    head = item.strip().split("::")[0].strip()
                    if head:
                        used.add(head)
            deps[m] |= {u for u in used if u in mods and u != m}
    return deps


def levels(deps):
    level = {}
    def visit(m, stack):
        if m in level:
            return level[m]
        if m in stack:
            return 0
        stack.add(m)
        lv = 1 + max((visit(d, stack) for d in deps[m]), default=-1)
        stack.discard(m)
        level[m] = lv
        return lv
    for m in deps:
        visit(m, set())
    return level


def cycles(deps):
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, on, stack, out, counter = {}, {}, set(), [], [], [0]
    def strong(v):
        index[v] = low[v] = counter[0]; counter[0] += 1
        stack.append(v); on.add(v)
        for w in sorted(deps[v]):
            if w not in index:
                strong(w); low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))
    sys.setrecursionlimit(10000)
    for v in sorted(deps):
        if v not in index:
            strong(v)
    return out


def main():
    deps = edges(modules())
    level = levels(deps)
    cyc = cycles(deps)
    n_edges = sum(len(v) for v in deps.values())
    if "--json" in sys.argv:
        print(json.dumps({"modules": {m: sorted(d) for m, d in sorted(deps.items())},
                          "levels": level, "edges": n_edges, "cycles": cyc}, indent=1))
    else:
        for lv in range(max(level.values()) + 1):
            print(f"level {lv}: {' '.join(sorted(m for m in level if level[m] == lv))}")
        print(f"{len(deps)} modules, {n_edges} dependencies, {max(level.values()) + 1} levels")
        for c in cyc:
            print("cycle: " + " <-> ".join(c))
    if "--dot" in sys.argv:
        path = sys.argv[sys.argv.index("--dot") + 1]
        with open(path, "w") as f:
            f.write("digraph dlw {\n  rankdir=BT; node [shape=box, fontname=\"sans-serif\", fontsize=11];\n")
            f.write("  edge [color=\"#00000055\", arrowsize=0.5];\n")
            for lv in range(max(level.values()) + 1):
                names = " ".join(f'"{m}"' for m in sorted(m for m in level if level[m] == lv))
                f.write(f"  {{ rank=same; {names} }}\n")
            back = {(a, b) for c in cyc for a in c for b in c if b in deps[a]}
            for a in sorted(deps):
                for b in sorted(deps[a]):
                    style = " [color=red, penwidth=2]" if (a, b) in back else ""
                    f.write(f'  "{a}" -> "{b}"{style};\n')
            f.write("}\n")


if __name__ == "__main__":
    main()
