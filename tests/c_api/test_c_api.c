/* The C interface used from C: compiled as C99 with -Wall -Wextra -Werror -pedantic. The driver
 * (driver.cpp) gives it the bundled captures' bytes; expected values here come from the packet
 * bytes by the manuals' layouts, or are typed in from hesai.h's contract. */
#include "c_api_test.h"

#include <stdio.h>
#include <string.h>

static hesai_decoder decoder;
static hesai_calibration_scratch scratch;
static hesai_point points[HESAI_MAX_POINTS_PER_PACKET];
static uint8_t copy[1500];
static int failures;

static void expect(int ok, const char* what, int line) {
  if (!ok) {
    ++failures;
    fprintf(stderr, "test_c_api.c:%d: failed: %s\n", line, what);
  }
}
#define EXPECT(cond) expect((cond) != 0, #cond, __LINE__)

/* Compares by the error's name: hesai_error_name() is under test too. */
static void expect_error(hesai_error got, const char* want, int line) {
  if (strcmp(hesai_error_name(got), want) != 0) {
    ++failures;
    fprintf(stderr, "test_c_api.c:%d: error %s, expected %s\n", line, hesai_error_name(got), want);
  }
}
#define EXPECT_ERROR(call, want) expect_error((call), (want), __LINE__)

static int take_failures(void) {
  const int n = failures;
  failures = 0;
  return n;
}

/* ---- What the driver compares with the C++ decoder ------------------------------------------- */

hesai_error c_open_csv(hesai_model model, const uint8_t* angles, size_t angles_size, const uint8_t* firetimes,
                       size_t firetimes_size) {
  hesai_error e = hesai_decoder_init(&decoder, model);
  if (e == HESAI_ERROR_ok && angles != NULL)
    e = hesai_decoder_set_angles_csv(&decoder, angles, angles_size, &scratch, NULL);
  if (e == HESAI_ERROR_ok && firetimes != NULL)
    e = hesai_decoder_set_firetimes_csv(&decoder, firetimes, firetimes_size, &scratch, NULL);
  return e;
}

hesai_error c_open_arrays(hesai_model model, const double* elevation_deg, const double* azimuth_deg,
                          const double* loop1_us, const double* loop2_us, size_t channels) {
  hesai_error e = hesai_decoder_init(&decoder, model);
  if (e == HESAI_ERROR_ok) e = hesai_decoder_set_angles(&decoder, elevation_deg, azimuth_deg, channels, &scratch);
  if (e == HESAI_ERROR_ok) e = hesai_decoder_set_firetimes(&decoder, loop1_us, loop2_us, channels, &scratch);
  return e;
}

hesai_error c_set_rotation(int rotation) { return hesai_decoder_set_rotation(&decoder, rotation); }

hesai_error c_feed(const uint8_t* payload, size_t size, hesai_packet_info* info, const hesai_point** out,
                   size_t* count) {
  uint8_t model = 0, is_gps = 0;
  const hesai_error e = hesai_identify(payload, size, &model, &is_gps);
  *out = points;
  *count = 0;
  if (e == HESAI_ERROR_ok && is_gps) return hesai_decoder_update_gps(&decoder, payload, size);
  /* Room for exactly the decoder's model, not for the largest of all models. */
  return hesai_decoder_decode(&decoder, payload, size, info, points,
                              hesai_model_max_points(hesai_decoder_model(&decoder)), count);
}

struct align_decoder { char c; hesai_decoder t; };
struct align_scratch { char c; hesai_calibration_scratch t; };
struct align_info { char c; hesai_packet_info t; };

size_t c_layout(size_t* out, size_t room) {
  const size_t v[] = {sizeof(hesai_point), offsetof(hesai_point, x), offsetof(hesai_point, y),
                      offsetof(hesai_point, z), offsetof(hesai_point, distance_m), offsetof(hesai_point, azimuth_deg),
                      offsetof(hesai_point, elevation_deg), offsetof(hesai_point, time_ns),
                      offsetof(hesai_point, intensity), offsetof(hesai_point, channel),
                      offsetof(hesai_point, return_index), offsetof(hesai_point, confidence),
                      offsetof(hesai_point, block), sizeof(hesai_decoder), offsetof(struct align_decoder, t),
                      sizeof(hesai_calibration_scratch), offsetof(struct align_scratch, t), sizeof(hesai_packet_info),
                      offsetof(struct align_info, t)};
  const size_t n = sizeof v / sizeof v[0];
  size_t i;
  for (i = 0; i < n && i < room; ++i) out[i] = v[i];
  return n;
}

