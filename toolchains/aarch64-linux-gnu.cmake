# Cross build for aarch64-linux-gnu Linux (aarch64). Debian packages: g++-aarch64-linux-gnu, qemu-user.
# +crc: the CRC32 instructions (optional in ARMv8.0 but in the Cortex-A cores and most others; mandatory from ARMv8.1), which
# the port's CRC-32 (IEEE) uses; +crypto: PMULL, which the core's CRC-32/MPEG-2 folding uses.
# CMAKE_CROSSCOMPILING_EMULATOR lets plain ctest (and gtest_discover_tests) run the target binaries.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_C_FLAGS_INIT "-march=armv8-a+crc+crypto")
set(CMAKE_CXX_FLAGS_INIT "-march=armv8-a+crc+crypto")

set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
