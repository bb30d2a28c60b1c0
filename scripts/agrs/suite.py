#!/usr/bin/env python3
"""AGRS on problems the seeds do not have: each deck of bench/agrs/ runs on its uniform coarse
grid, its uniform fine grid (half the spacing) and adaptively with the default triggers
(`adapt: {max_level: 1}`), and the adaptive and coarse runs are compared with the fine one.

Per run: crack path (Hausdorff distance between the node sets with damage > 0.35, in fine
spacings), damage-sum ratio, initiation time (first bond broken after the pre-cracks), final
active nodes and wall time as ratios to the fine run (smallest of --repeat alternating runs).

usage: suite.py BUILD/periadapt OUT_DIR [--only a,b] [--repeat N] [--threads N] [--table FILE]
                [--check] [--no-wall] [--decks DIR] [--adapt KEY=VALUE ...] [--moving-patches]
--check: exit 1 unless every adaptive run meets the acceptance bounds below.
--decks: the decks to run (default bench/agrs; e.g. a copy with another option set).
--no-wall: leave the wall-time bound out of --check (CI: speed is measured by benchmarks, on a
           quiet machine, not asserted by tests).
--adapt: sets a key of the adaptive runs' adapt section (repeatable), e.g. relax_sweeps=5.
--moving-patches: the adaptive runs also refine every boundary-condition region given by an
           expression of t from the start: an initial_refinement zone each, with the
           automatic profile restated (a zone switches the profile off). The profile's own
           refine_motions does this for every moving region since 2026-12-07.
"""
import argparse
import bisect
import csv
import json
import math
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtu import read_vtu, last_snapshot  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DECKS = os.path.join(ROOT, 'bench', 'agrs')
CRACKED = 0.35
# Acceptance of the adaptive run against the uniform fine one.
BOUNDS = {'path': 3.0, 'damage': 0.15, 'init': 0.05, 'nodes': 0.5, 'wall': 0.6}


# The automatic profile's keys (docs/deck-reference.md, `adapt`), restated where a deck adds an
# initial zone.
PROFILE = ('stretch_trigger: 0.5, damage_trigger: true, interface_horizon: true, refine_loads: true, '
           'refine_crack_tips: true, refine_motions: true')


def with_moving_patches(text):
    """The adaptive deck with an initial level-1 zone over each moving boundary condition."""
    import yaml  # only this option needs it
    deck = yaml.safe_load(text)
    zones = []
    for bc in deck.get('boundary_conditions') or []:
        values = bc.get('velocity') or bc.get('displacement') or []
        if any(isinstance(v, str) and re.search(r'\bt\b', v) for v in values):
            zones.append({'region': bc['region'], 'level': 1})
    if not zones:
        return text
    flow = yaml.safe_dump(zones, default_flow_style=True, width=100000).strip()
    out, n = re.subn(r'(?m)^adapt: \{max_level: 1\}$',
                     'adapt: {max_level: 1, %s, initial_refinement: %s}' % (PROFILE, flow), text)
    assert n == 1, 'the deck must end with adapt: {max_level: 1}'
    return out


def variant(text, kind, moving_patches=False):
    """The deck's text for 'coarse', 'fine' or 'adaptive'."""
    if kind == 'adaptive':
        return with_moving_patches(text) if moving_patches else text
    out = re.sub(r'(?m)^adapt:.*\n?', '', text)
    if kind == 'fine':
        def half(m):
            return '%sspacing: %.17g' % (m.group(1), float(m.group(2)) / 2)
        out, n = re.subn(r'(?m)^(\s*)spacing:\s*([0-9.eE+-]+)', half, out, count=1)
        assert n == 1, 'no spacing line'
    return out


def spacing_of(text):
    return float(re.search(r'(?m)^\s*spacing:\s*([0-9.eE+-]+)', text).group(1))


def run(exe, deck_path, out, threads, settings=()):
    cmd = [exe, 'run', deck_path, '--out', out, '--quiet']
    if threads:
        cmd += ['--threads', str(threads)]
    for kv in settings:
        cmd += ['--set', kv]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('%s failed (%d): %s' % (deck_path, r.returncode, r.stderr.strip()))
    summary = json.load(open(os.path.join(out, 'summary.json')))
    rows = list(csv.DictReader(open(os.path.join(out, 'history.csv'))))
    base = float(rows[0]['broken_bonds'])
    init = next((float(r['time_s']) for r in rows if float(r['broken_bonds']) > base), None)
    f = read_vtu(last_snapshot(out))
    cracked = [p[:3] for p, d in zip(f['Points'], f['damage']) if d > CRACKED]
    return {'init': init, 'damage': summary['damage_sum'], 'nodes': int(rows[-1]['nodes']),
            'wall': summary['wall_time_s'], 'cracked': cracked}


def directed_hausdorff(a, b):
    """max over a of the distance to the nearest point of b (b sorted by x, scanned outwards
    from p's x until the x gap alone exceeds the nearest distance found)."""
    if not a:
        return 0.0
    if not b:
        return math.inf
    b = sorted(b)
    xs = [q[0] for q in b]
    worst = 0.0
    for p in a:
        k = bisect.bisect_left(xs, p[0])
        best = math.inf
        lo, hi = k - 1, k
        while lo >= 0 or hi < len(b):
            if hi < len(b) and (lo < 0 or xs[hi] - p[0] <= p[0] - xs[lo]):
                if xs[hi] - p[0] > best:
                    break
                best = min(best, math.dist(p, b[hi]))
                hi += 1
            else:
                if p[0] - xs[lo] > best:
                    break
                best = min(best, math.dist(p, b[lo]))
                lo -= 1
        worst = max(worst, best)
    return worst


