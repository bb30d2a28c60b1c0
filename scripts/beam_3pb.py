#!/usr/bin/env python3
"""Notched beam in three-point bending: the initial slope of the load-displacement curve against
beam theory.

The beam (span S, depth W, thickness B, overhang 8 spacings past each support) carries a load
spread over the depth of the two node columns beside mid-span, and rests on one node column at
each support (y fixed over the depth, so the supports act on the neutral axis without clamping the
section; one node is pinned in x). A pre-crack of depth a runs up from the bottom at mid-span.
Loading the full depth keeps contact indentation out of the curve, so the compliance is:
  Timoshenko:  S^3 / (48 E I) + S / (4 k G A),   k = 5/6;
  the notch:   (2 / (E B)) int_0^a (K/P)^2 B^2 da,  K = 6 M sqrt(pi a) F(a/W) / (B W^2), M = P S / 4,
               F = 1.122 - 1.40 x + 7.33 x^2 - 13.08 x^3 + 14.0 x^4  (pure bending, Tada et al.),
from G = (P^2 / 2B) dC/da and G = K^2 / E (plane stress; in 3D the thin beam is near plane
stress too). The slope is read from the first row of history.csv (first of two load steps).

Usage: beam_3pb.py PERIADAPT OUTDIR [--dim 2|3] [--across N ...] [--formulation lps|pmb]
         [--surface-correction false|energy|moments] [--notch a/W] [--check TOL]
         [--solver relaxation|static]
--check TOL: exit 1 unless |slope_PD / slope_theory - 1| <= TOL for the last --across value (and,
with the static solver, the supports' reactions balance the load to 1e-8).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys


def notch_compliance(S, W, B, E, aW, n=4000):
    F = lambda x: 1.122 - 1.40 * x + 7.33 * x**2 - 13.08 * x**3 + 14.0 * x**4
    h = aW / n
    integral = sum((k + 0.5) * h * F((k + 0.5) * h) ** 2 for k in range(n)) * h
    return 4.5 * math.pi * S**2 / (E * B * W**2) * integral


def theory_compliance(S, W, B, E, nu, aW):
    I, A = B * W**3 / 12, B * W
    G = E / (2 * (1 + nu))
    return S**3 / (48 * E * I) + S / (4 * 5 / 6 * G * A) + notch_compliance(S, W, B, E, aW)


def deck(dim, formulation, sc, N, aW, outdir, solver, S0=0.2, W=0.025, B=0.01, E=1.0e9, P=100.0):
    nu = 0.25 if formulation == "lps" or dim == 3 else 1 / 3
    dx = W / N
    S = 2 * (round(S0 / 2 / dx) + 0.5) * dx  # supports on node columns; none at mid-span
    half = round(S / 2 / dx + 8) * dx
    q = dx / 4
    z = lambda lo, hi: (f", {lo}", f", {hi}") if dim == 3 else ("", "")
    zb = z(0.0, B)

    def box(x0, x1, y0, y1, zz=zb):
        return f"{{box: {{min: [{x0}, {y0}{zz[0]}], max: [{x1}, {y1}{zz[1]}]}}}}"

    vec = lambda *c: "[" + ", ".join(c + (("null",) if dim == 3 and len(c) == 2 else ())) + "]"
    model = "dimension: 3" if dim == 3 else f"dimension: 2, plane: stress, thickness: {B}"
    lps = ", formulation: lps" if formulation == "lps" else ""
    mat_nu = f", poisson_ratio: {nu}" if formulation == "lps" else ""
    crack = ""
    if aW > 0:
        a = aW * W
        crack = (f"cracks: [{{quad: [[0.0, 0.0, 0.0], [0.0, {a}, 0.0], [0.0, {a}, {B}], [0.0, 0.0, {B}]]}}]"
                 if dim == 3 else f"cracks: [{{segment: [[0.0, 0.0], [0.0, {a}]]}}]")
    load = [0.0, -P / (W * B)] + ([0.0] if dim == 3 else [])
    pins = (f"  - {{name: pin_x, region: {box(-S/2 - q, -S/2 + q, 0.0, dx, z(0.0, dx))}, "
            f"displacement: [0.0, null{', 0.0' if dim == 3 else ''}]}}\n")
    solver_line = ("{type: static}" if solver == "static"
                   else "{type: relaxation, load_steps: 2, tolerance: 1.0e-8}")
    text = f"""model: {{{model}{lps}}}
