#!/usr/bin/env python3
"""make test-readme: runs every shell command block of README.md and docs/*.md as a new user
would, and fails on a non-zero exit or an error printed; then checks the generated tables
(docs/performance.md's figures, docs/parameters.md's parameters and the launch arguments).

Every fenced ```sh or ```bash block is a test case named FILE:LINE. Each command in it
(continuation lines joined) runs in a fresh login shell (`env -i`, `bash -l`) that first runs
the README's workspace set-up block (the one that sources .ws/devel/setup.bash), from the
checkout. A command still running after --timeout-s (a launch file, `make demo`) has started
and passes unless it printed an error; it is then stopped with SIGINT, as Ctrl-C would.

The visible line just above a block may say:
  _Not run by `make test-readme`: REASON._   the block is skipped (and the reason shown)
  _With the demo running ..._                 the block runs while demo.launch runs (started
                                              here in the background, without rviz)
Files the README's commands name (/tmp/head.bag, /tmp/rle_vision_frames/...) are made first
by scripts/readme_fixtures.py.

  readme_check.py [FILE.md ...] [--junit OUT.xml] [--timeout-s 30] [--only FILE:LINE]
"""
import argparse
import glob
import os
import re
import signal
import subprocess
import sys
import time
import xml.sax.saxutils

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SKIP = re.compile(r'^_Not run by `make test-readme`: (.+?)\.?_$')
WITH_DEMO = re.compile(r'^_With the demo running\b')
# What a failing command prints (case matters: "error" is in many file names).
ERROR = re.compile(r'\bERROR\b|\bError:|Traceback \(most recent call last\)|command not found|No such file or directory|'
                   r'ModuleNotFoundError|RLException|process has died|does not appear to be published|'
                   r'Unable to load|cannot launch node|\bFAILED\b')
# Passed into the fresh shells: the build's settings (a different RLE_VISION_WERROR would
# reconfigure and rebuild everything) and where ROS writes its logs.
KEEP_ENV = ('HOME', 'TERM', 'CI', 'JOBS', 'RLE_VISION_WERROR', 'ROS_HOME')


class Block:
    def __init__(self, line, commands, skip_reason, with_demo):
        self.line, self.commands, self.skip_reason, self.with_demo = line, commands, skip_reason, with_demo


def read_blocks(path):
    lines = open(path).read().split('\n')
    blocks, i = [], 0
    while i < len(lines):
        fence = re.match(r'^```(sh|bash)\s*$', lines[i])
        if not fence:
            i += 1
            continue
        start = i
        above = next((lines[j].strip() for j in range(start - 1, -1, -1) if lines[j].strip()), '')
        body = []
        i += 1
        while i < len(lines) and not lines[i].startswith('```'):
            body.append(lines[i])
            i += 1
        commands, pending = [], ''
        for text in body:
            pending += text
            if pending.endswith('\\'):
                pending = pending[:-1] + ' '
                continue
            if pending.strip() and not pending.strip().startswith('#'):
                commands.append(pending.strip())
            pending = ''
        skip = SKIP.match(above)
        blocks.append(Block(start + 1, commands, skip.group(1) if skip else None, bool(WITH_DEMO.match(above))))
        i += 1
    return blocks


def shell_env():
    env = {k: os.environ[k] for k in KEEP_ENV if k in os.environ}
    env['PATH'] = '/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin'
    return env


def login_shell(script):
    """argv of a fresh login shell (only KEEP_ENV passed in) running `script` from the checkout."""
    return ['env', '-i'] + ['%s=%s' % kv for kv in shell_env().items()] + ['bash', '-l', '-c', 'cd %s\n%s' % (ROOT, script)]


def run(command, prelude, timeout_s):
    """(passed, how, output) of one command in a fresh login shell."""
    proc = subprocess.Popen(login_shell('%s\n%s\n' % ('\n'.join(prelude), command)), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, start_new_session=True, text=True, errors='replace')
    try:
        output, _ = proc.communicate(timeout=timeout_s)
        how = 'exit %d' % proc.returncode
        ok = proc.returncode == 0
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGINT)
        try:
            output, _ = proc.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            output, _ = proc.communicate()
        how = 'still running after %d s (stopped with Ctrl-C)' % timeout_s
        ok = True
    errors = [line for line in output.splitlines() if ERROR.search(line)]
    if errors:
        ok = False
        how += '; printed: ' + ' | '.join(errors[:3])
    return ok, how, output


class Demo:
    """demo.launch in the background for the blocks that need a running pipeline."""

    def __init__(self, prelude):
        script = '%s\nexec roslaunch --no-summary rle_vision demo.launch rviz:=false realtime_priority:=0\n' % (
            '\n'.join(prelude))
        self.log = open(os.path.join(os.environ.get('ROS_HOME', '/tmp'), 'readme_check_demo.log'), 'w')
        self.proc = subprocess.Popen(login_shell(script), stdout=self.log, stderr=subprocess.STDOUT,
                                     start_new_session=True)
        # Until the master is up rostopic fails at once: ask again, for up to 3 minutes (a slow
        # machine's start-up), returning as soon as blobs come.
        wait = ('%s\nend=$((SECONDS + 180)); while ((SECONDS < end)); do timeout 10 rostopic echo -n 1 /camera/blobs/header '
                '> /dev/null 2>&1 && exit 0; sleep 2; done; exit 1\n' % '\n'.join(prelude))
        ok = subprocess.call(login_shell(wait), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) == 0
        if not ok:
            print('[readme] the demo gave no blobs within 180 s (log: %s)' % self.log.name)

    def stop(self):
        os.killpg(self.proc.pid, signal.SIGINT)
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(self.proc.pid, signal.SIGKILL)
        self.log.close()