def hausdorff(a, b):
    return max(directed_hausdorff(a, b), directed_hausdorff(b, a))


def suite_arguments():
    """The arguments every suite script takes: the executable, the output folder, --only, --decks."""
    ap = argparse.ArgumentParser()
    ap.add_argument('exe')
    ap.add_argument('out')
    ap.add_argument('--only', default='')
    ap.add_argument('--decks', default=DECKS)
    return ap


def deck_names(a):
    """The decks of a.decks (without .yaml), those of --only if given."""
    names = sorted(f[:-5] for f in os.listdir(a.decks) if f.endswith('.yaml'))
    return [n for n in names if n in a.only.split(',')] if a.only else names


def main():
    ap = suite_arguments()
    ap.add_argument('--repeat', type=int, default=1)
    ap.add_argument('--threads', type=int, default=0)
    ap.add_argument('--table', default='')
    ap.add_argument('--check', action='store_true')
    ap.add_argument('--no-wall', action='store_true')
    ap.add_argument('--adapt', action='append', default=[])
    ap.add_argument('--moving-patches', action='store_true')
    a = ap.parse_args()
    adapt_settings = ['adapt.' + kv for kv in a.adapt]
    names = deck_names(a)
    os.makedirs(a.out, exist_ok=True)
    lines = ['| problem | run | nodes | path (fine dx) | damage sum | ratio | initiation (us) | '
             'error | nodes / fine | wall / fine |',
             '|---|---|---|---|---|---|---|---|---|---|']
    failures = []
    for name in names:
        text = open(os.path.join(a.decks, name + '.yaml')).read()
        h = spacing_of(text) / 2
        res = {}
        for kind in ('coarse', 'fine', 'adaptive'):
            p = os.path.join(a.out, '%s_%s.yaml' % (name, kind))
            open(p, 'w').write(variant(text, kind, a.moving_patches))
        # Fine and adaptive alternate, so a slow spell of the machine hits both.
        res['coarse'] = run(a.exe, os.path.join(a.out, name + '_coarse.yaml'),
                            os.path.join(a.out, name + '_coarse'), a.threads)
        for _ in range(a.repeat):
            for kind in ('fine', 'adaptive'):
                r = run(a.exe, os.path.join(a.out, '%s_%s.yaml' % (name, kind)),
                        os.path.join(a.out, '%s_%s' % (name, kind)), a.threads,
                        adapt_settings if kind == 'adaptive' else ())
                if kind in res:
                    r['wall'] = min(r['wall'], res[kind]['wall'])
                res[kind] = r
        fine = res['fine']
        for kind in ('coarse', 'adaptive'):
            r = res[kind]
            path = hausdorff(r['cracked'], fine['cracked']) / h
            dmg = r['damage'] / fine['damage'] if fine['damage'] > 0 else math.nan
            init_err = (r['init'] / fine['init'] - 1) if (r['init'] and fine['init']) else math.nan
            nodes = r['nodes'] / fine['nodes']
            wall = r['wall'] / fine['wall']
            lines.append('| %s | %s | %d | %.1f | %.1f | %.3f | %s | %s | %.3f | %.3f |' % (
                name, kind, r['nodes'], path, r['damage'], dmg,
                '%.2f' % (r['init'] * 1e6) if r['init'] else '-',
                '%+.1f%%' % (100 * init_err) if not math.isnan(init_err) else '-', nodes, wall))
            if kind == 'adaptive':
                bad = []
                if not path <= BOUNDS['path']:
                    bad.append('path %.1f' % path)
                if not abs(dmg - 1) <= BOUNDS['damage']:
                    bad.append('damage %.3f' % dmg)
                if not abs(init_err) <= BOUNDS['init']:
                    bad.append('initiation %+.1f%%' % (100 * init_err))
                if not nodes <= BOUNDS['nodes']:
                    bad.append('nodes %.3f' % nodes)
                if not a.no_wall and not wall <= BOUNDS['wall']:
                    bad.append('wall %.3f' % wall)
                if bad:
                    failures.append('%s: %s' % (name, ', '.join(bad)))
        lines.append('| %s | fine | %d | 0 | %.1f | 1 | %s | 0 | 1 | 1 |' % (
            name, fine['nodes'], fine['damage'],
            '%.2f' % (fine['init'] * 1e6) if fine['init'] else '-'))
        print('\n'.join(lines[-3:]), flush=True)
    table = '\n'.join(lines)
    if a.table:
        open(a.table, 'w').write(table + '\n')
    print()
    print(table)
    print()
    print('bounds (adaptive vs fine): path <= %(path)g fine spacings, damage sum within '
          '%(damage)g, initiation within %(init)g, nodes <= %(nodes)g, wall <= %(wall)g' % BOUNDS)
    for f in failures:
        print('outside the bounds: ' + f)
    print('%d of %d problems within every bound' % (len(names) - len(failures), len(names)))
    return 1 if (a.check and failures) else 0


if __name__ == '__main__':
    sys.exit(main())
