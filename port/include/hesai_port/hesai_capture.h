/* A capture file decoded by the hesai program's own pipeline, from C (C99; extern "C" from C++).
 *
 * Part of the shared library libhesai_c (with the core's C interface, hesai/hesai.h), which the
 * Python package (python/hesai) loads through ctypes. The rows are those `hesai decode --format
 * csv` writes, in the same order: the same capture reader, the same Pipeline (held packets until
 * each source's rotation is known, frame assembly, --cut-angle, --fov, --packets, range limits).
 *
 * The contract:
 * - Memory: a hesai_capture is allocated by hesai_capture_open (the port is hosted: the pipeline
 *   holds std::vector and std::map) and released by hesai_capture_close. The file is mapped
 *   read-only; rows go into the caller's hesai_capture_row array.
 * - Errors: functions return 0 on success, else the hesai program's exit status (1: a usage
 *   error such as a calibration file that does not parse, 2: an input error such as a file that
 *   cannot be read or a damaged capture) with a message in the caller's buffer.
 * - Threads: one hesai_capture must not be used by two threads at once; different ones are
 *   independent.
 * - Sensors: a capture may hold several (each source: an IPv4 or IPv6 address and port, or an MCAP
 *   bag's topic). Each row names its sensor by index (0, 1, ... in the order they first sent a
 *   point-cloud packet); hesai_capture_sensor_name gives the CSV's `sensor` text of an index.
 *   Frame ids count per sensor, so a closed frame is named by its sensor and id.
 *
 * ABI: the sensor members (hesai_capture_row.sensor, hesai_capture_columns.sensor) and
 * hesai_capture_read's closed_sensor changed this interface: a program or binding built against
 * the header without them must be rebuilt (hesai_capture_layout lets a binding check the rows).
 */
