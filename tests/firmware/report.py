#!/usr/bin/env python3
"""Size and stack report of the core on a bare-metal target, with the budgets of issue #6.

Sizes: arm-none-eabi-size of each core object (every function it has), and what the firmware
image's linker map says each object contributes after --gc-sections (what a product linking the
same functions pays). Stack: the worst path from each entry point through the call graph that GCC
writes with -fcallgraph-info=su (each function's own frame, from -fstack-usage, summed along the
deepest chain of calls). Budgets: every decoder with CRC and HMAC (with the C library and
libgcc routines they pull in) within 48 KiB of flash; at most 1 KiB of stack per call. With
--minimal-map, the same image built with the smallest configuration (HESAI_CRC_SLICING 1,
HESAI_SIGNATURE 0) gets a column too, and must link no crypto/ member (the decoder without
signature support needs no SHA-256/HMAC). Prints a Markdown report, writes it to --out, and exits 1
when a budget is exceeded.
"""
import argparse
import glob
import os
import re
import subprocess
import sys

FLASH_BUDGET = 48 * 1024
STACK_BUDGET = 1024

# Components of the core: (label, folder of core/src, archive members = source files). Every
# object the build produces must belong to exactly one row, in its own folder (checked below), so a
# new source file cannot drop out of the report.
COMPONENTS = [
    ('sensors/: identify, validate, decode (every sensor)', 'sensors',
     ['decoder', 'pandar40', 'pandar64', 'qt128', 'qt64', 'xt', 'tables', 'columns_x86', 'columns_neon']),
    ('base/: error names', 'base', ['error']),
    ('crc/: CRC-32/MPEG-2', 'crc', ['crc32', 'crc32_arm', 'crc32_x86']),
    ('crypto/: SHA-256 + HMAC-SHA256', 'crypto', ['sha256', 'hmac', 'ct']),
    ('crypto/: HKDF', 'crypto', ['hkdf']),
    ('calibration/: calibration files', 'calibration', ['decimal', 'csv_rows', 'angles_csv', 'firetimes_csv', 'channel_config_csv']),
    ('sensors/: GPS packets', 'sensors', ['gps']),
    ('streams/: frames, rotation, sequence, safety monitor, stats', 'streams',
     ['frame', 'rotation', 'sequence', 'safety', 'stats']),
    ('capi/: the C interface (hesai.h)', 'capi', ['hesai_c']),
]
IN_BUDGET = {'sensors/: identify, validate, decode (every sensor)', 'base/: error names', 'crc/: CRC-32/MPEG-2',
             'crypto/: SHA-256 + HMAC-SHA256'}


def check_components(folders):
    """Every object in its row's folder, and in exactly one row; returns the problems."""
    problems = []
    rows = {}
    for label, folder, members in COMPONENTS:
        for m in members:
            rows.setdefault(m, []).append(label)
            if m in folders and folders[m] != folder:
                problems.append('%s is in %s/, its row says %s/' % (m, folders[m], folder))
    for m in folders:
        if len(rows.get(m, [])) != 1:
            problems.append('%s (%s/) belongs to %d rows of COMPONENTS' % (m, folders[m], len(rows.get(m, []))))
    return problems


def object_sizes(size_tool, objects):
    """({member: (text, data, bss)}, {member: folder}) from arm-none-eabi-size (Berkeley format)."""
    files = sorted(glob.glob(os.path.join(objects, '**', '*.obj'), recursive=True) + glob.glob(os.path.join(objects, '**', '*.o'), recursive=True))
    out = subprocess.run([size_tool] + files, check=True, capture_output=True, text=True).stdout
    sizes, folders = {}, {}
    for line in out.splitlines()[1:]:
        f = line.split()
        member = os.path.basename(f[5]).split('.')[0]
        sizes[member] = (int(f[0]), int(f[1]), int(f[2]))
        folders[member] = os.path.basename(os.path.dirname(f[5]))
    return sizes, folders


