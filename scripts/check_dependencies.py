#!/usr/bin/env python3
"""Checks that package.xml declares what the set-up installs (issue 31): every Debian package
of scripts/install_deps.sh has a line in scripts/dependencies.tsv, and every package.xml key
named there is declared under a tag that covers its use. --tools prints the Ubuntu names of the
"tool" lines (what the Noetic set-up installs by name). Exit status 1 on a problem."""
import os
import re
import sys
import xml.etree.ElementTree as ElementTree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COVERS = {'depend': {'depend', 'build_depend', 'exec_depend', 'build_export_depend'},
          'build_depend': {'build_depend'}, 'exec_depend': {'exec_depend'}, 'test_depend': {'test_depend'},
          'buildtool_depend': {'buildtool_depend'}, 'build_export_depend': {'build_export_depend'}}


def debian_packages():
    text = open(os.path.join(ROOT, 'scripts', 'install_deps.sh')).read()
    block = re.search(r'^debian_packages=\(\n(.*?)^\)', text, re.S | re.M)
    if not block:
        raise SystemExit('scripts/install_deps.sh: no debian_packages=( ... ) list')
    return [p for line in block.group(1).splitlines() for p in line.split('#')[0].split()]


def mapping():
    rows = {}
    for number, line in enumerate(open(os.path.join(ROOT, 'scripts', 'dependencies.tsv')), 1):
        if not line.strip() or line.startswith('#'):
            continue
        fields = line.rstrip('\n').split('\t')
        if len(fields) != 3 or len(fields[1].split()) != 2:
            raise SystemExit('scripts/dependencies.tsv:%d: expected "package<TAB>key tag<TAB>why"' % number)
        rows[fields[0]] = fields[1].split()
    return rows


def declared():
    tags = {}
    for element in ElementTree.parse(os.path.join(ROOT, 'package.xml')).getroot():
        if element.tag.endswith('depend'):
            tags.setdefault(element.text.strip(), set()).add(element.tag)
    return tags


def main():
    rows = mapping()
    if '--tools' in sys.argv:
        print(' '.join(sorted({name for key, name in rows.values() if key == 'tool'})))
        return 0
    problems = []
    tags = declared()
    for package in debian_packages():
        if package not in rows:
            problems.append('%s (installed by scripts/install_deps.sh) has no line in scripts/dependencies.tsv' % package)
            continue
        key, tag = rows[package]
        if key == 'tool':
            continue
        if tag not in COVERS:
            problems.append('scripts/dependencies.tsv: %s: unknown tag %s' % (package, tag))
        elif not tags.get(key, set()) & ({tag} | {t for t, covered in COVERS.items() if tag in covered}):
            problems.append('package.xml does not declare %s as <%s> (or a tag covering it), which %s needs'
                            % (key, tag, package))
    for problem in problems:
        print('[dependencies] ' + problem)
    print('[dependencies] %d Debian packages, %d problems' % (len(debian_packages()), len(problems)))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
