#!/usr/bin/env python3
"""The core's layering (core/src/README.md): every file of the core, source or public header,
belongs to one concern, and includes only headers of its own concern or of the concerns below it.

    base <- crc, crypto, calibration, ptc, kernels <- sensors <- streams <- capi

A public header's concern is given below; a file under core/src/<folder>/ has that folder's, and
so has a private header reached from another folder as "../<folder>/name.h".
Exits 1 and names each include that reaches upward (or sideways) and each file of no concern.
"""
import os
import re
import sys

BELOW = {  # concern -> the concerns it may include
    'base': set(),
    'crc': {'base'},
    'crypto': {'base'},
    'calibration': {'base'},
    'ptc': {'base'},
    'kernels': {'base'},
    'sensors': {'base', 'crc', 'crypto', 'calibration', 'kernels'},
    'streams': {'base', 'crc', 'crypto', 'calibration', 'ptc', 'kernels', 'sensors'},
    'capi': {'base', 'crc', 'crypto', 'calibration', 'ptc', 'kernels', 'sensors', 'streams'},
}
HEADERS = {  # public header (under core/include/hesai/) -> concern
    'config.h': 'base', 'bytes.h': 'base', 'error.h': 'base', 'error_list.h': 'base', 'model.h': 'base', 'model_list.h': 'base',
    'civil_time.h': 'base', 'detail/math.h': 'base', 'saturating.h': 'base',
    'crc32.h': 'crc',
    'sha256.h': 'crypto', 'hmac.h': 'crypto', 'hkdf.h': 'crypto', 'ct.h': 'crypto',
    'calibration.h': 'calibration', 'detail/decimal.h': 'calibration',
    'ptc.h': 'ptc',
    'decoder.h': 'sensors', 'point.h': 'kernels', 'gps.h': 'sensors', 'detail/pandar40_packet.h': 'sensors',
    'detail/pandar64_packet.h': 'sensors', 'detail/qt128_packet.h': 'sensors', 'detail/xt_packet.h': 'sensors',
    'detail/tables/': 'sensors', 'detail/qt64_packet.h': 'sensors',
    'frame.h': 'streams', 'sequence.h': 'streams', 'stats.h': 'streams', 'safety.h': 'streams', 'health.h': 'streams',
    'rotation.h': 'streams', 'held_packets.h': 'streams',
    'hesai.h': 'capi', 'packet_info_list.h': 'capi',
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def header_concern(name):
    for key, concern in HEADERS.items():
        if name == key or (key.endswith('/') and name.startswith(key)):
            return concern
    return None


def main(core):
    problems, files = [], []
    include_dir = os.path.join(core, 'include', 'hesai')
    for root, _, names in os.walk(include_dir):
        for n in names:
            rel = os.path.relpath(os.path.join(root, n), include_dir)
            files.append((os.path.join(root, n), 'hesai/' + rel, header_concern(rel)))
    src = os.path.join(core, 'src')
    for root, _, names in os.walk(src):
        folder = os.path.relpath(root, src).split(os.sep)[0]
        for n in names:
            if n.endswith(('.cpp', '.h')):
                files.append((os.path.join(root, n), 'src/%s/%s' % (folder, n), folder if folder in BELOW else None))
    for path, name, concern in sorted(files):
        if concern is None:
            problems.append('%s belongs to no concern' % name)
            continue
        for line in open(path, encoding='utf-8'):
            m = INCLUDE.match(line)
            if not m:
                continue  # a system header
            if m.group(1).startswith('../'):
                target = m.group(1).split('/')[1]  # another folder's private header
                target = target if target in BELOW else None
            elif m.group(1).startswith('hesai/'):
                target = header_concern(m.group(1)[len('hesai/'):])
            else:
                continue  # a header of the file's own folder
            if target is None:
                problems.append('%s includes %s, which belongs to no concern' % (name, m.group(1)))
            elif target != concern and target not in BELOW[concern]:
                problems.append('%s (%s) includes %s (%s)' % (name, concern, m.group(1), target))
    for p in problems:
        print(p)
    print('core layering: %d files, %d problems' % (len(files), len(problems)))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', 'core')))
