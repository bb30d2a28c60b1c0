#!/usr/bin/env python3
"""Folder-level include graph of src/: prints each folder's dependencies and any cycle.

  python3 scripts/include-graph.py [--dot FILE]

Exit 1 when the graph has a cycle (a folder reaching itself through others)."""
import os, re, sys

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")
edges = {}
why = {}
for d, _, files in os.walk(root):
    folder = os.path.relpath(d, root)
    if folder == ".":
        continue
    for f in files:
        if not f.endswith((".cpp", ".hpp")):
            continue
        for line in open(os.path.join(d, f), encoding="utf-8"):
            m = re.match(r'\s*#include\s+"([^/"]+)/', line)
            if m and m.group(1) != folder and os.path.isdir(os.path.join(root, m.group(1))):
                edges.setdefault(folder, set()).add(m.group(1))
                why.setdefault((folder, m.group(1)), f"{folder}/{f}")
        edges.setdefault(folder, set())

for k in sorted(edges):
    print(f"{k:12s} -> {', '.join(sorted(edges[k])) or '-'}")

# Cycles: strongly connected components with more than one folder (Tarjan).
index, low, stack, on, sccs = {}, {}, [], set(), []
def visit(v, counter=[0]):
    index[v] = low[v] = counter[0]; counter[0] += 1
    stack.append(v); on.add(v)
    for w in edges[v]:
        if w not in index:
            visit(w); low[v] = min(low[v], low[w])
        elif w in on:
            low[v] = min(low[v], index[w])
    if low[v] == index[v]:
        c = []
        while True:
            w = stack.pop(); on.discard(w); c.append(w)
            if w == v: break
        sccs.append(c)
for v in sorted(edges):
    if v not in index:
        visit(v)
cycles = [sorted(c) for c in sccs if len(c) > 1]
if "--dot" in sys.argv:
    with open(sys.argv[sys.argv.index("--dot") + 1], "w") as o:
        o.write("digraph src {\n" + "".join(f'  "{a}" -> "{b}";\n' for a in sorted(edges) for b in sorted(edges[a])) + "}\n")
if cycles:
    for c in cycles:
        print("cycle:", " <-> ".join(c))
        for a in c:
            for b in c:
                if b in edges[a]:
                    print(f"  {a} -> {b} (e.g. {why[(a, b)]})")
    sys.exit(1)
print("no cycles")
