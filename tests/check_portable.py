#!/usr/bin/env python3
"""Fails when the portable core still uses a compiler extension that -pedantic-errors lets pass.

Preprocesses every core source twice, as the compiler sees it, and scans only the lines that come
from the core's own files (by the preprocessor's line markers): attributes, inline asm, builtins,
GNU keywords, and the intrinsics and CPUID headers.
- With HESAI_NO_GNU_EXTENSIONS (the portable core) nothing may be found.
- Without it, the GNU paths must be found (else the scan itself is broken).
The language extensions -pedantic-errors rejects (statement expressions, __int128, zero-length
arrays ...) are left to that flag, which every core build has.

Usage: check_portable.py CXX CORE_DIR SOURCE...
"""
import os
import re
import subprocess
import sys

TOKENS = re.compile(r"__attribute__|__asm__|__asm\b|\basm\b|__builtin_\w+|__extension__|__typeof__|\btypeof\b|"
                    r"__declspec|\[\[\s*(?:gnu|clang)::\w+|__restrict\w*|__int128|#\s*pragma\s+(?:GCC|clang)")
HEADERS = re.compile(r"(?:^|/)(?:\w*intrin\.h|cpuid\.h|arm_neon\.h|arm_acle\.h|intrin\.h)$")
MARKER = re.compile(r'^#\s+\d+\s+"([^"]*)"((?:\s+\d)*)')
# What standard macros of the compiler's own headers expand to in the core's lines: not written by
# the core, and every compiler's <cstddef> gives its own (offsetof -> __builtin_offsetof).
STANDARD_EXPANSIONS = {"__builtin_offsetof"}


def scan(cxx, core, source, portable):
    cmd = [cxx, "-E", "-std=c++17", "-I", os.path.join(core, "include"), source]
    if portable:
        cmd.insert(1, "-DHESAI_NO_GNU_EXTENSIONS")
    text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    found = []
    current = source
    for line in text.splitlines():
        m = MARKER.match(line)
        if m:
            new, flags = m.group(1), m.group(2).split()
            if "1" in flags and current.startswith(core) and HEADERS.search(new):
                found.append(f"{current}: includes {new}")
            current = os.path.realpath(new) if not new.startswith("<") else new
            continue
        if current.startswith(core):
            found += [f"{current}: {t.group(0)}" for t in TOKENS.finditer(line) if t.group(0) not in STANDARD_EXPANSIONS]
    return found


def main():
    cxx, core, sources = sys.argv[1], os.path.realpath(sys.argv[2]), sys.argv[3:]
    portable = [f for s in sources for f in scan(cxx, core, s, True)]
    gnu = [f for s in sources for f in scan(cxx, core, s, False)]
    for f in sorted(set(portable)):
        print("GNU construct in the portable core:", f)
    print(f"{len(sources)} sources; GNU constructs: {len(gnu)} with the GNU paths, {len(portable)} without")
    if not gnu:
        print("the scan found no GNU construct even with the GNU paths on: it is broken")
        return 1
    return 1 if portable else 0


if __name__ == "__main__":
    sys.exit(main())
