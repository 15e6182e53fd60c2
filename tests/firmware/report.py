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
signature support needs no SHA-256/HMAC). With --emulator and --image, runs the image under
qemu-system-arm -icount shift=7, where it counts the instructions of validate() and decode() per
packet of each sensor exactly (main.cpp, "Instructions per packet"), and checks them against
INSTRUCTION_BUDGETS. No double-precision soft-float routine (__aeabi_d*, __aeabi_*2d) may be reachable
from Decoder::validate or Decoder::decode (issue #13). Prints a Markdown report, writes it to --out,
and exits 1 when a budget is exceeded.
"""
import argparse
import json
import glob
import os
import re
import shlex
import subprocess
import sys

FLASH_BUDGET = 48 * 1024
STACK_BUDGET = 1024

# Instructions per packet, by core and sensor: what the image measured (GCC 12.2 -Os, the packets of
# fuzz/seed_packets.inc) plus about 25%, rounded up. Exact counts would fail on any compiler
# update or honest change; 25% still catches a double-precision routine or a library call per
# point coming back onto the path, each of which costs more than that (the per-block double sine
# and cosine that issue #13 replaced by float cost 76 000 instructions per Pandar40 packet on the
# Cortex-M4F, 63% of its decode).
INSTRUCTION_BUDGETS = {
    'cortex-m4': {
        'Pandar40': {'validate': 1000, 'decode': 21000, 'decode_columns': 18000, 'decode_rpm_change': 25000},
        'Pandar40P': {'validate': 2000, 'decode': 21000, 'decode_columns': 19000, 'decode_rpm_change': 25000},
        'Pandar64': {'validate': 1000, 'decode': 20000, 'decode_columns': 17000, 'decode_rpm_change': 27000},
        'QT128C2X': {'validate': 9000, 'decode': 22000, 'decode_columns': 19000, 'decode_rpm_change': 48000, 'signature': 97000},
        'PandarQT64': {'validate': 1000, 'decode': 14000, 'decode_columns': 12000, 'decode_rpm_change': 21000},
        'PandarXT16': {'validate': 2000, 'decode': 9000, 'decode_columns': 8000, 'decode_rpm_change': 11000},
        'PandarXT32': {'validate': 2000, 'decode': 15000, 'decode_columns': 13000, 'decode_rpm_change': 19000},
        'PandarXT32M2X': {'validate': 2000, 'decode': 12000, 'decode_columns': 10000, 'decode_rpm_change': 15000},
    },
    'cortex-m0plus': {
        'Pandar40': {'validate': 2000, 'decode': 723000, 'decode_columns': 619000, 'decode_rpm_change': 829000},
        'Pandar40P': {'validate': 3000, 'decode': 723000, 'decode_columns': 619000, 'decode_rpm_change': 830000},
        'Pandar64': {'validate': 2000, 'decode': 632000, 'decode_columns': 546000, 'decode_rpm_change': 802000},
        'QT128C2X': {'validate': 17000, 'decode': 453000, 'decode_columns': 392000, 'decode_rpm_change': 1081000, 'signature': 161000},
        'PandarQT64': {'validate': 2000, 'decode': 445000, 'decode_columns': 384000, 'decode_rpm_change': 615000},
        'PandarXT16': {'validate': 3000, 'decode': 242000, 'decode_columns': 217000, 'decode_rpm_change': 282000},
        'PandarXT32': {'validate': 3000, 'decode': 450000, 'decode_columns': 403000, 'decode_rpm_change': 528000},
        'PandarXT32M2X': {'validate': 3000, 'decode': 312000, 'decode_columns': 278000, 'decode_rpm_change': 390000},
    },
}
# Issue #32's stream health, by the same rule (measured + 25%, rounded up): the
# decode with the unit scan (Decoder::decode with a UnitScan: blockage markers, repeated returns,
# points beyond the rated range) and the monitor's work on the next packet in order
# (HealthMonitor::observe + observe_units). Checked only where a core has them.
HEALTH_BUDGETS = {
    # The Cortex-M4F's decode_scan since issue #43 (the scan folded into the assembly loops).
    'cortex-m4': {
        'Pandar40': {'decode_scan': 24000, 'health': 900},
        'Pandar40P': {'decode_scan': 24000, 'health': 800},
        'Pandar64': {'decode_scan': 22000, 'health': 800},
        'QT128C2X': {'decode_scan': 24000, 'health': 800},
        'PandarQT64': {'decode_scan': 16000, 'health': 800},
        'PandarXT16': {'decode_scan': 10000, 'health': 800},
        'PandarXT32': {'decode_scan': 16000, 'health': 800},
        'PandarXT32M2X': {'decode_scan': 13000, 'health': 800},
    },
    'cortex-m0plus': {
        'Pandar40': {'decode_scan': 745000, 'health': 2600},
        'Pandar40P': {'decode_scan': 746000, 'health': 2300},
        'Pandar64': {'decode_scan': 651000, 'health': 2200},
        'QT128C2X': {'decode_scan': 468000, 'health': 2200},
        'PandarQT64': {'decode_scan': 459000, 'health': 2300},
        'PandarXT16': {'decode_scan': 251000, 'health': 2300},
        'PandarXT32': {'decode_scan': 465000, 'health': 2300},
        'PandarXT32M2X': {'decode_scan': 322000, 'health': 2200},
    },
}
# Issue #43's frame assembly, by the same rule, on the Cortex-M4F only (the Cortex-M0+ image does
# not link the FrameAssembler: no room in its flash): `frames` is the FrameAssembler's work on one
# packet as hesai's Pipeline does it (begin_packet, block() per block, each block's points by
# FrameAssembler::points(), a stream under way, no block on the cut, the packet turned half a
# turn so that no point lies across 0 from its block), `full_path` the packet's
# whole path: decode_scan (validate included) + health + frames. `frames_per_point`, the same with
# point() for each point, is reported beside it, without a budget.
FRAMES_BUDGETS = {
    'cortex-m4': {
        'Pandar40': {'frames': 12000, 'full_path': 36000},
        'Pandar40P': {'frames': 12000, 'full_path': 36000},
        'Pandar64': {'frames': 7000, 'full_path': 30000},
        'QT128C2X': {'frames': 6000, 'full_path': 30000},
        'PandarQT64': {'frames': 6000, 'full_path': 22000},
        'PandarXT16': {'frames': 6000, 'full_path': 16000},
        'PandarXT32': {'frames': 9000, 'full_path': 26000},
        'PandarXT32M2X': {'frames': 5000, 'full_path': 18000},
    },
}
# Issue #43's target on the Cortex-M4F, every sensor: the decode with the unit scan at most 1.15
# times the decode (the scan folded into the assembly loops, not a second pass over the units).
SCAN_RATIO_TARGET = {'cortex-m4': 1.15}
# Issue #25's targets on the Cortex-M4F, every sensor: instructions per unit less validate (the
# ARMv7E-M assembly loops, kernels/armv7m_loops.h), and validate + columns decode at the sensor's
# dual-return packet rate within a 168 MHz core at one instruction a cycle.
PER_UNIT_TARGETS = {'cortex-m4': {'decode': 48, 'decode_columns': 40}}
COLUMNS_CLOCK_TARGET = {'cortex-m4': 168e6}
# Packets per second at 600 rpm in dual return, the bundled captures' mode (packets per rotation
# counted between azimuth wraps in data/*.pcap, and the pcap timestamps agree): Pandar40/40P 10
# blocks = 5 azimuths of 0.2 degrees per packet, 360 per rotation; Pandar64 6 blocks = 3 azimuths,
# 600 per rotation; QT128C2X 2 blocks = 1 azimuth of 0.4 degrees, 900 per rotation; PandarQT64 4
# blocks = 2 azimuths of 0.6 degrees, 300; PandarXT16/XT32 8 blocks = 4 azimuths of 0.18 degrees,
# 500; PandarXT32M2X 6 blocks = 3 azimuths of 0.18 degrees, 666.7 (its capture has gaps; the other
# captures count 300 and 500 between wraps). rpm / 60 x that.
PACKETS_PER_ROTATION = {'Pandar40': 360, 'Pandar40P': 360, 'Pandar64': 600, 'QT128C2X': 900, 'PandarQT64': 300,
                        'PandarXT16': 500, 'PandarXT32': 500, 'PandarXT32M2X': 360 / 0.54}
RPM = 600
# Units (blocks x channels) in the packet each sensor's count decodes (fuzz/seed_packets.inc: the
# layouts' block and channel counts; the QT128C2X packet has flags 0x1D, 2 blocks of 128).
UNITS = {'Pandar40': 400, 'Pandar40P': 400, 'Pandar64': 384, 'QT128C2X': 256, 'PandarQT64': 256,
         'PandarXT16': 128, 'PandarXT32': 256, 'PandarXT32M2X': 192}
CLOCKS = (('Cortex-M4F at 168 MHz', 168e6), ('Cortex-M7 at 400 MHz', 400e6))
# Double-precision soft-float: __aeabi_dadd, __aeabi_d2f, ..., and the conversions to double
# (__aeabi_f2d, __aeabi_i2d, __aeabi_l2d, ...); libgcc's generic names (__adddf3, __extendsfdf2, ...).
DOUBLE_ROUTINE = re.compile(r'^(__aeabi_d\w+|__aeabi_\w+2d|__\w+df\d?)$')

# Components of the core: (label, folder of core/src, archive members = source files). Every
# object the build produces must belong to exactly one row, in its own folder (checked below), so a
# new source file cannot drop out of the report.
COMPONENTS = [
    ('sensors/: identify, validate, decode (every sensor)', 'sensors',
     ['decoder', 'pandar40', 'pandar64', 'qt128', 'qt64', 'xt', 'registry', 'tables']),
    ('kernels/: the per-point code, the beam-cache rebuild, the vector path choice', 'kernels',
     ['beam_cache', 'vector_isa', 'x86_columns', 'x86_points', 'x86_scan', 'neon_columns', 'neon_points', 'armv7m_loops',
      'kernel_counters']),
    ('base/: error names, x86-64 CPU features', 'base', ['error', 'cpu_x86']),
    ('crc/: CRC-32/MPEG-2', 'crc', ['crc32', 'crc32_arm', 'crc32_x86']),
    ('crypto/: SHA-256 + HMAC-SHA256', 'crypto', ['sha256', 'hmac', 'ct']),
    ('crypto/: HKDF', 'crypto', ['hkdf']),
    ('calibration/: calibration files', 'calibration', ['decimal', 'csv_rows', 'angles_csv', 'firetimes_csv', 'channel_config_csv']),
    ('sensors/: GPS packets', 'sensors', ['gps']),
    ('streams/: frames, rotation, sequence, replays, stream health, safety monitor, stats', 'streams',
     ['frame', 'rotation', 'sequence', 'replay', 'health', 'safety', 'stats']),
    ('capi/: the C interface (hesai.h)', 'capi', ['hesai_c']),
    ('ptc/: PTC framing and payloads (hesai/ptc.h, hesai/ptc_settings.h)', 'ptc', ['ptc', 'ptc_settings']),
]
IN_BUDGET = {'sensors/: identify, validate, decode (every sensor)',
             'kernels/: the per-point code, the beam-cache rebuild, the vector path choice', 'base/: error names, x86-64 CPU features', 'crc/: CRC-32/MPEG-2',
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


# The functions a SensorDescriptor points to (group 1: the member; qt128::seal is a `seal`), the
# one a Decoder::CompareReturns points to (group 2, sensors/decoder.cpp), and which of them each
# function that calls through a pointer calls (core/src/sensors/).
REGISTRY_TARGET = re.compile(r'hesai::SensorCode<[^>]*>::(identify|design|validate|walk|sequence_at)\b|hesai::qt128::seal\b'
                             r'|hesai::\{anonymous\}::(compare_returns|survey_units)\b')
INDIRECT_CALLS = {
    'hesai::SensorBase::emit_blocks': ('compare_returns', 'survey_units'),
    'hesai::Decoder::survey': ('walk',),
    'hesai::Decoder::Decoder': ('design',),
    'hesai::identify': ('identify',),
    'hesai::Decoder::validate': ('identify', 'validate'),
    'hesai::Decoder::decode_into': ('walk',),
    'hesai::write_udp_sequence': ('identify', 'sequence_at', 'seal'),
}


# Frame bytes and variants of each family; the unit scan's loops (issue #43) push r11 too.
ASSEMBLY_FRAMES = {'hesai_armv7m_points_': (9 * 4 + 4, ('u3_l0', 'u3_l1', 'u4_l0', 'u4_l1')),
                   'hesai_armv7m_columns_': (9 * 4, ('u3_l0', 'u3_l1', 'u4_l0', 'u4_l1')),
                   'hesai_armv7m_points_scan_': (9 * 4 + 4, ('u3_l0', 'u3_l1', 'u4m_l0', 'u4m_l1')),
                   'hesai_armv7m_points_repeat_': (9 * 4 + 4, ('u3_l0', 'u3_l1', 'u4_l0', 'u4m_l0', 'u4m_l1'))}


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
    # The core's only indirect calls are through the registry of sensors (sensors/sensor.h): each
    # caller calls one or more SensorDescriptor members, and may reach that member of any sensor.
    # The stack and the double-precision check follow those (INDIRECT_CALLS); an indirect call
    # from any other function is left as `__indirect_call`, which fails the report.
    targets = {}
    for t, n in names.items():
        m = REGISTRY_TARGET.search(n)
        if m:
            targets.setdefault(m.group(1) or m.group(2) or 'seal', set()).add(t)
    for fn, callees in edges.items():
        members = INDIRECT_CALLS.get(short_name(names.get(fn, fn)))
        if '__indirect_call' in callees and members:
            callees.discard('__indirect_call')
            for member in members:
                callees |= targets.get(member, set())
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

def double_precision_check(rows, edges, frames, names, over):
    """Issue #13: no double-precision soft-float reachable from validate() or decode(). Names the
    core function that calls each routine found."""
    lines = ['', '### Double-precision soft-float under validate/decode', '']
    found = {}
    for total, name, chain, external, unbounded in rows:
        if name not in ('hesai::Decoder::validate', 'hesai::Decoder::decode'):
            continue
        doubles = sorted(e for e in external if DOUBLE_ROUTINE.match(e))
        if not doubles:
            continue
        callers = set()
        stack, seen = [chain[0]], set()
        while stack:  # every core function reachable from the entry point that calls one directly
            fn = stack.pop()
            if fn in seen:
                continue
            seen.add(fn)
            for callee in edges.get(fn, ()):
                if callee in frames:
                    stack.append(callee)
                elif DOUBLE_ROUTINE.match(callee):
                    callers.add(short_name(names.get(fn, fn)).replace('hesai::', ''))
        found[name] = (doubles, sorted(callers))
    if not found:
        lines.append('None: no __aeabi_d* (or conversion to double) reachable from Decoder::validate or Decoder::decode.')
    for name, (doubles, callers) in sorted(found.items()):
        lines.append('**%s** reaches %s, called from %s.' % (name.replace('hesai::', ''), ', '.join(doubles), ', '.join(callers)))
        over.append('double-precision soft-float under %s (%s)' % (name.replace('hesai::', ''), ', '.join(callers)))
    lines.append('')
    return lines


def instructions_json(counts, path):
    """build/<preset>/instructions.json: one entry per sensor, whole-call counts (decodes include validate)."""
    out = {}
    for sensor, c in counts.items():
        if sensor not in UNITS:
            continue
        out[sensor] = {'units': UNITS[sensor], 'packets_per_second': round(RPM / 60 * PACKETS_PER_ROTATION[sensor], 1),
                       'validate': c.get('validate'), 'decode_points': c.get('decode'),
                       'decode_columns': c.get('decode_columns'), 'decode_points_rate_change': c.get('decode_rpm_change'),
                       'decode_points_scan': c.get('decode_scan'), 'health': c.get('health'),
                       'frames': c.get('frames'), 'full_path': c.get('full_path')}
    with open(path, 'w') as f:
        json.dump(out, f, indent=2)
        f.write('\n')


def instruction_counts(emulator, image, over, json_path=None):
    """Runs the image under -icount shift=7 and tabulates its instruction counts."""
    cmd = shlex.split(emulator)
    at = cmd.index('-kernel') if '-kernel' in cmd else len(cmd)
    cmd = cmd[:at] + ['-icount', 'shift=7'] + cmd[at:] + ([image] if '-kernel' in cmd else ['-kernel', image])
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    out = run.stdout + run.stderr  # semihosting writes to stderr when stdout is not a terminal
    core = 'cortex-m0plus' if 'cortex-m0plus' in out else 'cortex-m4' if 'cortex-m4' in out else None
    counts = {}
    for m in re.finditer(r'^instructions: (\S+) (\S+) (\d+)$', out, re.M):
        counts.setdefault(m.group(1), {})[m.group(2)] = int(m.group(3))
    lines = ['### Instructions per packet (qemu-system-arm -icount shift=7, counted with SysTick)', '']
    if not counts or core is None or 'all checks passed' not in out:
        over.append('no instruction counts from %s' % image)
        return lines + ['The image printed no instruction counts (or failed): see its output.', '']
    budgets = INSTRUCTION_BUDGETS[core]
    for c in counts.values():
        if all(what in c for what in ('decode_scan', 'health', 'frames')):
            c['full_path'] = c['decode_scan'] + c['health'] + c['frames']
    lines += ['Exact counts of the instructions executed per call (main.cpp says how), for one real packet of '
              'each sensor (dual return); `decode` includes its `validate`. *rate change*: the packet at another '
              'spin rate, so that the per-rate cache is rebuilt first (the worst case). Budget (%s, in brackets): '
              'the count measured when it was set, plus 25%%.' % core, '',
              '| sensor | validate | decode | decode, columns | decode, rate change | per unit less validate: points, columns | packets/s | decode, M instructions/s |',
              '| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |']
    per_second = {}
    for sensor, c in counts.items():
        rate = RPM / 60 * PACKETS_PER_ROTATION.get(sensor, 0)
        per_second[sensor] = c.get('decode', 0) * rate
        budget = budgets.get(sensor, {})
        cell = lambda what: '%d (%s)' % (c.get(what, 0), budget.get(what, 'no budget'))
        units = UNITS.get(sensor, 0)
        per_unit = lambda what: (c.get(what, 0) - c.get('validate', 0)) / units if units else 0
        lines.append('| %s | %s | %s | %s | %s | %.0f, %.0f | %d | %.0f |' % (
            sensor, cell('validate'), cell('decode'), cell('decode_columns'), cell('decode_rpm_change'),
            per_unit('decode'), per_unit('decode_columns'), rate, per_second[sensor] / 1e6))
        for what in ('validate', 'decode', 'decode_columns', 'decode_rpm_change'):
            if what not in budget or c.get(what, 0) > budget[what]:
                over.append('instructions %s %s %d > budget %s' % (sensor, what, c.get(what, 0), budget.get(what)))
        health_budget = dict(HEALTH_BUDGETS.get(core, {}).get(sensor, {}))
        health_budget.update(FRAMES_BUDGETS.get(core, {}).get(sensor, {}))
        for what, limit in health_budget.items():
            if what not in c or c[what] > limit:
                over.append('instructions %s %s %s > budget %d' % (sensor, what, c.get(what), limit))
        scan_ratio = SCAN_RATIO_TARGET.get(core)
        if scan_ratio and 'decode_scan' in c and c['decode_scan'] > scan_ratio * c.get('decode', 0):
            over.append('instructions %s decode_scan %d > %.2f x decode %d' % (sensor, c['decode_scan'], scan_ratio, c.get('decode', 0)))
        for what, target in PER_UNIT_TARGETS.get(core, {}).items():
            if per_unit(what) > target:
                over.append('instructions %s %s %.1f a unit > target %d' % (sensor, what, per_unit(what), target))
        if core in COLUMNS_CLOCK_TARGET and c.get('decode_columns', 0) * rate > COLUMNS_CLOCK_TARGET[core]:
            over.append('instructions %s columns at %d packets/s: %.0f M/s > %.0f M/s' % (
                sensor, rate, c.get('decode_columns', 0) * rate / 1e6, COLUMNS_CLOCK_TARGET[core] / 1e6))
    if any('health' in c for c in counts.values()):
        lines += ['', 'Stream health (issue #32): `decode_scan` is the decode with the unit scan (`Decoder::decode` with a '
                  '`UnitScan`), `health` the monitor on the next packet in order (`HealthMonitor::observe` + '
                  '`observe_units`); budget in brackets where the core has one.', '',
                  '| sensor | decode | decode_scan | decode_scan / decode | health |', '| --- | ---: | ---: | ---: | ---: |']
        for sensor, c in counts.items():
            hb = HEALTH_BUDGETS.get(core, {}).get(sensor, {})
            ratio = c.get('decode_scan', 0) / c['decode'] if c.get('decode') else 0
            target = ' (target %.2f)' % SCAN_RATIO_TARGET[core] if core in SCAN_RATIO_TARGET else ''
            lines.append('| %s | %d | %d (%s) | %.3f%s | %d (%s) |' % (sensor, c.get('decode', 0), c.get('decode_scan', 0),
                                                                     hb.get('decode_scan', 'no budget'), ratio, target,
                                                                     c.get('health', 0), hb.get('health', 'no budget')))
    if any('frames' in c for c in counts.values()):
        lines += ['', 'Frames (issue #43): `frames` is the FrameAssembler on the packet (`begin_packet`, `block` per block, '
                  'each block\'s points by `points()`), a stream under way, no block on the cut; `per point` the same with '
                  '`point()` for each point; `full_path` = decode_scan (validate included) + health + frames. Budget in '
                  'brackets.', '',
                  '| sensor | frames | per point | full_path | full_path, Cortex-M4F at 168 MHz |', '| --- | ---: | ---: | ---: | ---: |']
        for sensor, c in counts.items():
            fb = FRAMES_BUDGETS.get(core, {}).get(sensor, {})
            rate = RPM / 60 * PACKETS_PER_ROTATION.get(sensor, 0)
            lines.append('| %s | %d (%s) | %d | %d (%s) | %.0f%% |' % (sensor, c.get('frames', 0), fb.get('frames', 'no budget'),
                                                                    c.get('frames_per_point', 0), c.get('full_path', 0),
                                                                    fb.get('full_path', 'no budget'),
                                                                    100 * c.get('full_path', 0) * rate / 168e6))
    qt = counts.get('QT128C2X', {})
    if 'validate_signed' in qt:
        signature = qt['validate_signed'] - qt['validate']
        rate = RPM / 60 * PACKETS_PER_ROTATION['QT128C2X']
        per_second['QT128C2X, signed'] = (qt['decode'] + signature) * rate
        lines += ['', 'QT128C2X signature check (validate of a signed packet with a session key, less validate '
                  'without): **%d instructions** (budget %d; HMAC-SHA256 over 1 095 bytes, key prepared; validate '
                  'signed: %d).' % (signature, budgets['QT128C2X']['signature'], qt['validate_signed'])]
        if signature > budgets['QT128C2X']['signature']:
            over.append('instructions QT128C2X signature %d > %d' % (signature, budgets['QT128C2X']['signature']))
    if core == 'cortex-m4':
        # The same ARMv7E-M code on a Cortex-M7. 1 instruction = 1 cycle: low on a Cortex-M4F
        # (loads take 2 cycles, taken branches 2-4, flash wait states above ~30 MHz unless an
        # accelerator or cache hides them), high on a Cortex-M7 (dual issue, from TCM or cache).
        lines += ['', 'CPU time per second of sensor data at 600 rpm, dual return, taking 1 instruction as 1 cycle '
                  '(an underestimate on a Cortex-M4F: loads take 2 cycles and taken branches 2-4, plus any flash wait '
                  'states; an overestimate on a Cortex-M7, which issues two instructions a cycle where it can):', '',
                  '| sensor | instructions/s | ' + ' | '.join(c[0] for c in CLOCKS) + ' |',
                  '| --- | ---: |' + ' ---: |' * len(CLOCKS)]
        for sensor, ips in per_second.items():
            lines.append('| %s | %.1f M | %s |' % (sensor, ips / 1e6, ' | '.join('%.0f%%' % (100 * ips / hz) for _, hz in CLOCKS)))
    if json_path:
        instructions_json(counts, json_path)
    lines.append('')
    return lines


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--map', required=True)
    ap.add_argument('--objects', required=True)
    ap.add_argument('--size', required=True)
    ap.add_argument('--minimal-map', help='linker map of the image built with the smallest configuration')
    ap.add_argument('--emulator', help='the command that runs an image, up to and including -kernel')
    ap.add_argument('--image', help='the firmware image that counts instructions under -icount')
    ap.add_argument('--out')
    ap.add_argument('--instructions-json', help='where to write the instruction counts as JSON')
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
    # The assembly loops (kernels/armv7m_loops.cpp) have no -fstack-usage entry: their frames by hand
    # (PUSH of 9 registers, and the Points loops' VPUSH of one), so that the stack figures hold.
    for name, (frame, variants) in ASSEMBLY_FRAMES.items():
        for variant in variants:
            frames[name + variant] = frame
            names[name + variant] = name + variant
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
        if '__indirect_call' in external:
            over.append('stack %s: an indirect call that INDIRECT_CALLS does not resolve' % name)
    lines += ['', 'Budget: at most %d bytes of stack per call; worst: %d bytes.' % (STACK_BUDGET, rows[0][0] if rows else 0)]
    lines += double_precision_check(rows, edges, frames, names, over)
    if args.emulator and args.image:
        lines += instruction_counts(args.emulator, args.image, over, args.instructions_json)

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
