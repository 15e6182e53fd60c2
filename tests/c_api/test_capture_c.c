/* hesai_port/hesai_capture.h from C99 (-std=c99 -pedantic, warnings are errors), linked against
 * the shared library libhesai_c: the row layout as the C compiler sees it, the errors of
 * hesai_capture_open, and a whole capture read in small batches with its frame closings; the
 * same capture as columns (hesai_capture_read_columns) against those rows, its bound, its
 * stats JSON, and the layout the library reports. Its one sensor is index 0 in every row, column
 * and closed frame, named by the sender of the file's first record (read here from its bytes).
 * Expected counts: the Pandar64 capture's 2400 packets and 716 622 points (tests/test_golden.cpp,
 * counted again without the library by tests/golden/count_points.py).
 * Usage: hesai_capture_c_test DATA_DIR */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "hesai/hesai.h"
#include "hesai_port/hesai_capture.h"

static int failures = 0;
#define CHECK(cond)                                                       \
  do {                                                                    \
    if (!(cond)) {                                                        \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                         \
    }                                                                     \
  } while (0)

/* The layout python/hesai/_lib.py reads (ROW_DTYPE), as a C compiler lays it out. */
typedef char row_size_is_56[sizeof(hesai_capture_row) == 56 ? 1 : -1];
typedef char row_offsets[offsetof(hesai_capture_row, time_ns) == 16 && offsetof(hesai_capture_row, azimuth_deg) == 24 &&
                                 offsetof(hesai_capture_row, z) == 44 && offsetof(hesai_capture_row, block) == 48 &&
                                 offsetof(hesai_capture_row, intensity) == 51 && offsetof(hesai_capture_row, sensor) == 52
                             ? 1
                             : -1];

/* The sender of the capture's first record, "a.b.c.d:port", read from the file's bytes (classic
 * little-endian pcap, Ethernet, IPv4, UDP): what the CSV's sensor column says. */
static int first_sender(const char* path, char* out, size_t size) {
  unsigned char b[24 + 16 + 64];
  size_t ip = 24 + 16 + 14, udp;
  FILE* f = fopen(path, "rb");
  if (f == NULL) return 0;
  if (fread(b, 1, sizeof b, f) != sizeof b) {
    fclose(f);
    return 0;
  }
  fclose(f);
  udp = ip + (size_t)(b[ip] & 0x0F) * 4;
  snprintf(out, size, "%u.%u.%u.%u:%u", b[ip + 12], b[ip + 13], b[ip + 14], b[ip + 15], (unsigned)(b[udp] << 8 | b[udp + 1]));
  return 1;
}

static hesai_capture_row rows[1000];

/* Every row of the Pandar64 capture, for the columns to be compared with. */
#define P64_POINTS 716622
static hesai_capture_row all_rows[P64_POINTS];
static float cx[P64_POINTS + 8000], cy[P64_POINTS + 8000], cz[P64_POINTS + 8000];
static int64_t ct[P64_POINTS + 8000];
static uint8_t ci[P64_POINTS + 8000], cc[P64_POINTS + 8000], cr[P64_POINTS + 8000];
static uint64_t cp[P64_POINTS + 8000];
static uint16_t cs[P64_POINTS + 8000];
static char json[1 << 16];

