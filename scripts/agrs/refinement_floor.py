#!/usr/bin/env python3
"""How much of each suite body an adaptive run must refine, read off the uniform fine run.

The critical stretch scales as delta^(-1/2) (thesis Eqs. 2.15, 2.21), so a coarse bond breaks at
sqrt(delta_fine / delta_coarse) = 1/sqrt(2) of the fine grid's s0. Wherever the fine run's
stretch field passes that level, a coarse node left there breaks bonds the fine grid keeps: the
adaptive run has to be fine there before it happens. The fine run writes `stretch_ratio` (each
node's largest intact breakable stretch over its s0) in many snapshots; per node its largest
value up to a time t gives the share f(t) of the body that must be fine by t, and the final
node count can fall no lower than f + (1 - f) / r of the fine grid's (r = 4 in 2D, 8 in 3D;
a refined parent has r children). Three shares per problem:
  at initiation: largest ratio up to the fine run's first broken bond;
  ever:          largest ratio up to the end (no coarsening);
  at the end:    ratio at the end, or damaged (ideal coarsening: only what is still needed).
The floor ignores the margin a zone needs around such nodes (a coarse horizon, children's
interface rows) and peaks between snapshots, so the true requirement is higher.

usage: refinement_floor.py BUILD/periadapt OUT_DIR [--only a,b] [--snapshots N] [--decks DIR]
"""
import csv
import glob
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from suite import deck_names, suite_arguments, variant  # noqa: E402
from vtu import read_vtu  # noqa: E402

LEVEL = 1.0 / math.sqrt(2.0)   # the coarse grid's s0 in units of the fine grid's


def fine_run(exe, text, out, snapshots):
    deck = re.sub(r'(?m)^(output:.*?)vtu_snapshots:\s*\d+', r'\g<1>vtu_snapshots: %d' % snapshots,
                  variant(text, 'fine'))
    assert 'vtu_snapshots: %d' % snapshots in deck, 'no output.vtu_snapshots to raise'
    path = out + '.yaml'
    open(path, 'w').write(deck)
    r = subprocess.run([exe, 'run', path, '--out', out, '--quiet'], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('%s failed (%d): %s' % (path, r.returncode, r.stderr.strip()))
    rows = list(csv.DictReader(open(os.path.join(out, 'history.csv'))))
    base = float(rows[0]['broken_bonds'])
    init = next((float(r['time_s']) for r in rows if float(r['broken_bonds']) > base), None)
    times = {}
    pvd = open(os.path.join(out, 'snapshot.pvd')).read() if os.path.exists(
        os.path.join(out, 'snapshot.pvd')) else ''
    for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd):
        times[os.path.basename(f)] = float(t)
    return init, times


def main():
    ap = suite_arguments()
    ap.add_argument('--snapshots', type=int, default=150)
    a = ap.parse_args()
    names = deck_names(a)
    os.makedirs(a.out, exist_ok=True)
    print('| problem | fine nodes | must be fine at initiation | node floor | ever | node floor '
          '| at the end | node floor |')
    print('|---|---|---|---|---|---|---|---|')
    for name in names:
        text = open(os.path.join(a.decks, name + '.yaml')).read()
        r = 8 if re.search(r'dimension:\s*3', text) else 4
        out = os.path.join(a.out, name + '_fine')
        init, times = fine_run(a.exe, text, out, a.snapshots)
        files = sorted(glob.glob(out + '/snapshot_*.vtu'))
        peak = peak_init = None
        for f in files:
            fields = read_vtu(f)
            s = fields['stretch_ratio']
            t = times.get(os.path.basename(f))
            if peak is None:
                peak = list(s)
                peak_init = list(s)
            else:
                peak = [max(p, q) for p, q in zip(peak, s)]
                if t is not None and init is not None and t <= init:
                    peak_init = [max(p, q) for p, q in zip(peak_init, s)]
        last = read_vtu(files[-1])
        n = len(peak)
        share_init = sum(p > LEVEL for p in peak_init) / n
        share_ever = sum(p > LEVEL for p in peak) / n
        share_end = sum((s > LEVEL or d > 0) for s, d in
                        zip(last['stretch_ratio'], last['damage'])) / n

        def floor(f):
            return f + (1 - f) / r
        print('| %s | %d | %.1f%% | %.3f | %.1f%% | %.3f | %.1f%% | %.3f |' % (
            name, n, 100 * share_init, floor(share_init), 100 * share_ever, floor(share_ever),
            100 * share_end, floor(share_end)), flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
