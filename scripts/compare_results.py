#!/usr/bin/env python3
"""Prints a run's figures beside the committed ones: for each NAME, bench/measured/NAME.json
(this machine, now) against bench/results/NAME.json (the figures the docs show, with their
machine and date). Numbers only; nested tables (the evaluations' methods, the latency runs)
are flattened to dotted keys. Machines differ: compare ratios within one run, not times
across runs. `make bench RECORD=1` (and eval, bench-latency) records a run instead.

  compare_results.py NAME..."""
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def flat(value, prefix=''):
    if isinstance(value, dict):
        out = {}
        for key, inner in value.items():
            out.update(flat(inner, '%s%s.' % (prefix, key) if prefix or isinstance(inner, (dict, list)) else key))
        return out
    if isinstance(value, list):
        out = {}
        for i, inner in enumerate(value):
            out.update(flat(inner, '%s%d.' % (prefix, i)))
        return out
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return {prefix.rstrip('.'): value}
    return {}


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def number(value):
    return '-' if value is None else '%.4g' % value


def compare(name):
    measured = load(os.path.join(ROOT, 'bench', 'measured', name + '.json'))
    committed = load(os.path.join(ROOT, 'bench', 'results', name + '.json'))
    if measured is None:
        print('[results] %s: nothing measured (bench/measured/%s.json)' % (name, name))
        return
    print('[results] %s: measured now (%s) | committed (%s, %s)' % (
        name, measured.get('machine', 'this machine'), (committed or {}).get('date', '-'),
        (committed or {}).get('machine', '-')))
    new, old = flat(measured), flat(committed or {})
    width = max((len(k) for k in new), default=10)
    for key in new:
        print('  %-*s %12s | %12s' % (width, key, number(new[key]), number(old.get(key))))


def main():
    for name in sys.argv[1:]:
        compare(name)
    return 0


if __name__ == '__main__':
    sys.exit(main())
