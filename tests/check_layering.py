#!/usr/bin/env python3
"""The layering of core/ and port/ (core/src/README.md, port/src/README.md): every file, source or
public header, belongs to one concern, and includes only headers of its own concern or of the
concerns below it.

    core:  base <- crc, crypto, calibration, ptc, kernels <- sensors <- streams <- capi
    port:  (all of core) <- base <- capture, net, formats <- pipeline <- cli, capi

Nothing in core/ includes a header of port/. A core public header's concern is given below; a port
public header's is the folder it sits in under port/include/hesai_port/; a file under
<tree>/src/<folder>/ has that folder's, and so has a private header reached from another folder as
"../<folder>/name.h".

Usage: check_layering.py ROOT [core|port]   (ROOT holds core/ and port/; both trees by default)
Exits 1 and names each include that reaches upward (or sideways) and each file of no concern.
"""
import os
import re
import sys

CORE_BELOW = {  # concern -> the concerns it may include
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
CORE_HEADERS = {  # public header (under core/include/hesai/) -> concern
    'config.h': 'base', 'bytes.h': 'base', 'error.h': 'base', 'error_list.h': 'base', 'model.h': 'base', 'model_list.h': 'base',
    'civil_time.h': 'base', 'detail/math.h': 'base', 'saturating.h': 'base',
    'crc32.h': 'crc',
    'sha256.h': 'crypto', 'hmac.h': 'crypto', 'hkdf.h': 'crypto', 'ct.h': 'crypto',
    'calibration.h': 'calibration', 'detail/decimal.h': 'calibration',
    'ptc.h': 'ptc', 'ptc_settings.h': 'ptc', 'detail/kernel_calls.h': 'kernels',
    'decoder.h': 'sensors', 'point.h': 'kernels', 'gps.h': 'sensors', 'detail/pandar40_packet.h': 'sensors',
    'detail/pandar64_packet.h': 'sensors', 'detail/qt128_packet.h': 'sensors', 'detail/xt_packet.h': 'sensors',
    'detail/tables/': 'sensors', 'detail/qt64_packet.h': 'sensors',
    'frame.h': 'streams', 'sequence.h': 'streams', 'stats.h': 'streams', 'safety.h': 'streams', 'health.h': 'streams',
    'rotation.h': 'streams', 'held_packets.h': 'streams', 'replay.h': 'streams', 'detail/seen_window.h': 'streams',
    'hesai.h': 'capi', 'packet_info_list.h': 'capi',
}

# The port sits on the whole core: each of its concerns may include any core header.
PORT_BELOW = {
    'base': set(),
    'capture': {'base'},
    'net': {'base'},
    'formats': {'base'},
    'pipeline': {'base', 'capture', 'formats'},
    'cli': {'base', 'capture', 'net', 'formats', 'pipeline'},
    'capi': {'base', 'capture', 'net', 'formats', 'pipeline'},
}
PORT_HEADERS = {'hesai_capture.h': 'capi'}  # the installed C header, at the top of hesai_port/

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def core_header_concern(name):
    for key, concern in CORE_HEADERS.items():
        if name == key or (key.endswith('/') and name.startswith(key)):
            return concern
    return None


def port_header_concern(name):
    if name in PORT_HEADERS:
        return PORT_HEADERS[name]
    folder = name.split('/')[0]
    return folder if '/' in name and folder in PORT_BELOW else None


class Tree:
    """One of core/ and port/: its public headers' folder, how a header's concern is found, and
    what each concern may include."""

    def __init__(self, root, name):
        self.name = name
        self.path = os.path.join(root, name)
        if name == 'core':
            self.prefix, self.below, self.header_concern = 'hesai/', CORE_BELOW, core_header_concern
        else:
            self.prefix, self.below, self.header_concern = 'hesai_port/', PORT_BELOW, port_header_concern

    def files(self):
        """(path, name shown, concern) for every public header and source."""
        out = []
        include_dir = os.path.join(self.path, 'include', self.prefix.rstrip('/'))
        for root, _, names in os.walk(include_dir):
            for n in names:
                rel = os.path.relpath(os.path.join(root, n), include_dir).replace(os.sep, '/')
                out.append((os.path.join(root, n), self.prefix + rel, self.header_concern(rel)))
        src = os.path.join(self.path, 'src')
        for root, _, names in os.walk(src):
            folder = os.path.relpath(root, src).split(os.sep)[0]
            for n in names:
                if n.endswith(('.cpp', '.h')):
                    concern = folder if folder in self.below else None
                    out.append((os.path.join(root, n), '%s/src/%s/%s' % (self.name, folder, n), concern))
        return out

    def target(self, include):
        """The concern an include names: (tree name, concern), concern None if it has none;
        None for a header of the file's own folder."""
        if include.startswith('../'):
            folder = include.split('/')[1]  # another folder's private header
            return self.name, folder if folder in self.below else None
        if include.startswith('hesai/'):
            return 'core', core_header_concern(include[len('hesai/'):])
        if include.startswith('hesai_port/'):
            return 'port', port_header_concern(include[len('hesai_port/'):])
        return None


def check(tree):
    problems, files = [], tree.files()
    for path, name, concern in sorted(files):
        if concern is None:
            problems.append('%s belongs to no concern' % name)
            continue
        for line in open(path, encoding='utf-8'):
            m = INCLUDE.match(line)
            if not m:
                continue  # a system header
            target = tree.target(m.group(1))
            if target is None:
                continue
            target_tree, target_concern = target
            if target_tree != tree.name:
                if tree.name == 'core':
                    problems.append('%s (core) includes %s, a header of port/' % (name, m.group(1)))
                elif target_concern is None:
                    problems.append('%s includes %s, which belongs to no concern' % (name, m.group(1)))
                continue  # the port may include any core header
            if target_concern is None:
                problems.append('%s includes %s, which belongs to no concern' % (name, m.group(1)))
            elif target_concern != concern and target_concern not in tree.below[concern]:
                problems.append('%s (%s) includes %s (%s)' % (name, concern, m.group(1), target_concern))
    for p in problems:
        print(p)
    print('%s layering: %d files, %d problems' % (tree.name, len(files), len(problems)))
    return problems


def main(argv):
    root = argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), '..')
    names = argv[2:] or ['core', 'port']
    failed = False
    for name in names:
        if name not in ('core', 'port'):
            print('usage: check_layering.py ROOT [core|port]')
            return 2
        failed |= bool(check(Tree(root, name)))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