#define OFFSET_INFO(type, name) offsetof(hesai_packet_info, name),
#define OFFSET_INFO_ARRAY(type, name, count) offsetof(hesai_packet_info, name),
#define OFFSET_INFO_NESTED(type, name, list) offsetof(hesai_packet_info, name),
#define OFFSET_DATE_TIME(type, name) offsetof(hesai_date_time, name),
#define OFFSET_SAFETY(type, name) offsetof(hesai_functional_safety, name),
size_t c_packet_info_layout(size_t* out, size_t room) {
  const size_t v[] = {HESAI_PACKET_INFO_LIST(OFFSET_INFO, OFFSET_INFO_ARRAY, OFFSET_INFO_NESTED)
                          HESAI_DATE_TIME_LIST(OFFSET_DATE_TIME) HESAI_FUNCTIONAL_SAFETY_LIST(OFFSET_SAFETY)
                              sizeof(hesai_packet_info),
                      sizeof(hesai_date_time), sizeof(hesai_functional_safety)};
  const size_t n = sizeof v / sizeof v[0];
  size_t i;
  for (i = 0; i < n && i < room; ++i) out[i] = v[i];
  return n;
}
#undef OFFSET_INFO
#undef OFFSET_INFO_ARRAY
#undef OFFSET_INFO_NESTED
#undef OFFSET_DATE_TIME
#undef OFFSET_SAFETY

/* ---- Errors ------------------------------------------------------------------------------------ */

/* QT128C2X protocol 3.2 (manual section 3.1.2): a 12-byte header (flags at byte 11), then two
 * blocks of a 2-byte azimuth and 128 units of 4 bytes (distance u16, reflectivity, confidence). */
static size_t qt128_points(const uint8_t* p) {
  size_t n = 0, b, u;
  for (b = 0; b < 2; ++b)
    for (u = 0; u < 128; ++u) {
      const uint8_t* q = p + 12 + b * 514 + 2 + u * 4;
      if ((unsigned)(q[0] | q[1] << 8) >= 2) ++n; /* distance 1 is a marker, not a point */
    }
  return n;
}

