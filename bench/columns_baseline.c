/* The C baseline of python/bench.py's decode_columns column: the core's columnar decode
 * (hesai_decoder_decode_columns, the same code as Google Benchmark's BM_<model>_decode_columns)
 * over every packet of a classic pcap, the payloads already in memory, timed two ways per run:
 *   hot    each packet into one packet's columns (the Google Benchmark's setting: output in cache);
 *   whole  each packet into columns of the whole capture (allocated and touched once, before the
 *          runs), with the absolute int64 time and the packet index written too: the bytes
 *          decode_columns returns, without the cost of new memory.
 * Usage: hesai_columns_baseline CAPTURE.pcap RUNS
 * Prints one JSON object: {"packets": N, "points": P, "hot_ns": [per packet, each run], "whole_ns": [...]}.
 * Exit 2 for a file it cannot read or a packet that does not decode (the bundled captures all do). */
#define _POSIX_C_SOURCE 200112L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hesai/hesai.h"

static double now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static uint32_t le32(const uint8_t* p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

int main(int argc, char** argv) {
  FILE* f;
  long size;
  uint8_t* data;
  const uint8_t** payload;
  size_t* length;
  size_t n = 0, off = 24, i, k, points = 0;
  int runs, r;
  static hesai_decoder decoder;
  static float hx[400], hy[400], hz[400];
  static int32_t ht[400];
  static uint8_t hi[400], hc[400], hr[400];
  hesai_point_columns hot;
  float *x, *y, *z;
  int64_t* t;
  uint8_t *in, *ch, *re;
  uint64_t* pk;
  uint8_t model = 0, gps = 0;
  if (argc != 3 || (runs = atoi(argv[2])) < 1) {
    fprintf(stderr, "usage: %s CAPTURE.pcap RUNS\n", argv[0]);
    return 1;
  }
  f = fopen(argv[1], "rb");
  if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 24 || fseek(f, 0, SEEK_SET) != 0) {
    fprintf(stderr, "%s: cannot read\n", argv[1]);
    return 2;
  }
  data = malloc((size_t)size);
  if (data == NULL || fread(data, 1, (size_t)size, f) != (size_t)size || le32(data) != 0xA1B2C3D4u) {
    fprintf(stderr, "%s: not a little-endian classic pcap\n", argv[1]);
    return 2;
  }
  fclose(f);
  payload = malloc(sizeof *payload * ((size_t)size / 60 + 1));
  length = malloc(sizeof *length * ((size_t)size / 60 + 1));
  while (off + 16 <= (size_t)size) { /* Ethernet, IPv4, UDP */
    const size_t incl = le32(data + off + 8);
    const uint8_t* fr = data + off + 16;
    off += 16 + incl;
    if (off > (size_t)size || incl < 42 || fr[12] != 0x08 || fr[13] != 0x00 || fr[23] != 17) continue;
    {
      const size_t udp = 14 + (size_t)(fr[14] & 0x0F) * 4;
      const size_t ulen = (size_t)fr[udp + 4] << 8 | fr[udp + 5];
      payload[n] = fr + udp + 8;
      length[n] = ulen - 8;
      ++n;
    }
  }
  if (n == 0 || hesai_identify(payload[0], length[0], &model, &gps) != HESAI_ERROR_ok || gps ||
      hesai_decoder_init(&decoder, (hesai_model)model) != HESAI_ERROR_ok) {
    fprintf(stderr, "%s: no point-cloud packet first\n", argv[1]);
    return 2;
  }
  hot.x = hx; hot.y = hy; hot.z = hz; hot.time_ns = ht; hot.intensity = hi; hot.channel = hc; hot.return_index = hr;
  hot.capacity = 400;
  {
    const size_t most = n * hesai_model_max_points((hesai_model)model);
    x = malloc(most * 4); y = malloc(most * 4); z = malloc(most * 4); t = malloc(most * 8);
    in = malloc(most); ch = malloc(most); re = malloc(most); pk = malloc(most * 8);
    if (!x || !y || !z || !t || !in || !ch || !re || !pk) return 2;
    memset(x, 1, most * 4); memset(y, 1, most * 4); memset(z, 1, most * 4); memset(t, 1, most * 8); /* not 0: malloc + memset 0 may become calloc, which touches nothing */
    memset(in, 1, most); memset(ch, 1, most); memset(re, 1, most); memset(pk, 1, most * 8);
  }
  printf("{\"packets\": %lu", (unsigned long)n);
  for (k = 0; k < 2; ++k) {
    printf(k == 0 ? ", \"hot_ns\": [" : "], \"whole_ns\": [");
    for (r = 0; r < runs; ++r) {
      size_t at = 0;
      double t0, t1;
      t0 = now_ns();
      for (i = 0; i < n; ++i) {
        hesai_packet_info info;
        size_t count = 0, j;
        hesai_point_columns cols = hot;
        if (k == 1) {
          cols.x = x + at; cols.y = y + at; cols.z = z + at; cols.intensity = in + at; cols.channel = ch + at;
          cols.return_index = re + at;
        }
        if (hesai_decoder_decode_columns(&decoder, payload[i], length[i], &info, &cols, &count) != HESAI_ERROR_ok) {
          fprintf(stderr, "packet %lu does not decode\n", (unsigned long)i);
          return 2;
        }
        if (k == 1) {
          for (j = 0; j < count; ++j) t[at + j] = info.time_ns + ht[j];
          for (j = 0; j < count; ++j) pk[at + j] = i;
          at += count;
        } else {
          points += count;
        }
      }
      t1 = now_ns();
      if (k == 1) {
        volatile float sink = x[at / 2];
        (void)sink;
      }
      printf("%s%.1f", r ? ", " : "", (t1 - t0) / (double)n);
    }
  }
  printf("], \"points\": %lu}\n", (unsigned long)(points / (size_t)runs));
  free(x); free(y); free(z); free(t); free(in); free(ch); free(re); free(pk);
  free(payload);
  free(length);
  free(data);
  return 0;
}
