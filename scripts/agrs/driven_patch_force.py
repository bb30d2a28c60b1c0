#!/usr/bin/env python3
"""How much force a driven region puts into a body on the coarse grid against the fine grid, by
the region's size: the suite's compact-tension deck with its pins (disks driven at a ramped
velocity) of several radii, each run on its uniform coarse and fine grids until before the
first break, and the upper pin's reaction compared at 1, 2, ... 7 us.

Why: `adapt.refine_motions` refines driven regions at set-up because a coarse patch can load
the body more softly than the fine grid does. The grid's share of that force sits in a layer
about one horizon wide at the region's edge, so a region much larger than a horizon needs no
refinement; the profile keeps coarse every region that holds a whole family (a node all of
whose bonds end inside it). This script measures where that line lies.

usage: driven_patch_force.py BUILD/periadapt OUT_DIR [--radii 1.5,2,3,4,6] (mm)
"""
import argparse
import bisect
import csv
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from suite import DECKS, run, variant  # noqa: E402

PIN = re.compile(r'radius: 0\.004\}\}, velocity')
TIMES_US = (1, 2, 3, 4, 5, 6, 7)


def reaction(out, column='bc_upper_pin_fy_N'):
    t, f = [], []
    for row in csv.DictReader(open(os.path.join(out, 'history.csv'))):
        t.append(float(row['time_s']))
        f.append(float(row[column]))
    return t, f


def at(series, time):
    t, f = series
    return f[min(bisect.bisect_left(t, time), len(t) - 1)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('exe')
    ap.add_argument('out')
    ap.add_argument('--radii', default='1.5,2,3,4,6')
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    text = open(os.path.join(DECKS, 'compact_tension_lps.yaml')).read()
    assert len(PIN.findall(text)) == 2, 'the deck no longer has its two 4 mm pins'
    print('pin radius (mm) | coarse / fine force at ' + ', '.join('%d' % t for t in TIMES_US) + ' us')
    for r in (float(v) for v in a.radii.split(',')):
        series = {}
        for kind in ('coarse', 'fine'):
            deck = PIN.sub('radius: %.6g}}, velocity' % (r * 1e-3), variant(text, kind))
            path = os.path.join(a.out, 'pin_%g_%s.yaml' % (r, kind))
            open(path, 'w').write(deck)
            out = os.path.join(a.out, 'pin_%g_%s' % (r, kind))
            run(a.exe, path, out, 0, ['solver.end_time=8e-6'])
            series[kind] = reaction(out)
        ratios = [at(series['coarse'], t * 1e-6) / at(series['fine'], t * 1e-6) for t in TIMES_US]
        print('%g | %s' % (r, ' '.join('%.3f' % v for v in ratios)))


if __name__ == '__main__':
    main()
