"""Build step of the hesai package (pyproject.toml holds the metadata): puts libhesai_c.so into
the package, so that the installed package loads its own copy.

The library, the first that exists of:
  1. HESAI_LIBRARY: a built libhesai_c.so (an error when it names no file);
  2. HESAI_BUILD_DIR/lib/libhesai_c.so: a CMake build tree of this project;
  3. build/release/lib/libhesai_c.so of the checkout this directory is in (`cmake --preset release
     && cmake --build build/release --target hesai_c`);
  4. a CMake build of the target hesai_c into the checkout's build/python (Release, no tests;
     HESAI_BUILD_JOBS parallel jobs, default 1), which needs cmake and a C++17 compiler.
"""

import os
import pathlib
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent  # the checkout, when this is its python/ directory


def _library() -> pathlib.Path:
    env = os.environ.get("HESAI_LIBRARY")
    if env:
        if not pathlib.Path(env).is_file():
            raise SystemExit(f"hesai: HESAI_LIBRARY={env} is not a file")
        return pathlib.Path(env)
    build = os.environ.get("HESAI_BUILD_DIR")
    if build:
        lib = pathlib.Path(build) / "lib" / "libhesai_c.so"
        if not lib.is_file():
            raise SystemExit(f"hesai: HESAI_BUILD_DIR={build} has no lib/libhesai_c.so "
                             f"(cmake --build {build} --target hesai_c)")
        return lib
    lib = ROOT / "build" / "release" / "lib" / "libhesai_c.so"
    if lib.is_file():
        return lib
    if not (ROOT / "CMakeLists.txt").is_file() or not (ROOT / "port" / "include" / "hesai_port").is_dir():
        raise SystemExit("hesai: no libhesai_c.so: set HESAI_LIBRARY to a built one (this directory is not in a "
                         "checkout of the project, so it cannot be built here)")
    tree = ROOT / "build" / "python"
    jobs = os.environ.get("HESAI_BUILD_JOBS", "1")
    configure = ["cmake", "-S", str(ROOT), "-B", str(tree), "-DCMAKE_BUILD_TYPE=Release", "-DHESAI_BUILD_TESTS=OFF"]
    if shutil.which("ninja"):
        configure += ["-G", "Ninja"]
    for cmd in (configure, ["cmake", "--build", str(tree), "--target", "hesai_c", "-j", jobs]):
        print("hesai:", " ".join(cmd), flush=True)
        try:
            subprocess.run(cmd, check=True)
        except (OSError, subprocess.CalledProcessError) as e:
            raise SystemExit(f"hesai: building libhesai_c failed ({e}); build it yourself and set HESAI_LIBRARY")
    return tree / "lib" / "libhesai_c.so"


class BuildWithLibrary(build_py):
    def run(self):
        super().run()
        lib = _library().resolve()  # the file itself, not the symlink
        target = pathlib.Path(self.build_lib) / "hesai" / "libhesai_c.so"
        print(f"hesai: {lib} -> {target}", flush=True)
        shutil.copyfile(lib, target)


class BinaryDistribution(Distribution):
    """A wheel for this platform (it carries a shared library), not a pure-Python one."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": BuildWithLibrary}, distclass=BinaryDistribution)
