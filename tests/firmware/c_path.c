/* The firmware image's C path: a C99 translation unit that uses the decoder as firmware written in
 * C would, through hesai.h: the decoder in static storage, the points in the caller's array, no
 * heap. main.cpp runs it on the real QT128C2X packet and checks its points against the manual's
 * and against hesai::Decoder's. */
#include "c_path.h"

#include <string.h>

#include "semihost.h"

static hesai_decoder decoder; /* HESAI_DECODER_SIZE bytes */

static int expect_error(hesai_error got, const char* want, const char* what) {
  if (strcmp(hesai_error_name(got), want) == 0) return 0;
  semihost_write("FAIL: C path: ");
  semihost_write(what);
  semihost_write(": ");
  semihost_write(hesai_error_name(got));
  semihost_write("\n");
  return 1;
}

int firmware_c_path_checks(const uint8_t* qt128, size_t size, hesai_point* points, size_t capacity,
                           uint8_t* damaged, size_t damaged_size) {
  int failures = 0;
  size_t count = 0;
  hesai_packet_info info;
  failures += expect_error(hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x), "ok", "init");
  if (size > damaged_size || capacity < hesai_model_max_points(HESAI_MODEL_qt128c2x)) return failures + 1;
  /* A flipped body byte fails CRC1; one byte short, the flags' length; an array one point short of
   * the QT128's 2 x 128 is refused before the packet is read. */
  memcpy(damaged, qt128, size);
  damaged[100] ^= 0x01;
  failures += expect_error(hesai_decoder_decode(&decoder, damaged, size, &info, points, capacity, &count), "crc_body",
                           "flipped body byte");
  failures += expect_error(hesai_decoder_decode(&decoder, qt128, size - 1, &info, points, capacity, &count),
                           "flags_length_mismatch", "one byte short");
  failures += expect_error(hesai_decoder_decode(&decoder, qt128, size, &info, points, 255, &count),
                           "buffer_too_small", "255 points of room");
  return failures;
}

hesai_error firmware_c_decode(const uint8_t* qt128, size_t size, hesai_point* points, size_t capacity, size_t* count) {
  hesai_packet_info info;
  return hesai_decoder_decode(&decoder, qt128, size, &info, points, capacity, count);
}
