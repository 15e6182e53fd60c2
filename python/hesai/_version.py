"""The package's version: the CMake project's (CMakeLists.txt `project(hesai VERSION ...)`)."""

__version__ = "0.1.0"
