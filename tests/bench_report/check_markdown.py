#!/usr/bin/env python3
"""bench/report.py --markdown on a small hand-made run (sample.json: Pandar64 and one CRC, two
repetitions each) against the tables written by hand (expected.md), and report.py's exit codes:
0 for a run, 1 for an unreadable file, 2 for bad arguments.
Usage: python3 check_markdown.py REPORT_PY"""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
report = sys.argv[1]
sample = os.path.join(here, 'sample.json')


def run(*args):
    return subprocess.run([sys.executable, report] + list(args), capture_output=True, text=True)


failures = []
got = run('--markdown', sample)
with open(os.path.join(here, 'expected.md'), encoding='utf-8') as f:
    want = f.read()
if got.returncode != 0 or got.stdout != want:
    failures.append('--markdown: exit %d, output differs:\n%s' % (got.returncode, got.stdout))
plain = run(sample)
if plain.returncode != 0 or 'Pandar64 Points <= 1.5 x write_points' not in plain.stdout:
    failures.append('plain report: exit %d\n%s' % (plain.returncode, plain.stdout))
for args, code in (((os.path.join(here, 'missing.json'),), 1), (('--markdown', os.path.join(here, 'missing.json')), 1),
                   ((), 2), (('--markdown',), 2)):
    r = run(*args)
    if r.returncode != code:
        failures.append('report.py %s: exit %d, expected %d' % (' '.join(args), r.returncode, code))
for f in failures:
    print('FAIL', f)
print('bench_report_markdown: %s' % ('ok' if not failures else '%d failures' % len(failures)))
sys.exit(1 if failures else 0)
