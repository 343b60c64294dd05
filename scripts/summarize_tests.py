#!/usr/bin/env python3
"""Counts the test cases in catkin's result files and prints, last, one line:
"N passed, M failed". Exit status 1 when anything failed or no result was found.

Every gtest and rosunit test case counts once. A rostest-*.xml wrapper only adds a failure
when its test node failed without results of its own (crash, time limit); catkin's
MISSING-*.xml files (a test binary that wrote nothing) count as failures."""
import glob
import os
import sys
import xml.etree.ElementTree as ET


def why(case):
    """The first lines of a failed case's message, so a CI log says what broke."""
    for tag in ('failure', 'error'):
        node = case.find(tag)
        if node is not None:
            text = (node.text or node.get('message') or '').strip()
            lines = [line.strip() for line in text.splitlines() if line.strip()]
            return ' | '.join(lines[-3:])[:400]
    return ''


def cases(path):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        return [('%s (unreadable result file: %s)' % (os.path.basename(path), e), False, '')]
    out = []
    for case in root.iter('testcase'):
        failed = case.find('failure') is not None or case.find('error') is not None
        name = '%s.%s' % (case.get('classname', '?'), case.get('name', '?'))
        out.append((name, not failed, why(case) if failed else ''))
    return out


def main(results_dir, extra_failures):
    passed, failed = 0, []
    files = sorted(glob.glob(os.path.join(results_dir, '**', '*.xml'), recursive=True))
    for path in files:
        base = os.path.basename(path)
        if base.startswith('rostest-'):
            for name, ok, _ in cases(path):
                test_name = name.rsplit('.', 1)[-1][len('test'):]
                own = os.path.join(os.path.dirname(path), 'rosunit-%s.xml' % test_name)
                own_failed = os.path.exists(own) and any(not ok2 for _, ok2, _ in cases(own))
                if not ok and not own_failed:
                    failed.append('%s: %s (the test node crashed, timed out or wrote no results)' % (base, name))
            continue
        for name, ok, reason in cases(path):
            if ok and not base.startswith('MISSING'):
                passed += 1
            else:
                failed.append('%s: %s%s' % (base, name, ('  (' + reason + ')') if reason else ''))
    failed += extra_failures
    if not files:
        failed.append('no test results found in %s' % results_dir)
    for line in failed:
        print('FAILED  %s' % line)
    print('%d passed, %d failed' % (passed, len(failed)))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1], ['%s' % f for f in sys.argv[2:]]))
