#!/usr/bin/env python3
"""Fails when a C++ function in the given folders is longer than --max-lines lines (from the
line of its opening brace to its closing one): long functions mix concerns and are hard to
change. Brace matching on comment- and string-free text; a '{' at namespace or class scope whose
head holds a ')' opens a function. Writes a JUnit report with --junit (catkin run_tests)."""
import argparse
import os
import re
import sys
from xml.sax.saxutils import escape


def code_only(text):
    text = re.sub(r'//[^\n]*', '', text)
    text = re.sub(r'/\*.*?\*/', lambda m: '\n' * m.group(0).count('\n'), text, flags=re.S)
    text = re.sub(r'"(\\.|[^"\\\n])*"', '""', text)
    return re.sub(r"'(\\.|[^'\\\n])*'", "''", text)


def functions(path):
    """(first line, line count, head) of every function defined in the file."""
    text = code_only(open(path, encoding='utf-8').read())
    stack, found, last, line = [], [], 0, 1
    for i, ch in enumerate(text):
        if ch == '\n':
            line += 1
        elif ch == ';':
            last = i + 1
        elif ch == '{':
            head = ' '.join(text[last:i].split())
            kind = 'other'
            if re.search(r'\b(namespace|class|struct|enum|union)\b[^()]*$', head):
                kind = 'scope'
            elif all(k != 'function' for k, _, _ in stack) and ')' in head and \
                    not re.match(r'^(if|for|while|switch|else|do)\b', head):
                kind = 'function'
            stack.append((kind, line, head))
            last = i + 1
        elif ch == '}':
            if stack:
                kind, start, head = stack.pop()
                if kind == 'function':
                    found.append((start, line - start + 1, head))
            last = i + 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('folders', nargs='+')
    parser.add_argument('--max-lines', type=int, default=80)
    parser.add_argument('--junit', help='write a JUnit XML report here')
    args = parser.parse_args()
    too_long = []
    checked = 0
    for folder in args.folders:
        for root, _, files in os.walk(folder):
            for name in sorted(files):
                if not name.endswith(('.cpp', '.h', '.hpp')):
                    continue
                path = os.path.join(root, name)
                for start, length, head in functions(path):
                    checked += 1
                    if length > args.max_lines:
                        too_long.append('%s:%d: %d lines: %s' % (path, start, length, head[-100:]))
    for problem in too_long:
        print(problem)
    print('%d functions checked, %d over %d lines' % (checked, len(too_long), args.max_lines))
    if args.junit:
        os.makedirs(os.path.dirname(args.junit), exist_ok=True)
        failure = '<failure message="%s"/>' % escape('\n'.join(too_long), {'"': '&quot;'}) if too_long else ''
        with open(args.junit, 'w') as report:
            report.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="code_shape" tests="1" '
                         'failures="%d" errors="0"><testcase classname="code_shape" name="function_length">%s'
                         '</testcase></testsuite>\n' % (1 if too_long else 0, failure))
    return 1 if too_long else 0


if __name__ == '__main__':
    sys.exit(main())
