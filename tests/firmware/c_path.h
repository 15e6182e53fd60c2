/* The firmware image's C path (c_path.c): the decoder used from C through hesai.h. */
#ifndef HESAI_FIRMWARE_C_PATH_H
#define HESAI_FIRMWARE_C_PATH_H

#include <stddef.h>
#include <stdint.h>

#include "hesai/hesai.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sets up the C path's QT128C2X decoder (design values) and checks from C what hesai.h promises
 * for a damaged packet and a short point array; prints each failure. `points` is the caller's
 * array of `capacity` entries; `scratch` (at least `size` bytes) is the caller's too, where the
 * damaged copy of the packet is made, so that the C path takes no RAM beyond its decoder.
 * Returns the number of failures. */
int firmware_c_path_checks(const uint8_t* qt128, size_t size, hesai_point* points, size_t capacity,
                           uint8_t* scratch, size_t scratch_size);
/* Decodes a QT128C2X packet with the C path's decoder into points[0 .. *count). */
hesai_error firmware_c_decode(const uint8_t* qt128, size_t size, hesai_point* points, size_t capacity, size_t* count);

#ifdef __cplusplus
}
#endif

#endif
