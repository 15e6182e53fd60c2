/* bench/e2e's `columns`: the core's columnar decode (hesai_decoder_decode_columns, the vector path
 * the CPU has) of every point-cloud packet of a classic pcap, once, in a process of its own, as
 * `hesai stats CAPTURE` is run: what the program's whole path (health, frames, counters) is
 * measured against. The file is mapped, as the program maps it; each packet goes into one packet's
 * columns (in cache): the decode alone, with reading the file and finding the payloads, and
 * nothing written beyond.
 * Usage: hesai_columns_decode CAPTURE.pcap
 * Prints "PACKETS POINTS". Exit 2 for a file it cannot read or a point-cloud packet that does not
 * decode (the bundled captures all do); GPS packets and other datagrams are passed over. */
#define _POSIX_C_SOURCE 200112L
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hesai/hesai.h"

static uint32_t le32(const uint8_t* p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

int main(int argc, char** argv) {
  static hesai_decoder decoder;
  static float x[400], y[400], z[400];
  static int32_t t[400];
  static uint8_t in[400], ch[400], re[400];
  int fd;
  struct stat st;
  size_t size;
  const uint8_t* data;
  size_t off = 24, packets = 0, points = 0;
  int have_decoder = 0;
  hesai_point_columns cols;
  if (argc != 2) {
    fprintf(stderr, "usage: %s CAPTURE.pcap\n", argv[0]);
    return 1;
  }
  fd = open(argv[1], O_RDONLY);
  if (fd < 0 || fstat(fd, &st) != 0 || st.st_size < 24) {
    fprintf(stderr, "%s: cannot read\n", argv[1]);
    return 2;
  }
  size = (size_t)st.st_size;
  data = mmap(NULL, size, PROT_READ, MAP_PRIVATE, fd, 0);
  if (data == MAP_FAILED || le32(data) != 0xA1B2C3D4u) {
    fprintf(stderr, "%s: not a little-endian classic pcap of microseconds\n", argv[1]);
    return 2;
  }
  cols.x = x; cols.y = y; cols.z = z; cols.time_ns = t; cols.intensity = in; cols.channel = ch; cols.return_index = re;
  cols.capacity = 400;
  while (off + 16 <= size) { /* Ethernet, IPv4, UDP */
    const size_t incl = le32(data + off + 8);
    const uint8_t* fr = data + off + 16;
    size_t udp, length, count = 0;
    uint8_t model = 0, gps = 0;
    hesai_packet_info info;
    off += 16 + incl;
    if (off > size || incl < 42 || fr[12] != 0x08 || fr[13] != 0x00 || fr[23] != 17) continue;
    udp = 14 + (size_t)(fr[14] & 0x0F) * 4;
    length = ((size_t)fr[udp + 4] << 8 | fr[udp + 5]) - 8;
    if (udp + 8 + length > incl || hesai_identify(fr + udp + 8, length, &model, &gps) != HESAI_ERROR_ok || gps) continue;
    if (!have_decoder || hesai_decoder_model(&decoder) != (hesai_model)model) {
      if (hesai_decoder_init(&decoder, (hesai_model)model) != HESAI_ERROR_ok) return 2;
      have_decoder = 1;
    }
    if (hesai_decoder_decode_columns(&decoder, fr + udp + 8, length, &info, &cols, &count) != HESAI_ERROR_ok) {
      fprintf(stderr, "%s: point-cloud packet %lu does not decode\n", argv[1], (unsigned long)packets);
      return 2;
    }
    ++packets;
    points += count;
  }
  printf("%lu %lu\n", (unsigned long)packets, (unsigned long)points);
  munmap((void*)data, size);
  close(fd);
  return 0;
}
