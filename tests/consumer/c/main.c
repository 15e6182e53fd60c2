/* A C99 program outside the project that links the installed hesai::core. It decodes one Pandar64
 * packet built here field by field (Pandar64 manual section 3.1.2): channel 5 of block 3 at a
 * distance of 2500 x 4 mm = 10 m, all other channels empty. */
#include <stdio.h>

#include "hesai/hesai.h"

static hesai_decoder decoder;   /* HESAI_DECODER_SIZE bytes, static */
static hesai_point points[384]; /* the Pandar64's most points: 6 blocks x 64 channels */
static uint8_t packet[1194];

int main(void) {
  static const uint8_t date[6] = {24, 5, 17, 8, 30, 15}; /* 2024-05-17 08:30:15, year - 2000 */
  const size_t point = 8 + 194 * 2 + 2 + 3 * 4;          /* block 3, channel 5 */
  size_t count = 0, i;
  hesai_error e;
  /* Header: EE FF, 64 lasers, 6 blocks, distance unit 4 mm. */
  packet[0] = 0xEE;
  packet[1] = 0xFF;
  packet[2] = 64;
  packet[3] = 6;
  packet[5] = 4;
  /* Six blocks of 2 + 64 x 3 bytes from byte 8, each at azimuth 100.00 degrees (10000). */
  for (i = 0; i < 6; ++i) {
    packet[8 + 194 * i] = 10000 & 0xFF;
    packet[8 + 194 * i + 1] = 10000 >> 8;
  }
  packet[point] = 2500 & 0xFF; /* distance, little endian */
  packet[point + 1] = 2500 >> 8;
  packet[point + 2] = 77; /* reflectivity */
  /* Tail from byte 1172: 600 rpm at +8, return mode 0x37 (strongest) at +14, date-time at +16. */
  packet[1180] = 600 & 0xFF;
  packet[1181] = 600 >> 8;
  packet[1186] = 0x37;
  for (i = 0; i < 6; ++i) packet[1188 + i] = date[i];

  e = hesai_decoder_init(&decoder, HESAI_MODEL_pandar64);
  if (e == HESAI_ERROR_ok) e = hesai_decoder_decode(&decoder, packet, sizeof packet, NULL, points, 384, &count);
  printf("C consumer: %s, %u point(s); channel %u of block %u at %.3f m, reflectivity %u\n", hesai_error_name(e),
         (unsigned)count, points[0].channel, points[0].block + 1u, (double)points[0].distance_m, points[0].intensity);
  return e == HESAI_ERROR_ok && count == 1 && points[0].channel == 5 && points[0].block == 2 &&
                 points[0].distance_m > 9.999f && points[0].distance_m < 10.001f && points[0].intensity == 77
             ? 0
             : 1;
}