material: {{youngs_modulus: {E}, density: 1000.0{mat_nu}}}
discretization:
  spacing: {dx}
  surface_correction: {sc}
  body: {box(-half, half, 0.0, W)}
{crack}
loads:
  - {{name: load, type: traction, region: {box(-dx, dx, 0.0, W)}, value: {load}}}
boundary_conditions:
  - {{name: left, region: {box(-S/2 - q, -S/2 + q, 0.0, W)}, displacement: {vec("null", "0.0")}}}
  - {{name: right, region: {box(S/2 - q, S/2 + q, 0.0, W)}, displacement: {vec("null", "0.0")}}}
{pins}damage: {{enabled: false}}
solver: {solver_line}
output: {{directory: {outdir}, load_displacement: {{name: load, component: y}}}}
"""
    return text, S, nu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("periadapt")
    ap.add_argument("outdir")
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
    ap.add_argument("--across", type=int, nargs="+", default=[10, 20, 40])
    ap.add_argument("--formulation", default="lps", choices=("lps", "pmb"))
    ap.add_argument("--surface-correction", default="moments")
    ap.add_argument("--notch", type=float, default=0.2)
    ap.add_argument("--solver", default="relaxation", choices=("relaxation", "static"))
    ap.add_argument("--check", type=float)
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    W, B, E = 0.025, 0.01, 1.0e9
    print("dim formulation surface_correction nodes_across a/W slope_pd/slope_theory notch_share")
    ratio = None
    worst_imbalance = 0.0
    for N in args.across:
        name = f"{args.dim}d_{args.formulation}_{args.surface_correction}_{N}_{args.notch}"
        out = os.path.join(args.outdir, name)
        text, S, nu = deck(args.dim, args.formulation, args.surface_correction, N, args.notch, out,
                           args.solver)
        path = os.path.join(args.outdir, name + ".yaml")
        with open(path, "w") as f:
            f.write(text)
        p = subprocess.run([args.periadapt, "run", path, "--quiet"], capture_output=True, text=True)
        if p.returncode != 0:
            sys.exit(f"run failed ({path}): {p.stdout[-400:]} {p.stderr[-400:]}")
        if args.solver == "static":
            # One linear solve: the slope from summary.json, and the supports' reactions must
            # balance the load to the solver's residual.
            with open(os.path.join(out, "summary.json")) as f:
                res = json.load(f)["resultants"]
            force = -res["loads"]["load"]["force_N"][1]
            deflection = -res["loads"]["load"]["mean_displacement_m"][1]
            reactions = [sum(bc["reaction_N"][d] for bc in res["boundary_conditions"].values())
                         for d in range(args.dim)]
            imbalance = max(abs(reactions[d] + res["loads"]["load"]["force_N"][d])
                            for d in range(args.dim)) / force
            worst_imbalance = max(worst_imbalance, imbalance)
        else:
            with open(os.path.join(out, "history.csv")) as f:
                row = next(csv.DictReader(f))
            force = -float(row["load_load_fy_N"])
            deflection = -float(row["load_load_uy_m"])
        c_theory = theory_compliance(S, W, B, E, nu, args.notch)
        ratio = c_theory / (deflection / force)
        share = notch_compliance(S, W, B, E, args.notch) / c_theory
        print(f"{args.dim} {args.formulation} {args.surface_correction} {N} {args.notch} {ratio:.4f} {share:.3f}"
              + (f"  reaction imbalance {imbalance:.1e}" if args.solver == "static" else ""))
    if args.check is not None:
        ok = abs(ratio - 1) <= args.check and worst_imbalance <= 1e-8
        print(("ok" if ok else "FAIL") + f": slope ratio {ratio:.4f}, bound 1 +- {args.check}")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