def linked_sizes(map_file):
    """{owner: [flash, ram]} from a GNU ld map; owner is a core member, 'libgcc', 'picolibc' or 'test image'."""
    sizes = {}
    in_map = False
    pending = None
    row = re.compile(r'^ (\S+)?\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+(\S.*)$')
    for line in open(map_file):
        if line.startswith('Linker script and memory map'):
            in_map = True
            continue
        if not in_map:
            continue
        if re.match(r'^ \.\S+$', line.rstrip('\n')):  # a long section name alone on its line
            pending = line.strip()
            continue
        m = row.match(line.rstrip('\n'))
        if not m:
            pending = None
            continue
        section = m.group(1) or pending
        pending = None
        if not section or not section.startswith('.') or section.startswith(('.debug', '.comment', '.ARM.attributes')):
            continue
        size, source = int(m.group(3), 16), m.group(4)
        if size == 0:
            continue
        core = re.search(r'libhesai_core\w*\.a\((\w+)\.', source)
        if core:
            owner = core.group(1)
        elif 'libgcc.a(' in source:
            owner = 'libgcc'
        elif 'libc.a(' in source:
            owner = 'picolibc'
        else:
            owner = 'test image'
        flash = 0 if section.startswith(('.bss', 'COMMON', '.stack')) else size
        ram = size if section.startswith(('.data', '.bss', 'COMMON')) else 0
        entry = sizes.setdefault(owner, [0, 0])
        entry[0] += flash
        entry[1] += ram
    return sizes


def call_graph(objects):
    """(frames, edges, names): own frame bytes per function, its callees, and demangled names."""
    frames, edges, names, dynamic = {}, {}, {}, set()
    node = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
    edge = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
    for path in glob.glob(os.path.join(objects, '**', '*.ci'), recursive=True):
        for line in open(path):
            m = node.match(line)
            if m:
                title, label = m.groups()
                parts = label.split('\\n')
                names.setdefault(title, parts[0])
                frame = re.search(r'(\d+) bytes \((\w[\w,]*)\)', label)
                if frame:
                    frames[title] = int(frame.group(1))
                    if 'dynamic' in frame.group(2) and 'bounded' not in frame.group(2):
                        dynamic.add(title)
                continue
            m = edge.match(line)
            if m:
                edges.setdefault(m.group(1), set()).add(m.group(2))
    return frames, edges, names, dynamic


def worst_stack(fn, frames, edges, memo, stack=()):
    """Deepest stack from fn: (bytes, chain, external calls, recursive)."""
    if fn in memo:
        return memo[fn]
    if fn in stack:
        return (0, [fn], set(), True)
    best = (0, [], set(), False)
    external = set()
    recursive = False
    for callee in sorted(edges.get(fn, ())):
        if callee not in frames:
            external.add(callee)
            continue
        r = worst_stack(callee, frames, edges, memo, stack + (fn,))
        external |= r[2]
        recursive |= r[3]
        if r[0] > best[0]:
            best = r
    result = (frames.get(fn, 0) + best[0], [fn] + best[1], external, recursive)
    memo[fn] = result
    return result


