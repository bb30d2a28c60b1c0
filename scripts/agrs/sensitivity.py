#!/usr/bin/env python3
"""How far the suite's measures move when the input moves by a negligible amount.

Each deck of bench/agrs/ runs on its uniform fine grid and adaptively (the automatic profile) with
a material constant (--key, default the fracture energy) as written and scaled by (1 + eps) for
each eps of --eps. (Young's modulus alone is no test: with the default time step, which follows
the wave speed, a scaled modulus replays the same run in scaled time.) Against the
unperturbed fine run, per perturbation: crack path (Hausdorff distance between the node sets with
damage > 0.35, in fine spacings), damage-sum ratio and initiation error, for the perturbed fine
run (the measure's own reproducibility: what the fine grid itself does under the perturbation)
and for the perturbed adaptive run against the perturbed fine run (the suite's comparison, redone
on a neighbouring input). A bound below the fine grid's own spread cannot tell a good adaptive
run from a bad one.

usage: sensitivity.py BUILD/periadapt OUT_DIR [--only a,b] [--key fracture_energy]
                      [--eps 1e-6,1e-4,-1e-4] [--threads N] [--table FILE]
"""
import math
import os
import sys

import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from suite import hausdorff, run, spacing_of, suite_arguments, deck_names, variant  # noqa: E402


def compare(r, ref, h):
    path = hausdorff(r['cracked'], ref['cracked']) / h
    dmg = r['damage'] / ref['damage'] if ref['damage'] > 0 else math.nan
    init = (r['init'] / ref['init'] - 1) if (r['init'] and ref['init']) else math.nan
    return path, dmg, init


def main():
    ap = suite_arguments()
    ap.add_argument('--eps', default='1e-6,1e-4,-1e-4')
    ap.add_argument('--key', default='fracture_energy')
    ap.add_argument('--threads', type=int, default=0)
    ap.add_argument('--table', default='')
    a = ap.parse_args()
    eps_list = [float(e) for e in a.eps.split(',')]
    os.makedirs(a.out, exist_ok=True)
    lines = ['| problem | eps | fine: path (fine dx) | damage | initiation | '
             'adaptive vs fine: path | damage | initiation |',
             '|---|---|---|---|---|---|---|---|']
    for name in deck_names(a):
        text = open(os.path.join(a.decks, name + '.yaml')).read()
        h = spacing_of(text) / 2
        value = float(yaml.safe_load(text)['material'][a.key])
        res = {}
        for kind in ('fine', 'adaptive'):
            deck = os.path.join(a.out, '%s_%s.yaml' % (name, kind))
            open(deck, 'w').write(variant(text, kind))
            for e in [0.0] + eps_list:
                setting = ('material.%s=%.17g' % (a.key, value * (1 + e)),) if e else ()
                res[kind, e] = run(a.exe, deck, os.path.join(a.out, '%s_%s_%g' % (name, kind, e)),
                                   a.threads, setting)
        for e in [0.0] + eps_list:
            f = compare(res['fine', e], res['fine', 0.0], h)
            ad = compare(res['adaptive', e], res['fine', e], h)
            lines.append('| %s | %g | %.1f | %.3f | %+.1f%% | %.1f | %.3f | %+.1f%% |' % (
                name, e, f[0], f[1], 100 * f[2], ad[0], ad[1], 100 * ad[2]))
        print('\n'.join(lines[-1 - len(eps_list):]), flush=True)
    table = '\n'.join(lines)
    if a.table:
        open(a.table, 'w').write(table + '\n')
    print()
    print(table)
    return 0


if __name__ == '__main__':
    sys.exit(main())
