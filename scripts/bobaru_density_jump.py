#!/usr/bin/env python3
"""Independent check of `periadapt study bobaru-1d-density-jump` (Bobaru et al. 2009, Table III).

A 1D linear bond-based bar (E = A = rho = 1) on [0, 300], free ends, horizon 0.5, coarse cells
of 0.2 and cells of 0.2/f (f = 2, 4) on the cells of the nodes 100 ... 200. Each row i sums
c(xi) (u_j - u_i)/|xi| V_j beta_ij over the cells j that reach into [x_i - delta, x_i + delta],
beta_ij the covered fraction of j's cell (the exact 1D overlap, PeriAdapt's `subcell`
quadrature). `--reach source` looks for cells within delta + dx_i/2 of node i (i's own spacing),
`--reach all` within delta + dx_j/2 (every cell that reaches the horizon). Velocity-Verlet,
dt = 0.02, u0 = 0.02 exp(-0.01 x^2); prints the largest |u(150, t)| for t >= 200 (the reflection
from x = 200) in % of the main amplitude 0.01. Needs python3-numpy only.
Usage: scripts/bobaru_density_jump.py [--reach source|all]
"""
import argparse

import numpy as np


def reflection(factor, shape, reach, h=0.2, delta=0.5, dt=0.02, end=300.0):
    hf = h / factor
    lo, hi = 100 - h / 2, 200 + h / 2
    x = np.concatenate([np.arange(0, lo, h), lo + hf / 2 + hf * np.arange(round((hi - lo) / hf)),
                        np.arange(200 + h, 300 + 1e-9, h)])
    n = len(x)
    sp = np.where((x > lo) & (x < hi), hf, h)
    vol = np.minimum(x + sp / 2, 300.0) - np.maximum(x - sp / 2, 0.0)
    c0 = 2 / delta**2 if shape == "constant" else 6 / delta**2
    rows, cols, vals = [], [], []
    for i in range(n):
        for j in range(np.searchsorted(x, x[i] - delta - h), np.searchsorted(x, x[i] + delta + h)):
            xi = abs(x[j] - x[i])
            r = delta + 0.5 * (sp[i] if reach == "source" else sp[j])
            if j == i or xi > r * (1 + 1e-12):
                continue
            beta = min(1.0, max(0.0, (delta - (xi - 0.5 * sp[j])) / sp[j]))
            g = 1.0 if shape == "constant" else 1 - min(xi / delta, 1.0)
            if beta > 0:
                rows.append(i), cols.append(j), vals.append(c0 * g * beta * vol[j] / xi)
    rows, cols, vals = np.array(rows), np.array(cols), np.array(vals)
    diag = np.bincount(rows, vals, n)

    def acc(u):
        return np.bincount(rows, vals * u[cols], n) - diag * u

    u = 0.02 * np.exp(-0.01 * x**2)
    v = np.zeros(n)
    a = acc(u)
    k = np.searchsorted(x, 150.0)
    w = (150.0 - x[k - 1]) / (x[k] - x[k - 1])
    best, when = 0.0, 0.0
    for s in range(1, round(end / dt) + 1):
        v += 0.5 * dt * a
        u += dt * v
        a = acc(u)
        v += 0.5 * dt * a
        up = (1 - w) * u[k - 1] + w * u[k]
        if s * dt >= 200 and abs(up) > abs(best):
            best, when = up, s * dt
    return when, best


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--reach", choices=["source", "all"], default="all")
    args = p.parse_args()
    for f in (2, 4):
        for shape in ("constant", "triangular"):
            t, a = reflection(f, shape, args.reach)
            print(f"x{f} {shape:10s} T {t:7.2f}  reflected {100 * a / 0.01:+.4f} %")


if __name__ == "__main__":
    main()
