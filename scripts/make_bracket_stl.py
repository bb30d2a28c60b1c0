#!/usr/bin/env python3
"""Writes examples/bracket.stl: an L-shaped bracket with a chamfered outer corner, extruded
along z (lengths in metres). Outline (mm): (6,0) (40,0) (40,10) (10,10) (10,30) (0,30) (0,6),
15 mm thick: area 582 mm^2, volume 8730 mm^3. Closed and outward oriented (20 triangles)."""
import sys

outline = [(6, 0), (40, 0), (40, 10), (10, 10), (10, 30), (0, 30), (0, 6)]  # counter-clockwise
thick = 15.0
reflex = 3  # (10, 10): a fan from the reflex corner covers the outline
mm = 1e-3


def facet(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    s = sum(x * x for x in n) ** 0.5
    n = [x / s for x in n]
    lines = [f"  facet normal {n[0]:.6e} {n[1]:.6e} {n[2]:.6e}", "    outer loop"]
    lines += [f"      vertex {p[0] * mm:.9e} {p[1] * mm:.9e} {p[2] * mm:.9e}" for p in (a, b, c)]
    lines += ["    endloop", "  endfacet"]
    return "\n".join(lines)


def main(path):
    k = len(outline)
    bottom = [(x, y, 0.0) for x, y in outline]
    top = [(x, y, thick) for x, y in outline]
    facets = []
    for i in range(1, k - 1):
        a, b = (reflex + i) % k, (reflex + i + 1) % k
        facets.append(facet(top[reflex], top[a], top[b]))        # normal +z
        facets.append(facet(bottom[reflex], bottom[b], bottom[a]))  # normal -z
    for i in range(k):
        j = (i + 1) % k
        facets.append(facet(bottom[i], bottom[j], top[j]))
        facets.append(facet(bottom[i], top[j], top[i]))
    with open(path, "w") as f:
        f.write("solid bracket\n" + "\n".join(facets) + "\nendsolid bracket\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "examples/bracket.stl")
