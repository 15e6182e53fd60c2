# Bare-metal Arm Cortex-M with Debian's gcc-arm-none-eabi and picolibc-arm-none-eabi (memcpy and
# memset are all the firmware takes from it). Included by cortex-m4f.cmake and cortex-m0plus.cmake,
# which set HESAI_CPU_FLAGS (the -mcpu/-mfpu flags) and HESAI_QEMU_MACHINE (the qemu-system-arm
# board that runs the firmware image) first.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_SIZE arm-none-eabi-size)
# No host to link a test program against while CMake probes the compiler.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(HESAI_BARE_METAL_FLAGS
    "${HESAI_CPU_FLAGS} --specs=picolibc.specs -ffreestanding -ffunction-sections -fdata-sections")
set(CMAKE_C_FLAGS_INIT "${HESAI_BARE_METAL_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${HESAI_BARE_METAL_FLAGS} -fno-exceptions -fno-rtti -fno-threadsafe-statics")
# The firmware brings its own startup code and linker script (tests/firmware/); the compile
# flags above reach the link too.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-nostartfiles -Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

# ctest runs `qemu-system-arm ... -kernel <image>`; the image reports through semihosting and
# ends qemu with its exit status.
set(CMAKE_CROSSCOMPILING_EMULATOR
    qemu-system-arm -M ${HESAI_QEMU_MACHINE} -nographic -monitor none -serial none
    -semihosting-config enable=on,target=native -kernel)
