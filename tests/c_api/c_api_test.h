/* The C side of the C interface's test: functions written in C99 (test_c_api.c) that the C++
 * driver (driver.cpp) calls with the bundled captures' bytes. */
#ifndef HESAI_TEST_C_API_H
#define HESAI_TEST_C_API_H

#include <stddef.h>
#include <stdint.h>

#include "hesai/hesai.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sets up the C test's decoder for `model` from the bytes of an angle and a firing-time file
 * (either may be NULL: design values). Returns the first error. */
hesai_error c_open_csv(hesai_model model, const uint8_t* angles, size_t angles_size, const uint8_t* firetimes,
                       size_t firetimes_size);
/* The same from arrays indexed by channel - 1 (loop2_us NULL for one firing sequence). */
hesai_error c_open_arrays(hesai_model model, const double* elevation_deg, const double* azimuth_deg,
                          const double* loop1_us, const double* loop2_us, size_t channels);
/* hesai_decoder_set_rotation on the C test's decoder. */
hesai_error c_set_rotation(int rotation);
/* One UDP payload through the C test's decoder: a GPS packet updates it (*count = 0), any other
 * is decoded into the test's static point array (*points). */
hesai_error c_feed(const uint8_t* payload, size_t size, hesai_packet_info* info, const hesai_point** points,
                   size_t* count);

/* The layout of the C structs as a C compiler sees it: sizeof, then offsetof of each hesai_point
 * member in declaration order (12), then sizeof and alignment of hesai_decoder,
 * hesai_calibration_scratch and hesai_packet_info. Returns the number of values written. */
size_t c_layout(size_t* out, size_t room);
/* The offset of every member of hesai_packet_info, then of hesai_date_time, then of
 * hesai_functional_safety, in the order hesai/packet_info_list.h lists them, then the three
 * structs' sizes, as a C compiler sees them. Returns the number of values written. */
size_t c_packet_info_layout(size_t* out, size_t room);

/* Checks of behaviour the header promises, each on its own packet copy; they print what fails to
 * stderr and return the number of failures.
 * - qt128: a real unsigned QT128 packet; qt128_signed: the same signed with `key`, the session
 *   key of secret "0123456789abcdef", lidar random 00..1f and client random 20..3f. */
int c_check_errors(const uint8_t* qt128, size_t size);
/* - hesai_decoder_decode_columns on `qt128`: the points of hesai_decoder_decode, element by
 *   element; capacity and NULL checks. */
int c_check_columns(const uint8_t* qt128, size_t size);
int c_check_keys(const uint8_t* qt128, const uint8_t* qt128_signed, size_t size, const uint8_t key[32]);
/* - pandar40: a Pandar40 packet (1256 bytes) whose timestamp is below 1 s into the hour. */
int c_check_pandar40_gps(const uint8_t* pandar40, size_t size);
int c_check_calibration_errors(void);
/* - qt128_custom: a QT128 packet with customised channels (flags bit 6) whose units are the
 *   channels `config` (a channel-configuration CSV of LaserNum 80) lists; `points` the points it
 *   decodes to; pandar64: a Pandar64 packet. */
int c_check_sensor_settings(const uint8_t* qt128_custom, size_t size, const uint8_t* config, size_t config_size,
                            size_t points, const uint8_t* pandar64, size_t pandar64_size);

/* Stream health: `n` packets (their bytes one after another in `bytes`, their sizes in `sizes`) of
 * `model` through hesai_decoder_decode_health with `returns` into a fresh monitor (clockwise);
 * writes its counters and the points the calls gave. Returns the first error (and checks the
 * invalid arguments the header names, counted in *failures). */
hesai_error c_health_run(hesai_model model, const uint8_t* bytes, const size_t* sizes, size_t n, int returns,
                         hesai_health_counts* counts, uint64_t* points_given, int* failures_out);

#ifdef __cplusplus
}
#endif

#endif