int main(int argc, char** argv) {
  char path[1024], cal[1024], message[256], sender[64];
  hesai_capture* c = NULL;
  hesai_capture_options o;
  size_t count = 0, total = 0, i;
  uint64_t closed = 0, last_closed = 0, frames = 0;
  uint16_t closed_sensor = 0;
  int st;
  (void)sizeof(row_size_is_56);
  (void)sizeof(row_offsets);
  if (argc != 2) {
    fprintf(stderr, "usage: %s DATA_DIR\n", argv[0]);
    return 2;
  }
  snprintf(path, sizeof path, "%s/pandar64_dual.pcap", argv[1]);
  snprintf(cal, sizeof cal, "%s/calibration/pandar40p_unit_a_angles.csv", argv[1]);

  /* Errors: the program's exit statuses, with a message. */
  hesai_capture_default_options(&o);
  CHECK(o.rotation == -1 && o.firetime_azimuth == 1 && o.end_packet == UINT64_MAX && o.max_range_m == 1e9f);
  message[0] = '\0';
  CHECK(hesai_capture_open("/nonexistent/x.pcap", &o, &c, message, sizeof message) == 2 && c == NULL);
  CHECK(strlen(message) > 0);
  CHECK(hesai_capture_open(NULL, &o, &c, message, sizeof message) == 1 && c == NULL);
  CHECK(hesai_capture_open(path, &o, NULL, message, sizeof message) == 1);
  o.cut_angle_deg = 360.0f;
  CHECK(hesai_capture_open(path, &o, &c, message, sizeof message) == 1 && c == NULL);
  o.cut_angle_deg = 0.0f;
  /* A 40-channel file for a 64-channel capture: applied at the first packet, so reading fails. */
  o.calibration = cal;
  CHECK(hesai_capture_open(path, &o, &c, message, 8) == 0 && c != NULL);
  CHECK(hesai_capture_read(c, rows, 1000, &count, &closed, &closed_sensor, message, 8) == 1 && count == 0);
  CHECK(strlen(message) == 7); /* cut to the buffer, terminated */
  hesai_capture_close(c);
  hesai_capture_close(NULL);

  /* The whole capture, 1000 rows at most per call: one sensor, index 0, named by its sender. */
  CHECK(first_sender(path, sender, sizeof sender));
  CHECK(hesai_capture_open(path, NULL, &c, message, sizeof message) == 0 && c != NULL);
  CHECK(hesai_capture_sensors(c) == 0 && hesai_capture_sensor_name(c, 0) == NULL);
  CHECK(hesai_capture_sensors(NULL) == 0 && hesai_capture_sensor_name(NULL, 0) == NULL);
  CHECK(hesai_capture_read(c, rows, 0, &count, &closed, &closed_sensor, message, sizeof message) == 1);
  CHECK(hesai_capture_read(c, NULL, 10, &count, &closed, &closed_sensor, message, sizeof message) == 1);
  CHECK(hesai_capture_read(NULL, rows, 10, &count, &closed, &closed_sensor, message, sizeof message) == 1);
  for (;;) {
    st = hesai_capture_read(c, rows, 1000, &count, &closed, &closed_sensor, message, sizeof message);
    CHECK(st == 0);
    if (st != 0 || (count == 0 && closed == 0)) break;
    CHECK(count <= 1000);
    for (i = 0; i < count; ++i) {
      /* Rows after frame f closed belong to later frames. */
      CHECK(rows[i].frame > last_closed);
      CHECK(rows[i].packet < 2400);
      CHECK(rows[i].channel >= 1 && rows[i].channel <= 64 && rows[i].return_index <= 1);
      CHECK(rows[i].azimuth_deg >= 0.0f && rows[i].azimuth_deg < 360.0f);
      CHECK(rows[i].sensor == 0);
      if (failures > 20) return 1;
    }
    if (total + count <= P64_POINTS) memcpy(all_rows + total, rows, count * sizeof rows[0]);
    total += count;
    if (closed != 0) {
      CHECK(closed == last_closed + 1); /* frames close in id order */
      CHECK(closed_sensor == 0);
      last_closed = closed;
      ++frames;
    }
  }
  CHECK(total == 716622);
  CHECK(frames >= 2);
  CHECK(hesai_capture_packets(c) == 2400);
  CHECK(hesai_capture_sensors(c) == 1);
  CHECK(hesai_capture_sensor_name(c, 0) != NULL && strcmp(hesai_capture_sensor_name(c, 0), sender) == 0);
  CHECK(hesai_capture_sensor_name(c, 1) == NULL);
  /* At the end it stays at the end. */
  CHECK(hesai_capture_read(c, rows, 1000, &count, &closed, &closed_sensor, message, sizeof message) == 0 && count == 0 && closed == 0);
  hesai_capture_close(c);

  /* The bound: 2400 datagrams, each a Pandar64 point-cloud packet of 6 blocks x 64 channels. */
  {
    uint64_t datagrams = 0, most = 0;
    CHECK(hesai_capture_open(path, NULL, &c, message, sizeof message) == 0);
    CHECK(hesai_capture_bound(c, &datagrams, &most, message, sizeof message) == 0);
    CHECK(datagrams == 2400 && most == 2400u * 384u);
    CHECK(hesai_capture_bound(c, NULL, &most, message, sizeof message) == 1);
    CHECK(hesai_capture_bound(NULL, &datagrams, &most, message, sizeof message) == 1);
    hesai_capture_close(c);
  }

  /* Columns: the rows above, member for member, in calls of at most 5000 points. */
  {
    hesai_capture_columns cols;
    size_t n = 0, got = 0, mismatches = 0;
    cols.x = cx; cols.y = cy; cols.z = cz; cols.time_ns = ct;
    cols.intensity = ci; cols.channel = cc; cols.return_index = cr; cols.packet = cp; cols.sensor = cs;
    memset(cs, 0xFF, sizeof cs);
    cols.capacity = HESAI_CAPTURE_COLUMNS_MIN - 1;
    CHECK(hesai_capture_open(path, NULL, &c, message, sizeof message) == 0);
    CHECK(hesai_capture_read_columns(c, &cols, &got, message, sizeof message) == 1 && got == 0);
    cols.capacity = 5000;
    cols.y = NULL;
    CHECK(hesai_capture_read_columns(c, &cols, &got, message, sizeof message) == 1);
    cols.y = cy;
    CHECK(hesai_capture_read_columns(c, NULL, &got, message, sizeof message) == 1);
    for (;;) {
      hesai_capture_columns at = cols;
      at.x += n; at.y += n; at.z += n; at.time_ns += n; at.intensity += n; at.channel += n;
      at.return_index += n; at.packet += n; at.sensor += n;
      st = hesai_capture_read_columns(c, &at, &got, message, sizeof message);
      CHECK(st == 0);
      if (st != 0 || got == 0 || n + got > P64_POINTS) break;
      CHECK(got <= 5000);
      n += got;
    }
    CHECK(n == P64_POINTS);
    CHECK(hesai_capture_sensors(c) == 1);
    CHECK(hesai_capture_sensor_name(c, 0) != NULL && strcmp(hesai_capture_sensor_name(c, 0), sender) == 0);
    /* A capture read as columns is read one way. */
    CHECK(hesai_capture_read(c, rows, 1000, &count, &closed, &closed_sensor, message, sizeof message) == 1);
    CHECK(hesai_capture_stats_json(c, json, sizeof json, &count, message, sizeof message) == 1);
    hesai_capture_close(c);
    for (i = 0; i < n && i < total; ++i)
      if (cx[i] != all_rows[i].x || cy[i] != all_rows[i].y || cz[i] != all_rows[i].z || ct[i] != all_rows[i].time_ns ||
          ci[i] != all_rows[i].intensity || cc[i] != all_rows[i].channel || cr[i] != all_rows[i].return_index ||
          cp[i] != all_rows[i].packet || cs[i] != all_rows[i].sensor)
        ++mismatches;
    CHECK(mismatches == 0);
    /* Options the columns do not take are refused, not ignored. */
    hesai_capture_default_options(&o);
    o.min_range_m = 1.0f;
    CHECK(hesai_capture_open(path, &o, &c, message, sizeof message) == 0);
    CHECK(hesai_capture_read_columns(c, &cols, &got, message, sizeof message) == 1 && got == 0);
    CHECK(strstr(message, "range") != NULL);
    hesai_capture_close(c);
  }

  /* Stats: the program's JSON object; a buffer too small gets it cut, and its full length. */
  {
    size_t length = 0, again = 0;
    CHECK(hesai_capture_open(path, NULL, &c, message, sizeof message) == 0);
    CHECK(hesai_capture_stats_json(c, json, 16, &length, message, sizeof message) == 0);
    CHECK(strlen(json) == 15 && length > 100);
    CHECK(hesai_capture_stats_json(c, json, sizeof json, &again, message, sizeof message) == 0);
    CHECK(again == length && strlen(json) == length);
    CHECK(json[0] == '{' && json[length - 1] == '}');
    CHECK(strstr(json, "\"packets\":2400,") != NULL && strstr(json, "\"points\":716622,") != NULL);
    CHECK(strstr(json, "\"models\":{\"Pandar64\":2400}") != NULL);
    CHECK(hesai_capture_read(c, rows, 1000, &count, &closed, &closed_sensor, message, sizeof message) == 1);
    CHECK(hesai_capture_stats_json(c, json, 0, &length, message, sizeof message) == 1);
    hesai_capture_close(c);
  }

  /* The layout the library reports is the one this compiler sees. */
  CHECK(hesai_capture_layout(0, NULL) == sizeof(hesai_capture_row));
  CHECK(hesai_capture_layout(0, "time_ns") == offsetof(hesai_capture_row, time_ns));
  CHECK(hesai_capture_layout(0, "return") == offsetof(hesai_capture_row, return_index));
  CHECK(hesai_capture_layout(0, "intensity") == offsetof(hesai_capture_row, intensity));
  CHECK(hesai_capture_layout(0, "sensor") == offsetof(hesai_capture_row, sensor));
  CHECK(hesai_capture_layout(1, "sensor") == (size_t)-1);
  CHECK(hesai_capture_layout(1, NULL) == sizeof(hesai_point));
  CHECK(hesai_capture_layout(1, "confidence") == offsetof(hesai_point, confidence));
  CHECK(hesai_capture_layout(1, "block") == offsetof(hesai_point, block));
  CHECK(hesai_capture_layout(1, "frame") == (size_t)-1);
  CHECK(hesai_capture_layout(0, "nope") == (size_t)-1);
  CHECK(hesai_capture_layout(2, NULL) == (size_t)-1);

  /* The core's C interface is in the same library. */
  CHECK(strcmp(hesai_model_name(HESAI_MODEL_pandar64), "Pandar64") == 0);
  if (failures == 0) printf("hesai_capture.h from C99: %lu rows, %lu frames\n", (unsigned long)total, (unsigned long)frames);
  return failures == 0 ? 0 : 1;
}
