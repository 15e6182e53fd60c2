# Bare-metal Cortex-M4F (ARMv7E-M, single-precision FPU, hard-float ABI). The firmware image runs
# on qemu-system-arm's mps2-an386 board (a Cortex-M4 MPS2 FPGA image). Debian packages:
# gcc-arm-none-eabi, libstdc++-arm-none-eabi-dev, picolibc-arm-none-eabi, qemu-system-arm.
set(HESAI_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
set(HESAI_QEMU_MACHINE mps2-an386)
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