int c_check_errors(const uint8_t* qt128, size_t size) {
  hesai_packet_info info;
  size_t count = 99;
  uint8_t model = 0, is_gps = 1;

  EXPECT(size <= sizeof copy);
  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x), "ok");
  EXPECT(hesai_decoder_model(&decoder) == HESAI_MODEL_qt128c2x);

  /* The packet as captured: every unit with a distance is a point; header fields as sent. */
  EXPECT_ERROR(hesai_identify(qt128, size, &model, &is_gps), "ok");
  EXPECT(model == HESAI_MODEL_qt128c2x && is_gps == 0);
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info, points, 256, &count), "ok");
  EXPECT(count == qt128_points(qt128));
  EXPECT(info.model == HESAI_MODEL_qt128c2x && info.blocks == 2 && info.flags == qt128[11]);
  EXPECT(info.returns == qt128[10] && info.dis_unit_mm == qt128[9]);
  EXPECT(points[0].channel >= 1 && points[0].channel <= 128 && points[0].block == 0);
  EXPECT_ERROR(hesai_decoder_validate(&decoder, qt128, size, &info), "ok");
  EXPECT(info.model == HESAI_MODEL_qt128c2x);

  /* Lengths: too short for any header; one byte short of what the flags announce; nothing. */
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, 10, &info, points, 256, &count), "bad_length");
  EXPECT(count == 0);
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size - 1, &info, points, 256, &count), "flags_length_mismatch");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, NULL, 0, &info, points, 256, &count), "bad_length");

  /* A body byte flipped: CRC1 covers the body. */
  memcpy(copy, qt128, size);
  copy[100] ^= 0x01;
  count = 99;
  EXPECT_ERROR(hesai_decoder_decode(&decoder, copy, size, &info, points, 256, &count), "crc_body");
  EXPECT(count == 0);

  /* Capacity: 2 x 128 is the QT128's worst case; one less is refused before the packet is read,
   * and nothing is written. */
  points[0].distance_m = -1.0f;
  count = 99;
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info, points, 255, &count), "buffer_too_small");
  EXPECT(count == 0 && points[0].distance_m == -1.0f);
  EXPECT_ERROR(hesai_decoder_decode(&decoder, copy, size, &info, points, 0, &count), "buffer_too_small");
  EXPECT(hesai_model_max_points(HESAI_MODEL_qt128c2x) == 256);

  /* NULL where a pointer is needed. */
  EXPECT_ERROR(hesai_decoder_decode(NULL, qt128, size, &info, points, 256, &count), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info, NULL, 256, &count), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info, points, 256, NULL), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, NULL, size, &info, points, 256, &count), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, NULL, points, 256, &count), "ok"); /* info optional */
  EXPECT_ERROR(hesai_decoder_validate(&decoder, qt128, size, NULL), "invalid_argument");
  EXPECT_ERROR(hesai_identify(qt128, size, NULL, &is_gps), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_init(NULL, HESAI_MODEL_qt128c2x), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_session_key(&decoder, NULL), "invalid_argument");
  EXPECT(hesai_decoder_model(NULL) == HESAI_MODEL_unknown);

  /* Another model's decoder; then no model at all. */
  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_pandar64), "ok");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info, points, 384, &count), "model_mismatch");
  EXPECT_ERROR(hesai_decoder_init(&decoder, (hesai_model)9), "invalid_argument");
  EXPECT(hesai_decoder_model(&decoder) == HESAI_MODEL_unknown);
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info, points, 400, &count), "model_mismatch");

  /* Names. */
  EXPECT(strcmp(hesai_error_name(HESAI_ERROR_ok), "ok") == 0);
  EXPECT(strcmp(hesai_error_name(HESAI_ERROR_COUNT), "unknown") == 0);
  EXPECT(strcmp(hesai_error_name((hesai_error)-1), "unknown") == 0);
  EXPECT(strcmp(hesai_error_name((hesai_error)(HESAI_ERROR_crc_body + 256)), "unknown") == 0);
  EXPECT(strcmp(hesai_model_name(HESAI_MODEL_qt128c2x), "QT128C2X") == 0);
  EXPECT(strcmp(hesai_model_name(HESAI_MODEL_pandar40p), "Pandar40P") == 0);
  EXPECT(strcmp(hesai_model_name((hesai_model)77), "unknown") == 0);
  EXPECT(hesai_model_channels(HESAI_MODEL_pandar40) == 40 && hesai_model_channels(HESAI_MODEL_pandar64) == 64 &&
         hesai_model_channels(HESAI_MODEL_qt128c2x) == 128 && hesai_model_channels(HESAI_MODEL_unknown) == 0);
  EXPECT(hesai_model_max_points(HESAI_MODEL_pandar40) == 400 && hesai_model_max_points(HESAI_MODEL_pandar40p) == 400 &&
         hesai_model_max_points(HESAI_MODEL_pandar64) == 384 && hesai_model_max_points(HESAI_MODEL_unknown) == 0);
  return take_failures();
}

/* ---- Session keys (QT128 signatures) ------------------------------------------------------------ */

static hesai_error decode_into(const uint8_t* p, size_t size, hesai_packet_info* info, size_t* count) {
  return hesai_decoder_decode(&decoder, p, size, info, points, 256, count);
}

