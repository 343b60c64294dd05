#!/usr/bin/env python3
"""The parameter reference (docs/parameters.md) written from the nodes' parameter tables
(include/rle_vision/params/*.def, read by cfg/param_table.py as the .cfg files read them), and
the launch files held to the same tables. A node's table sits between
`<!-- params: NODE -->` and `<!-- /params -->`.

  param_docs.py --write   rewrite the tables in docs/parameters.md
  param_docs.py --check   exit 1 when a table differs from the parameter tables, or a launch
                          argument named after a parameter has another default (it must be
                          empty, meaning the node's own, or the table's) or a doc that is not
                          the table's description (make test runs this)"""
import argparse
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, 'cfg'))
import param_table  # noqa: E402

DOC = os.path.join(ROOT, 'docs', 'parameters.md')
REGION = re.compile(r'(<!-- params: (\w+) -->\n)(.*?)(<!-- /params -->)', re.S)
# Launch files of the simulator alone, whose parameters (seed, ...) are not these nodes'.
SIMULATOR_ONLY = {'simulator.launch'}
# node -> (table, live-tunable groups, start-up setting prefixes)
NODES = {
    'Tracker': ('tracker', ['SEGMENTER', 'REGION_LIMITS', 'TRACKER'], ['TRACKER']),
    'EdgeDetector': ('landmark', ['EDGE'], ['EDGE']),
    'Landmark': ('landmark', ['OBJECTS', 'HOUGH', 'HORIZON', 'LEARNING_LOOP', 'LEARNING', 'FIELD_COLOR', 'FIELD_BOUNDARY'], ['LANDMARK']),
    'GroundProjector': ('ground', ['GROUND', 'GROUND_ATTITUDE', 'ATTITUDE_FILTER'], ['GROUND']),
    'ImageInput': ('image_input', [], ['IMAGE_INPUT']),
}


def rows(node):
    """(key, type, default, min, max, description, live) of a node's parameters."""
    table, groups, settings = NODES[node]
    out = []
    for group in groups:
        out += [entry + (True,) for entry in param_table.entries(group, table)]
    for prefix in settings:
        out += [entry + (False,) for entry in param_table.settings(prefix, table)]
    return out


def shown(value):
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, str):
        return '"%s"' % value
    return repr(value)


def type_name(cpp_type):
    return {'std::string': 'string', 'double': 'double', 'bool': 'bool'}.get(cpp_type, 'int')


def render_table(node):
    lines = ['| parameter | type | default | range | | meaning |', '|---|---|---|---|---|---|']
    for key, cpp_type, default, lo, hi, description, live in rows(node):
        limits = '' if lo is None or cpp_type == 'bool' else '%s to %s' % (shown(lo), shown(hi))
        lines.append('| `%s` | %s | `%s` | %s | %s | %s |' % (key, type_name(cpp_type), shown(default), limits,
                                                              'live' if live else 'start', description.replace('|', '\\|')))
    return '\n'.join(lines) + '\n'


def launch_problems():
    """Launch arguments named after a parameter must not repeat its default otherwise than
    exactly, and must describe it as the table does."""
    known = {}
    for node in NODES:
        for key, _t, default, _lo, _hi, description, _live in rows(node):
            known.setdefault(key, []).append((default, description))
    problems = []
    for path in sorted(glob.glob(os.path.join(ROOT, 'launch', '*.launch'))):
        if os.path.basename(path) in SIMULATOR_ONLY:
            continue
        for arg in ET.parse(path).getroot().iter('arg'):
            key = arg.get('name')
            if key not in known or arg.get('default') is None:
                continue
            where = '%s: arg %s' % (os.path.relpath(path, ROOT), key)
            given = arg.get('default')
            defaults = [shown(d).strip('"') for d, _ in known[key]]
            if given != '' and given not in defaults:
                problems.append('%s: default %r; leave it empty (the node\'s default) or give the table\'s %s'
                                % (where, given, ' or '.join(repr(d) for d in defaults)))
            if not any(description in (arg.get('doc') or '') for _, description in known[key]):
                problems.append('%s: its doc must hold the table\'s description: %r' % (where, known[key][0][1]))
    return problems


def main():
    parser = argparse.ArgumentParser()
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument('--write', action='store_true')
    mode.add_argument('--check', action='store_true')
    args = parser.parse_args()
    text = open(DOC).read()
    new = REGION.sub(lambda m: m.group(1) + render_table(m.group(2)) + m.group(4), text)
    if args.write:
        with open(DOC, 'w') as f:
            f.write(new)
        print('[params] wrote %d tables into %s' % (len(REGION.findall(new)), os.path.relpath(DOC, ROOT)))
        return 0
    stale = [m.group(2) for m, n in zip(REGION.finditer(text), REGION.finditer(new)) if m.group(3) != n.group(3)]
    missing = sorted(set(NODES) - {m.group(2) for m in REGION.finditer(text)})
    problems = ['docs/parameters.md: the %s table differs from its parameter table (scripts/param_docs.py --write)' % n
                for n in stale]
    problems += ['docs/parameters.md has no table of %s' % n for n in missing]
    problems += launch_problems()
    for problem in problems:
        print('[params] ' + problem)
    print('[params] %d node tables, %d problems' % (len(NODES), len(problems)))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