def check_block(block, prelude, timeout_s, readme_name):
    failures = []
    for command in block.commands:
        start = time.time()
        # `make` first checks the Debian packages and the build: give the command itself time too.
        ok, how, output = run(command, prelude, timeout_s * 2 if command.startswith('make ') else timeout_s)
        print('[readme] %s:%d %s  %s: %s (%.0f s)' % (readme_name, block.line, 'ok' if ok else 'FAILED', command, how,
                                                    time.time() - start), flush=True)
        if not ok:
            print('\n'.join('    ' + line for line in output.splitlines()[-25:]), flush=True)
            failures.append('%s: %s' % (command, how))
    return failures


def write_junit(path, results):
    cases = []
    for name, failures, skipped in results:
        if skipped:
            continue  # printed with its reason, not counted as passed
        inner = ''
        if failures:
            # Terminal colour codes (ESC) and other control characters are not allowed in XML.
            text = re.sub(r'[\x00-\x08\x0b\x0c\x0e-\x1f]', '', '\n'.join(failures))
            inner = '<failure message=%s/>' % xml.sax.saxutils.quoteattr(text)
        cases.append('<testcase classname="readme" name=%s>%s</testcase>' % (xml.sax.saxutils.quoteattr(name), inner))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="readme" tests="%d" failures="%d">%s</testsuite>\n'
                % (len(cases), sum(1 for _, fl, sk in results if fl and not sk), ''.join(cases)))


SELF_TEST = """# a README with one broken command

```sh
export PATH=/usr/bin:$PATH
source .ws/devel/setup.bash
```

```sh
.ws/devel/lib/rle_vision/rle_vision_detect --print-params > /dev/null
```

```sh
.ws/devel/lib/rle_vision/rle_vision_detect --print-parms
```
"""


def self_test():
    """The check itself: a misspelt option fails, named by its block's line; the rest passes."""
    import tempfile
    with tempfile.NamedTemporaryFile('w', suffix='.md', delete=False) as f:
        f.write(SELF_TEST)
    blocks = read_blocks(f.name)
    prelude = blocks[0].commands
    results = [(b.line, check_block(b, prelude, 30, 'self-test.md')) for b in blocks]
    os.unlink(f.name)
    expected = [(3, False), (8, False), (12, True)]
    got = [(line, bool(failures)) for line, failures in results]
    return [] if got == expected else ['the check itself: blocks (line, failed) %s, expected %s' % (got, expected)]


def documents(paths):
    """(name, blocks) of README.md and every docs/*.md, or of the files given."""
    if not paths:
        paths = [os.path.join(ROOT, 'README.md')] + sorted(glob.glob(os.path.join(ROOT, 'docs', '*.md')))
    return [(os.path.relpath(os.path.abspath(p), ROOT), read_blocks(p)) for p in paths]


def generated_tables():
    """The figure tables (docs/performance.md) and the parameter tables (docs/parameters.md,
    and the launch files' arguments) against what writes them."""
    results = []
    for script, name in (('readme_figures.py', 'docs/performance.md: tables of measured figures'),
                         ('param_docs.py', 'docs/parameters.md: parameter tables and launch arguments')):
        run = subprocess.run([sys.executable, os.path.join(ROOT, 'scripts', script), '--check'], capture_output=True,
                             text=True)
        print(run.stdout, end='')
        results.append((name, [] if run.returncode == 0 else [run.stdout.strip() or run.stderr.strip()], None))
    return results


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('docs', nargs='*', help='Markdown files (default: README.md and docs/*.md)')
    parser.add_argument('--junit')
    parser.add_argument('--timeout-s', type=float, default=30)
    parser.add_argument('--only', help='run only the block that starts at FILE:LINE')
    args = parser.parse_args()
    docs = documents(args.docs)
    setup = [b for _, blocks in docs for b in blocks if any('.ws/devel/setup.bash' in c for c in b.commands)]
    if not setup:
        print('[readme] no block sources .ws/devel/setup.bash')
        return 1
    prelude = setup[0].commands
    fixtures = subprocess.call(login_shell('%s\npython3 scripts/readme_fixtures.py' % '\n'.join(prelude)))
    if fixtures != 0:
        print('[readme] making the files the docs name failed')
        return 1
    named = [('%s:%d' % (name, b.line), name, b) for name, blocks in docs for b in blocks]
    if args.only:
        named = [n for n in named if n[0] == args.only]
    results = [('readme check: a broken command fails with its line', self_test(), None)]
    # The demo's blocks first: the others start their own roscore and pipeline (make demo,
    # play.launch), which a running demo would clash with.
    demo_blocks = [n for n in named if n[2].with_demo and not n[2].skip_reason]
    if demo_blocks:
        demo = Demo(prelude)
        try:
            for label, name, block in demo_blocks:
                results.append((label, check_block(block, prelude, args.timeout_s, name), None))
        finally:
            demo.stop()
    for label, name, block in named:
        if block.with_demo and not block.skip_reason:
            continue
        if block.skip_reason:
            print('[readme] %s skipped: %s' % (label, block.skip_reason))
            results.append((label, [], block.skip_reason))
            continue
        results.append((label, check_block(block, prelude, args.timeout_s, name), None))
    if not args.only:
        results += generated_tables()
    if args.junit:
        write_junit(args.junit, results)
    failed = [n for n, f, s in results if f and not s]
    print('[readme] %d blocks passed, %d failed, %d skipped%s' % (
        sum(1 for _, f, s in results if not f and not s), len(failed), sum(1 for _, _, s in results if s),
        (': ' + ', '.join(failed)) if failed else ''))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