int c_check_keys(const uint8_t* qt128, const uint8_t* qt128_signed, size_t size, const uint8_t key[32]) {
  /* `key` is a fixed vector computed outside this code base from this secret and these randoms. */
  static const char secret[] = "0123456789abcdef";
  uint8_t lidar[32], client[32], derived[32], wrong[32];
  hesai_packet_info info;
  size_t count = 0;
  int i;
  for (i = 0; i < 32; ++i) {
    lidar[i] = (uint8_t)i;
    client[i] = (uint8_t)(0x20 + i);
  }
  EXPECT_ERROR(hesai_session_key_derive((const uint8_t*)secret, sizeof secret - 1, lidar, client, derived), "ok");
  EXPECT(memcmp(derived, key, 32) == 0);
  memset(wrong, 0xEE, sizeof wrong);
  EXPECT_ERROR(hesai_session_key_derive((const uint8_t*)secret, 7, lidar, client, wrong), "invalid_argument");
  EXPECT_ERROR(hesai_session_key_derive((const uint8_t*)secret, 33, lidar, client, wrong), "invalid_argument");
  EXPECT(wrong[0] == 0xEE && wrong[31] == 0xEE); /* untouched */

  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x), "ok");
  /* No key: nothing is checked. */
  EXPECT_ERROR(decode_into(qt128, size, &info, &count), "ok");
  EXPECT(info.signature == HESAI_SIGNATURE_not_signed);
  EXPECT_ERROR(decode_into(qt128_signed, size, &info, &count), "ok");
  EXPECT(info.signature == HESAI_SIGNATURE_unverified);

  /* The key: the signed packet verifies; the unsigned one is refused unless allowed. */
  EXPECT_ERROR(hesai_decoder_set_session_key(&decoder, derived), "ok");
  memset(derived, 0, sizeof derived); /* the decoder keeps its own copy */
  EXPECT_ERROR(decode_into(qt128_signed, size, &info, &count), "ok");
  EXPECT(info.signature == HESAI_SIGNATURE_valid && count > 0);
  EXPECT_ERROR(decode_into(qt128, size, &info, &count), "signature_missing");
  EXPECT(count == 0);
  EXPECT_ERROR(hesai_decoder_set_allow_unsigned(&decoder, 1), "ok");
  EXPECT_ERROR(decode_into(qt128, size, &info, &count), "ok");
  EXPECT(info.signature == HESAI_SIGNATURE_accepted_unsigned);
  EXPECT_ERROR(hesai_decoder_set_allow_unsigned(&decoder, 0), "ok");
  EXPECT_ERROR(decode_into(qt128, size, &info, &count), "signature_missing");

  /* A signature byte flipped, then another key. */
  memcpy(copy, qt128_signed, size);
  copy[size - 1] ^= 0x80;
  EXPECT_ERROR(decode_into(copy, size, &info, &count), "signature_invalid");
  memcpy(wrong, key, 32);
  wrong[0] ^= 1;
  EXPECT_ERROR(hesai_decoder_set_session_key(&decoder, wrong), "ok");
  EXPECT_ERROR(decode_into(qt128_signed, size, &info, &count), "signature_invalid");

  /* Cleared: as before any key. */
  EXPECT_ERROR(hesai_decoder_clear_session_key(&decoder), "ok");
  EXPECT_ERROR(decode_into(qt128_signed, size, &info, &count), "ok");
  EXPECT(info.signature == HESAI_SIGNATURE_unverified);
  EXPECT_ERROR(decode_into(qt128, size, &info, &count), "ok");
  EXPECT(info.signature == HESAI_SIGNATURE_not_signed);
  return take_failures();
}

/* ---- Pandar40 time from a GPS packet ------------------------------------------------------------ */

/* A Pandar40 GPS packet (Pandar40 manual, GPS data format table): FF EE, the date and time as 12
 * ASCII digits at byte 2 (year, month, day, second, minute, hour; each units digit first), 0xDF
 * filler at bytes 95..505, location 'A' at 506, PPS locked at 507. */
static void pandar40_gps(uint8_t* g, const char* digits) {
  memset(g, 0, 512);
  g[0] = 0xFF;
  g[1] = 0xEE;
  memcpy(g + 2, digits, 12);
  memset(g + 95, 0xDF, 506 - 95);
  g[506] = 'A';
  g[507] = 1;
}