#ifndef HESAI_PORT_HESAI_CAPTURE_H
#define HESAI_PORT_HESAI_CAPTURE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
#define HESAI_CAPTURE_NOEXCEPT noexcept
extern "C" {
#else
#define HESAI_CAPTURE_NOEXCEPT
#endif

/* The decode options of the hesai program (docs/CLI.md). hesai_capture_default_options gives the
 * program's defaults. */
typedef struct hesai_capture_options {
  const char* calibration;    /* --calibration: angle-correction CSV path; NULL: the manual's angles */
  const char* firetimes;      /* --firetimes: firing-time CSV path; NULL: the manual's */
  const char* channel_config; /* --channel-config: QT128 channel-configuration CSV path; NULL: none */
  int reflectivity;           /* --reflectivity: 0 raw (default), 1 nonlinear (Pandar64) */
  int firetime_azimuth;       /* 1 (default); 0: --no-firetime-azimuth */
  int rotation;               /* --rotation: -1 auto (default), 0 cw, 1 ccw */
  uint64_t first_packet;      /* --packets FIRST:END, point-cloud packet indices (0, UINT64_MAX) */
  uint64_t end_packet;
  float cut_angle_deg;        /* --cut-angle, degrees in [0, 360) (0) */
  int has_fov;                /* --fov START:END when 1 (0) */
  float fov_start_deg;
  float fov_end_deg;
  float min_range_m;          /* --min-range (0) */
  float max_range_m;          /* --max-range (1e9) */
  const uint8_t* session_key; /* --session-key: 32 bytes, or NULL (no signature verification) */
  int allow_unsigned;         /* --allow-unsigned (0) */
  int returns;                /* --returns: 0 all (default), 1 distinct (a repeated second return once) */
} hesai_capture_options;

/* One row of the CSV. Field order favours alignment; the meaning of each is the CSV column's.
 * 56 bytes: sensor fills what was padding after intensity, the last two bytes are padding. */
typedef struct hesai_capture_row {
  uint64_t frame;        /* frame id, 1-based in rotation order */
  uint64_t packet;       /* 0-based index of the point-cloud packet in the capture */
  int64_t time_ns;       /* firing time, ns since the Unix epoch */
  float azimuth_deg;     /* degrees, [0, 360) */
  float elevation_deg;   /* degrees, up positive */
  float distance_m;      /* metres */
  float x;               /* metres */
  float y;               /* metres */
  float z;               /* metres */
  uint8_t block;         /* 0-based block in the packet */
  uint8_t channel;       /* 1-based laser channel */
  uint8_t return_index;  /* the CSV's "return" */
  uint8_t intensity;     /* reflectivity byte (or the Pandar64's nonlinear percentage) */
  uint16_t sensor;       /* its sensor: hesai_capture_sensor_name(capture, sensor) is the CSV's `sensor` */
} hesai_capture_row;

typedef struct hesai_capture hesai_capture;

/* The hesai program's defaults. */
void hesai_capture_default_options(hesai_capture_options* options) HESAI_CAPTURE_NOEXCEPT;

/* Opens the capture at `path` (pcap or pcapng) and loads the calibration files of `options` (NULL:
 * the defaults). On success *out is the capture (release with hesai_capture_close) and 0 is
 * returned; otherwise *out is NULL, the status is 1 (bad option value) or 2 (a file that cannot be
 * read or is no capture) and `message` (when not NULL, `message_size` bytes) says why. */
int hesai_capture_open(const char* path, const hesai_capture_options* options, hesai_capture** out,
                       char* message, size_t message_size) HESAI_CAPTURE_NOEXCEPT;

/* The next rows, in the CSV's order: writes up to `capacity` rows to rows[0 .. *count). Stops early
 * where a frame closes: then *closed_frame is the id of the frame whose every row has now been
 * given and *closed_sensor its sensor (the rows of the next frame may already have started, as a
 * packet that straddles the cut gives points to both, and so may other sensors' rows); otherwise
 * *closed_frame is 0 (and *closed_sensor 0). Frames close in id order within each sensor.
 * *count == 0 with *closed_frame == 0: the end of the capture. Returns 0, or the status of a
 * failure (1: a calibration file that does not fit the model; 2: a damaged capture, after its rows
 * up to the damage have been given, or a capture with more than 65 536 sensors, after the rows of
 * the first 65 536) with a message. closed_sensor may be NULL. closed_frame NULL: the rows only,
 * without stopping where frames close (fewer, fuller calls). A NULL capture, rows or count, or a
 * capacity of 0: 1. */
int hesai_capture_read(hesai_capture* capture, hesai_capture_row* rows, size_t capacity, size_t* count,
                       uint64_t* closed_frame, uint16_t* closed_sensor, char* message,
                       size_t message_size) HESAI_CAPTURE_NOEXCEPT;

/* The sensors known so far: those of the rows or columns given (and of the rows or points read
 * but not yet given), 0 before the first. Grows as the capture is read; after the end, all. */
size_t hesai_capture_sensors(const hesai_capture* capture) HESAI_CAPTURE_NOEXCEPT;

/* The name of sensor `index` (< hesai_capture_sensors): the CSV's `sensor` column,
 * "192.168.1.201:2368", "[fe80::1]:2368" or an MCAP topic ("mcap channel N" when it has none).
 * NUL-terminated, valid until hesai_capture_close. NULL for another index or a NULL capture. */
const char* hesai_capture_sensor_name(const hesai_capture* capture, size_t index) HESAI_CAPTURE_NOEXCEPT;

/* UDP payloads the pipeline has examined so far (point-cloud, GPS and rejected ones). */
uint64_t hesai_capture_packets(const hesai_capture* capture) HESAI_CAPTURE_NOEXCEPT;

/* An upper bound on what the capture can give, from one pass over its records that decodes
 * nothing (a second mapping of the file, so the capture's own reading is not moved): *datagrams
 * the UDP datagrams up to the end or the first damage, *points the sum over them of
 * hesai_model_max_points() of each point-cloud packet's model (hesai_identify). Neither
 * hesai_capture_read nor hesai_capture_read_columns gives more rows than *points. Returns 0, or 2
 * (with a message) when the file cannot be mapped again; NULL arguments: 1. */
int hesai_capture_bound(const hesai_capture* capture, uint64_t* datagrams, uint64_t* points, char* message,
                        size_t message_size) HESAI_CAPTURE_NOEXCEPT;

/* Caller-owned columns for hesai_capture_read_columns: element i of each is one point, as the
 * CSV's row i gives it. Each pointer addresses `capacity` elements; `packet` and `sensor` may be
 * NULL. */
typedef struct hesai_capture_columns {
  float* x;              /* metres */
  float* y;              /* metres */
  float* z;              /* metres */
  int64_t* time_ns;      /* firing time, ns since the Unix epoch */
  uint8_t* intensity;    /* the CSV's intensity */
  uint8_t* channel;      /* 1-based laser channel */
  uint8_t* return_index; /* the CSV's "return" */
  uint64_t* packet;      /* the CSV's packet (NULL: not written) */
  uint16_t* sensor;      /* the point's sensor, as hesai_capture_row.sensor (NULL: not written) */
  size_t capacity;
} hesai_capture_columns;

/* The capture's points by the core's columnar decode (hesai_decoder_decode_columns: the vector
 * path the CPU has) straight into the caller's columns: the program's Pipeline in its columns
 * mode, without frames or the unit scan (nor counts to read). The points and their order are the CSV's with the same options
 * (held packets until each source's rotation is known included), for the options it takes:
 * calibration, firetimes, channel_config, reflectivity, firetime_azimuth, rotation, packets,
 * session_key, allow_unsigned. A capture opened with another option away from its default
 * (cut_angle, fov, ranges, returns distinct) is refused with 1, as is one already read with
 * hesai_capture_read or counted: a capture is read one way.
 * Writes up to columns->capacity points (fewer: it stops where the next packet might not fit) and
 * sets *count; *count == 0 is the end. columns->capacity must be at least
 * HESAI_CAPTURE_COLUMNS_MIN points, else 1. Returns 0, or the status of a failure (1: a
 * calibration file that does not fit the model; 2: a damaged capture, after its points up to the
 * damage have been given, or more than 65 536 sensors) with a message. */
#define HESAI_CAPTURE_COLUMNS_MIN 4000
int hesai_capture_read_columns(hesai_capture* capture, const hesai_capture_columns* columns, size_t* count,
                               char* message, size_t message_size) HESAI_CAPTURE_NOEXCEPT;

/* The counters `hesai stats CAPTURE --json` prints for the capture with the same options: reads
 * what is left of it without keeping rows (a capture not read before: the whole of it), then
 * writes the JSON object (the same text as the program's, without its newline) to
 * json[0 .. size), cut and terminated when it does not fit; *length gets its full length (call
 * again with a larger buffer: the counts stay). Returns 0; 1 (a calibration file that does not fit
 * the model, no JSON, as the program prints none) or 2 (a damaged capture: the counts up to the
 * damage are written, as the program prints them) with a message. NULL capture, json or length, or
 * size 0: 1. A capture read with hesai_capture_read_columns has no counts: 1. */
int hesai_capture_stats_json(hesai_capture* capture, char* json, size_t size, size_t* length, char* message,
                             size_t message_size) HESAI_CAPTURE_NOEXCEPT;

/* The layout this library was compiled with, for bindings that read its structs as records (the
 * Python package checks its numpy dtypes against it at import): of hesai_capture_row (which 0) or
 * hesai_point (which 1, hesai/hesai.h), the offset of the member that holds the CSV column `name`
 * ("frame", "packet", "block", "channel", "return", "azimuth_deg", "elevation_deg", "distance_m",
 * "x", "y", "z", "intensity", "time_ns", "sensor"; hesai_point has no frame, packet or sensor, and has
 * "confidence"), or with name NULL the struct's size. SIZE_MAX for another name or `which`. */
size_t hesai_capture_layout(int which, const char* name) HESAI_CAPTURE_NOEXCEPT;

/* Releases the capture (NULL: nothing). */
void hesai_capture_close(hesai_capture* capture) HESAI_CAPTURE_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* HESAI_PORT_HESAI_CAPTURE_H */
