# Bare-metal Cortex-M0+ (ARMv6-M: Thumb-1 subset, no FPU, no hardware divide, and every unaligned
# load or store faults). qemu-system-arm has no Cortex-M0+ board with RAM for a packet's points,
# so the ARMv6-M image runs on the mps2-an385 board (Cortex-M3, which executes ARMv6-M code); its
# startup code sets CCR.UNALIGN_TRP so that an unaligned access faults there as on an M0+.
set(HESAI_CPU_FLAGS "-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft")
set(HESAI_QEMU_MACHINE mps2-an385)
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