int c_check_pandar40_gps(const uint8_t* pandar40, size_t size) {
  /* The tail's timestamp (Pandar40 manual section 3.1.2: bytes 1250..1253 of the 1256, little
   * endian) counts us from the top of the hour. */
  const int64_t ts = (int64_t)((uint32_t)pandar40[1250] | (uint32_t)pandar40[1251] << 8 |
                               (uint32_t)pandar40[1252] << 16 | (uint32_t)pandar40[1253] << 24);
  /* 2017-09-06 16:00:00 UTC = 1504714786 (16:19:46 that day) - 19 x 60 - 46. */
  const int64_t hour_ns = 1504713600LL * 1000000000LL;
  hesai_packet_info info;
  size_t count = 0;
  uint8_t gps[512], model = 9, is_gps = 0;

  EXPECT(size == 1256 && ts < 1000000);
  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_pandar40), "ok");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, pandar40, size, &info, points, 400, &count), "ok");
  EXPECT(info.time_reference == HESAI_TIME_hour_relative && info.time_ns == ts * 1000);

  /* 2017-09-06 16:00:00: year 17, month 09, day 06, second 00, minute 00, hour 16. */
  pandar40_gps(gps, "719060000061");
  EXPECT_ERROR(hesai_identify(gps, sizeof gps, &model, &is_gps), "ok");
  EXPECT(is_gps == 1 && model == HESAI_MODEL_unknown);
  EXPECT_ERROR(hesai_decoder_update_gps(&decoder, gps, 511), "bad_length");
  gps[200] = 0;
  EXPECT_ERROR(hesai_decoder_update_gps(&decoder, gps, sizeof gps), "bad_magic");
  pandar40_gps(gps, "7190600000x1");
  EXPECT_ERROR(hesai_decoder_update_gps(&decoder, gps, sizeof gps), "bad_gps_field");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, pandar40, size, &info, points, 400, &count), "ok");
  EXPECT(info.time_reference == HESAI_TIME_hour_relative); /* the refused packets changed nothing */

  pandar40_gps(gps, "719060000061");
  EXPECT_ERROR(hesai_decoder_update_gps(&decoder, gps, sizeof gps), "ok");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, pandar40, size, &info, points, 400, &count), "ok");
  EXPECT(info.time_reference == HESAI_TIME_utc && info.time_ns == hour_ns + ts * 1000);
  EXPECT(info.date_time.year == 2017 && info.date_time.month == 9 && info.date_time.day == 6 &&
         info.date_time.hour == 16);
  return take_failures();
}

/* ---- Calibration errors -------------------------------------------------------------------------- */

static hesai_error angles_text(const char* text, uint32_t* line) {
  return hesai_decoder_set_angles_csv(&decoder, (const uint8_t*)text, strlen(text), &scratch, line);
}

int c_check_calibration_errors(void) {
  static double elevation[64], azimuth[64], loop1[128], loop2[128];
  uint32_t line = 99;

  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_pandar64), "ok");
  /* CSV: the line of the first bad row (1-based), 0 when the file is refused as a whole. */
  EXPECT_ERROR(angles_text("Laser id,Elevation,Azimuth\n1,abc,0\n", &line), "calib_bad_number");
  EXPECT(line == 2);
  EXPECT_ERROR(angles_text("Channel,Height\n", &line), "calib_bad_header");
  EXPECT(line == 1);
  EXPECT_ERROR(angles_text("Laser id,Elevation,Azimuth\n1,1.5,0.25,7\n", &line), "calib_bad_row");
  EXPECT(line == 2);
  /* One row of the Pandar64's 64: the missing row is the line after the last. */
  EXPECT_ERROR(angles_text("Laser id,Elevation,Azimuth\n1,1.5,0.25\n", &line), "calib_channel_count");
  EXPECT(line == 3);
  EXPECT_ERROR(angles_text("Laser id,Elevation,Azimuth\n1,1.5,0.25\n", NULL), "calib_channel_count");
  EXPECT_ERROR(hesai_decoder_set_angles_csv(&decoder, (const uint8_t*)"x", 1, NULL, &line), "invalid_argument");
  EXPECT(line == 0);
  EXPECT_ERROR(hesai_decoder_set_firetimes_csv(&decoder, (const uint8_t*)"Laser,Time\n", 11, &scratch, &line),
               "calib_bad_header");

  /* Arrays: the model's channel count, angles and firing times in range. */
  EXPECT_ERROR(hesai_decoder_set_angles(&decoder, elevation, azimuth, 64, &scratch), "ok");
  EXPECT_ERROR(hesai_decoder_set_angles(&decoder, elevation, azimuth, 63, &scratch), "calib_channel_count");
  EXPECT_ERROR(hesai_decoder_set_angles(&decoder, elevation, azimuth, 200, &scratch), "calib_channel_count");
  elevation[4] = 90.5;
  EXPECT_ERROR(hesai_decoder_set_angles(&decoder, elevation, azimuth, 64, &scratch), "invalid_argument");
  elevation[4] = 0;
  azimuth[63] = -360.5;
  EXPECT_ERROR(hesai_decoder_set_angles(&decoder, elevation, azimuth, 64, &scratch), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_angles(&decoder, elevation, NULL, 64, &scratch), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_firetimes(&decoder, loop1, NULL, 64, &scratch), "ok");
  loop1[10] = -1000.5;
  EXPECT_ERROR(hesai_decoder_set_firetimes(&decoder, loop1, NULL, 64, &scratch), "invalid_argument");
  loop1[10] = 0;
  /* The QT128 fires two sequences: a one-loop table is refused. */
  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x), "ok");
  EXPECT_ERROR(hesai_decoder_set_firetimes(&decoder, loop1, NULL, 128, &scratch), "calib_channel_count");
  EXPECT_ERROR(hesai_decoder_set_firetimes(&decoder, loop1, loop2, 128, &scratch), "ok");
  EXPECT_ERROR(hesai_decoder_set_firetime_correction(&decoder, 0), "ok");
  EXPECT_ERROR(hesai_decoder_set_firetime_correction(NULL, 0), "invalid_argument");
  return take_failures();
}

