/* Arm semihosting: the test image's only way out of the emulator (text and exit status). */
#ifndef HESAI_FIRMWARE_SEMIHOST_H
#define HESAI_FIRMWARE_SEMIHOST_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes a NUL-terminated string to the host's console (SYS_WRITE0). */
void semihost_write(const char* text);
/* Ends the emulator: exit status 0 when ok, 1 otherwise (SYS_EXIT). */
__attribute__((noreturn)) void semihost_exit(bool ok);

#ifdef __cplusplus
}
#endif

#endif
