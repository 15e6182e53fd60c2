#!/usr/bin/env python3
"""Runs one firmware image on two qemu-system-arm boards (-icount shift=7, as report.py) and checks
that it passes on both and that its instruction counts per packet are the same: the Cortex-M4F
image on the Cortex-M7 board (mps2-an500) against the M4F's (mps2-an386).
Usage: same_counts.py QEMU IMAGE REFERENCE_MACHINE MACHINE"""
import subprocess
import sys

qemu, image, reference, machine = sys.argv[1:5]


def run(board):
    r = subprocess.run([qemu, '-M', board, '-nographic', '-monitor', 'none', '-serial', 'none',
                        '-semihosting-config', 'enable=on,target=native', '-icount', 'shift=7',
                        '-kernel', image], capture_output=True, text=True, timeout=280)
    out = r.stdout + r.stderr
    counts = [line for line in out.splitlines() if line.startswith('instructions: ')]
    ok = r.returncode == 0 and 'all checks passed' in out and 'FAIL' not in out and 'FAULT' not in out
    return ok, counts, out


ok, counts, out = run(machine)
print(out)
ok_ref, counts_ref, out_ref = run(reference)
if not ok_ref:
    print(out_ref)
failures = []
if not ok:
    failures.append('the image did not pass on %s' % machine)
if not ok_ref:
    failures.append('the image did not pass on %s' % reference)
if not counts:
    failures.append('no instruction counts on %s' % machine)
for a, b in zip(counts, counts_ref):
    if a != b:
        failures.append('%s: "%s", %s: "%s"' % (machine, a, reference, b))
if len(counts) != len(counts_ref):
    failures.append('%d counts on %s, %d on %s' % (len(counts), machine, len(counts_ref), reference))
for f in failures:
    print('MISMATCH ' + f)
print('%s: %d instruction counts %s those on %s' % (
    machine, len(counts), 'equal to' if not failures else 'NOT equal to', reference))
print('same counts passed' if not failures else 'same counts failed')
sys.exit(1 if failures else 0)