/* ---- Sensor settings: channel configuration, reflectivity mapping ------------------------------- */

int c_check_sensor_settings(const uint8_t* qt128_custom, size_t size, const uint8_t* config, size_t config_size,
                            size_t want_points, const uint8_t* pandar64, size_t pandar64_size) {
  static const char bad_channel[] = "EEFF,1,1\nLaserNum,2,BlockNum,2\nLoop1,Loop2\n1,2\n3,129\n";
  static const char three_blocks[] = "EEFF,1,1\nLaserNum,1,BlockNum,3\nLoop1\n5\n";
  hesai_packet_info info;
  size_t count = 99;
  uint32_t line = 99;

  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x), "ok");
  EXPECT_ERROR(decode_into(qt128_custom, size, &info, &count), "channel_config_required");
  EXPECT(count == 0);
  EXPECT_ERROR(hesai_decoder_set_channel_config_csv(&decoder, (const uint8_t*)bad_channel, strlen(bad_channel),
                                                    &scratch, &line),
               "calib_bad_channel");
  EXPECT(line == 5);
  EXPECT_ERROR(hesai_decoder_set_channel_config_csv(&decoder, (const uint8_t*)three_blocks, strlen(three_blocks),
                                                    &scratch, &line),
               "channel_config_mismatch");
  EXPECT(line == 0);
  EXPECT_ERROR(hesai_decoder_set_channel_config_csv(&decoder, config, config_size, NULL, &line), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_channel_config_csv(&decoder, config, config_size, &scratch, &line), "ok");
  EXPECT_ERROR(decode_into(qt128_custom, size, &info, &count), "ok");
  EXPECT(count == want_points);
  EXPECT(info.flags == 0x5D);
  EXPECT_ERROR(hesai_decoder_clear_channel_config(&decoder), "ok");
  EXPECT_ERROR(decode_into(qt128_custom, size, &info, &count), "channel_config_required");
  EXPECT_ERROR(hesai_decoder_clear_channel_config(NULL), "invalid_argument");
  /* The mapping is the Pandar64's only. */
  EXPECT_ERROR(hesai_decoder_set_reflectivity(&decoder, HESAI_REFLECTIVITY_nonlinear), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_reflectivity(&decoder, HESAI_REFLECTIVITY_raw), "ok");

  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_pandar64), "ok");
  EXPECT_ERROR(hesai_decoder_set_channel_config_csv(&decoder, config, config_size, &scratch, &line),
               "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_reflectivity(&decoder, 2), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_set_reflectivity(NULL, HESAI_REFLECTIVITY_raw), "invalid_argument");
  {
    /* Field value 100 is 15.87 % in Appendix D: 16 with the mapping, 100 without. */
    uint8_t p[1198];
    size_t i, raw = 0, mapped = 0;
    if (pandar64_size > sizeof p) return take_failures() + 1;
    memcpy(p, pandar64, pandar64_size);
    p[8 + 2] = 0xE8; /* block 1, channel 1: distance 1000 (u16 LE), then the reflectivity byte */
    p[8 + 3] = 0x03;
    p[8 + 4] = 100;
    EXPECT_ERROR(hesai_decoder_decode(&decoder, p, pandar64_size, &info, points, 384, &count), "ok");
    for (i = 0; i < count; ++i)
      if (points[i].block == 0 && points[i].channel == 1) raw = points[i].intensity;
    EXPECT_ERROR(hesai_decoder_set_reflectivity(&decoder, HESAI_REFLECTIVITY_nonlinear), "ok");
    EXPECT_ERROR(hesai_decoder_decode(&decoder, p, pandar64_size, &info, points, 384, &count), "ok");
    for (i = 0; i < count; ++i)
      if (points[i].block == 0 && points[i].channel == 1) mapped = points[i].intensity;
    EXPECT(raw == 100);
    EXPECT(mapped == 16);
  }
  return take_failures();
}