def short_name(demangled):
    """'hesai::Error hesai::Decoder::decode(...)' -> 'hesai::Decoder::decode'."""
    head = re.sub(r'\[with .*\]$', '', demangled).split('(')[0].strip()
    return head.split(' ')[-1] if head else demangled


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--map', required=True)
    ap.add_argument('--objects', required=True)
    ap.add_argument('--size', required=True)
    ap.add_argument('--minimal-map', help='linker map of the image built with the smallest configuration')
    ap.add_argument('--out')
    args = ap.parse_args()
    lines, over = [], []

    objs, folders = object_sizes(args.size, args.objects)
    over += check_components(folders)
    linked = linked_sizes(args.map)
    minimal = linked_sizes(args.minimal_map) if args.minimal_map else None
    flash = lambda sizes, owners: sum(sizes.get(o, [0, 0])[0] for o in owners)
    extra = ' flash, linked, smallest configuration |' if minimal else ''
    lines += ['### Size of the core (bytes)', '',
              '| component | archive members | flash, every function (text + data) | flash, linked into the test image | RAM (data + bss) |' + extra,
              '| --- | --- | ---: | ---: | ---: |' + (' ---: |' if minimal else '')]
    budget_flash = minimal_flash = 0
    for name, folder, members in COMPONENTS:
        present = [m for m in members if m in objs]
        whole = sum(objs[m][0] + objs[m][1] for m in present)
        used = flash(linked, present)
        ram = sum(objs[m][1] + objs[m][2] for m in present)
        row = '| %s | %s | %d | %d | %d |' % (name, ', '.join(present), whole, used, ram)
        if minimal:
            row += ' %d |' % flash(minimal, present)
            if folder == 'crypto' and flash(minimal, present):
                over.append('HESAI_SIGNATURE 0 image links %s' % name)
        lines.append(row)
        if name in IN_BUDGET:
            budget_flash += used
            minimal_flash += flash(minimal, present) if minimal else 0
    runtime = flash(linked, ['libgcc', 'picolibc'])
    lines.append('| libgcc + picolibc routines the image uses (soft-float double, memcpy, ...) | | | %d | |' % runtime
                 + (' %d |' % flash(minimal, ['libgcc', 'picolibc']) if minimal else ''))
    lines.append('| the test image itself (known answers, one real packet per sensor, startup) | | | %d | %d |'
                 % (linked.get('test image', [0, 0])[0], linked.get('test image', [0, 0])[1])
                 + (' %d |' % flash(minimal, ['test image']) if minimal else ''))
    budget_flash += runtime
    verdict = 'within' if budget_flash <= FLASH_BUDGET else 'OVER'
    lines += ['', 'Every decoder + CRC + SHA-256/HMAC + the libgcc/picolibc routines linked: **%d bytes (%.1f KiB), %s the 48 KiB budget**.'
              % (budget_flash, budget_flash / 1024.0, verdict)]
    if minimal:
        minimal_flash += flash(minimal, ['libgcc', 'picolibc'])
        lines.append('Smallest configuration (HESAI_CRC_SLICING 1, HESAI_SIGNATURE 0), the same components (no SHA-256/HMAC '
                     'linked): **%d bytes (%.1f KiB)**.' % (minimal_flash, minimal_flash / 1024.0))
    lines.append('')
    if budget_flash > FLASH_BUDGET:
        over.append('flash %d > %d' % (budget_flash, FLASH_BUDGET))

    frames, edges, names, dynamic = call_graph(args.objects)
    memo = {}
    rows = []
    for fn in frames:
        n = names.get(fn, fn)
        # The C++ API (hesai::) and the C interface (hesai_*, extern "C").
        if ('hesai::' not in n and not n.startswith('hesai_')) or '{anonymous}' in n or '::detail::' in n:
            continue
        total, chain, external, recursive = worst_stack(fn, frames, edges, memo)
        rows.append((total, short_name(n), chain, external, recursive or fn in dynamic))
    rows.sort(key=lambda r: (-r[0], r[1]))
    lines += ['### Worst stack use per entry point (bytes, from -fstack-usage and the call graph)', '',
              '| function | worst stack | deepest chain | library calls (not counted) |', '| --- | ---: | --- | --- |']
    seen = set()
    for total, name, chain, external, unbounded in rows:
        if name in seen:
            continue
        seen.add(name)
        chain_text = ' → '.join(short_name(names.get(c, c)).replace('hesai::', '') for c in chain[1:4])
        # Library routines only: a title with a path is a local function of the core that was
        # inlined everywhere (it has no frame of its own).
        lib = ', '.join(sorted(e for e in external if not e.startswith(('_ZN5hesai', '/'))))[:60]
        lines.append('| %s | %d%s | %s | %s |' % (name, total, ' (unbounded!)' if unbounded else '', chain_text, lib))
        if total > STACK_BUDGET or unbounded:
            over.append('stack %s %d' % (name, total))
    lines += ['', 'Budget: at most %d bytes of stack per call; worst: %d bytes.' % (STACK_BUDGET, rows[0][0] if rows else 0)]

    text = '\n'.join(lines) + '\n'
    print(text)
    if args.out:
        with open(args.out, 'w') as f:
            f.write(text)
    if over:
        print('BUDGET EXCEEDED: ' + '; '.join(over))
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
