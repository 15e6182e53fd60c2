#!/usr/bin/env python3
"""check_layering.py catches what it is there to catch: on a copy of core/ and port/, each include
planted below (a format reaching into the network code, a capture reader into a format, the core
into the port, a library file or the engine into the program, the engine into the network) makes it exit 1 and name that include, while the
unplanted copy passes.

Usage: check_layering_planted.py ROOT   (ROOT holds core/, port/ and tests/check_layering.py)
"""
import os
import shutil
import subprocess
import sys
import tempfile

PLANTS = [  # (file to plant in, the include, the line check_layering.py must print)
    ('port/src/formats/png.cpp', '#include "hesai_port/net/udp.h"',
     'port/src/formats/png.cpp (formats) includes hesai_port/net/udp.h (net)'),
    ('port/src/capture/mcap_parser.cpp', '#include "hesai_port/formats/writers.h"',
     'port/src/capture/mcap_parser.cpp (capture) includes hesai_port/formats/writers.h (formats)'),
    ('port/src/net/udp.cpp', '#include "../cli/options.h"',
     'port/src/net/udp.cpp (net) includes ../cli/options.h (cli)'),
    ('port/src/cli/decode.cpp', '#include "hesai_port/hesai_capture.h"',
     'port/src/cli/decode.cpp (cli) includes hesai_port/hesai_capture.h (capi)'),
    ('port/src/capi/hesai_capture.cpp', '#include "../cli/options.h"',
     'port/src/capi/hesai_capture.cpp (capi) includes ../cli/options.h (cli)'),
    ('port/src/pipeline/sinks.cpp', '#include "../cli/commands.h"',
     'port/src/pipeline/sinks.cpp (pipeline) includes ../cli/commands.h (cli)'),
    ('port/src/pipeline/pipeline.cpp', '#include "hesai_port/net/udp.h"',
     'port/src/pipeline/pipeline.cpp (pipeline) includes hesai_port/net/udp.h (net)'),
    ('core/src/streams/frame.cpp', '#include "hesai_port/capture/capture.h"',
     'core/src/streams/frame.cpp (core) includes hesai_port/capture/capture.h, a header of port/'),
]


def run(script, root):
    r = subprocess.run([sys.executable, script, root], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def main(root):
    script = os.path.join(root, 'tests', 'check_layering.py')
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for tree in ('core', 'port'):
            for part in ('include', 'src'):
                shutil.copytree(os.path.join(root, tree, part), os.path.join(tmp, tree, part))
        rc, out = run(script, tmp)
        if rc != 0:
            print('the unplanted copy fails:\n' + out)
            return 1
        for path, include, expected in PLANTS:
            target = os.path.join(tmp, path)
            original = open(target, encoding='utf-8').read()
            with open(target, 'w', encoding='utf-8') as f:
                f.write(include + '\n' + original)
            rc, out = run(script, tmp)
            with open(target, 'w', encoding='utf-8') as f:
                f.write(original)
            caught = rc == 1 and expected in out.splitlines()
            print('%s: %s planted in %s (exit %d)' % ('caught' if caught else 'MISSED', include, path, rc))
            if not caught:
                print(out)
                failures += 1
    print('%d planted includes, %d missed' % (len(PLANTS), failures))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..')))