int c_check_columns(const uint8_t* qt128, size_t size) {
  static float x[256], y[256], z[256];
  static int32_t t[256];
  static uint8_t intensity[256], channel[256], ret[256];
  hesai_point_columns columns = {x, y, z, t, intensity, channel, ret, 256};
  hesai_packet_info info, info_points;
  size_t count = 99, want = 0, i;

  EXPECT_ERROR(hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x), "ok");
  EXPECT_ERROR(hesai_decoder_decode(&decoder, qt128, size, &info_points, points, 256, &want), "ok");
  EXPECT_ERROR(hesai_decoder_decode_columns(&decoder, qt128, size, &info, &columns, &count), "ok");
  EXPECT(count == want && want > 0);
  for (i = 0; i < count && i < want; ++i) {
    EXPECT(x[i] == points[i].x && y[i] == points[i].y && z[i] == points[i].z);
    EXPECT(info.time_ns + t[i] == points[i].time_ns);
    EXPECT(intensity[i] == points[i].intensity && channel[i] == points[i].channel &&
           ret[i] == points[i].return_index);
  }

  /* Room for one point less than the QT128's 2 x 128; a missing column; missing arguments. */
  columns.capacity = 255;
  count = 99;
  EXPECT_ERROR(hesai_decoder_decode_columns(&decoder, qt128, size, &info, &columns, &count), "buffer_too_small");
  EXPECT(count == 0);
  columns.capacity = 256;
  columns.z = NULL;
  EXPECT_ERROR(hesai_decoder_decode_columns(&decoder, qt128, size, &info, &columns, &count), "invalid_argument");
  columns.z = z;
  EXPECT_ERROR(hesai_decoder_decode_columns(&decoder, qt128, size, &info, NULL, &count), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode_columns(&decoder, qt128, size, &info, &columns, NULL), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode_columns(NULL, qt128, size, &info, &columns, &count), "invalid_argument");
  EXPECT_ERROR(hesai_decoder_decode_columns(&decoder, qt128, size, NULL, &columns, &count), "ok"); /* info optional */
  return take_failures();
}

/* ---- Stream health ---------------------------------------------------------------------------- */

static hesai_health health;

hesai_error c_health_run(hesai_model model, const uint8_t* bytes, const size_t* sizes, size_t n, int returns,
                         hesai_health_counts* counts, uint64_t* points_given, int* failures_out) {
  hesai_error first = HESAI_ERROR_ok;
  size_t i, at = 0, count = 0;
  uint32_t lost = 0;
  hesai_packet_info info;
  EXPECT_ERROR(hesai_health_init(NULL, HESAI_ROTATION_clockwise), "invalid_argument");
  EXPECT_ERROR(hesai_health_init(&health, 2), "invalid_argument");
  EXPECT_ERROR(hesai_health_counts_get(NULL, counts), "invalid_argument");
  EXPECT_ERROR(hesai_health_init(&health, HESAI_ROTATION_clockwise), "ok");
  EXPECT_ERROR(hesai_decoder_init(&decoder, model), "ok");
  EXPECT_ERROR(hesai_decoder_decode_health(&decoder, bytes, sizes[0], &info, points, HESAI_MAX_POINTS_PER_PACKET, &count,
                                           2, &health, &lost),
               "invalid_argument");
  *points_given = 0;
  for (i = 0; i < n; ++i) {
    const hesai_error e = hesai_decoder_decode_health(&decoder, bytes + at, sizes[i], &info, points,
                                                      HESAI_MAX_POINTS_PER_PACKET, &count, returns, &health, &lost);
    if (e != HESAI_ERROR_ok && first == HESAI_ERROR_ok) first = e;
    *points_given += count;
    at += sizes[i];
  }
  EXPECT_ERROR(hesai_health_counts_get(&health, counts), "ok");
  *failures_out = take_failures();
  return first;
}
