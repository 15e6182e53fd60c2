/* The decoder from C (C99; the same declarations, extern "C", from C++).
 *
 * The contract:
 * - Memory: all of it is the caller's. A decoder is a hesai_decoder of HESAI_DECODER_SIZE bytes
 *   (static, on the stack or in a struct: it needs no release); the points of a packet go into the
 *   caller's hesai_point array; calibration calls work in a caller's hesai_calibration_scratch of
 *   HESAI_CALIBRATION_SCRATCH_SIZE bytes (the parsed file, too big for a small stack). The library
 *   never allocates and holds no pointer to caller memory after a call returns.
 * - Stack: no call uses more than 1 KiB on a Cortex-M (tests/firmware measures each).
 * - Errors: every call that can fail returns a hesai_error; HESAI_ERROR_ok is 0. A NULL pointer
 *   where one is needed is HESAI_ERROR_invalid_argument. Nothing throws, asserts or aborts.
 * - Threads: calls on different decoders are independent; one decoder must not be used by two
 *   threads at once. The only shared state is the x86 CPU-feature flags, cached atomically.
 *
 *     static hesai_decoder decoder;
 *     static hesai_point points[HESAI_MAX_POINTS_PER_PACKET];
 *     size_t count;
 *     hesai_packet_info info;
 *     hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x);
 *     hesai_error e = hesai_decoder_decode(&decoder, payload, size, &info, points, 256, &count);
 *     if (e != HESAI_ERROR_ok) log(hesai_error_name(e));
 */
#ifndef HESAI_HESAI_H
#define HESAI_HESAI_H

#include <stddef.h>
#include <stdint.h>

#include "hesai/error_list.h"
#include "hesai/model_list.h"
#include "hesai/packet_info_list.h"

#ifdef __cplusplus
#define HESAI_NOEXCEPT noexcept
extern "C" {
#else
#define HESAI_NOEXCEPT
#endif

/* ---- Codes ------------------------------------------------------------------------------- */

/* Outcome of a call: HESAI_ERROR_<name> has the value of hesai::Error::<name>, and
 * hesai_error_name() gives "<name>". The codes and their meaning: hesai/error_list.h. */
typedef enum hesai_error {
#define HESAI_C_ERROR(name) HESAI_ERROR_##name,
  HESAI_ERROR_LIST(HESAI_C_ERROR)
#undef HESAI_C_ERROR
  HESAI_ERROR_COUNT /* number of codes, not a code */
} hesai_error;

/* A sensor model (values of hesai::Model): HESAI_MODEL_<id> for each model of hesai/model_list.h,
 * in its order from 1; 0 is unknown. */
typedef enum hesai_model {
  HESAI_MODEL_unknown = 0,
#define HESAI_C_MODEL(id, name, channels, blocks, firings, ptc) HESAI_MODEL_##id,
  HESAI_MODEL_LIST(HESAI_C_MODEL)
#undef HESAI_C_MODEL
  HESAI_MODEL_COUNT /* number of values, unknown included; not a model */
} hesai_model;

/* What became of a packet's signature (hesai_packet_info.signature; hesai::SignatureStatus). */
enum {
  HESAI_SIGNATURE_not_signed = 0,       /* no signature (or all zero) and no key configured */
  HESAI_SIGNATURE_unverified = 1,       /* a signature is present but no key is configured */
  HESAI_SIGNATURE_valid = 2,            /* HMAC-SHA256 verified under the session key */
  HESAI_SIGNATURE_accepted_unsigned = 3 /* a key is set, the packet is unsigned, unsigned allowed */
};

/* Whether times are absolute (hesai_packet_info.time_reference; hesai::TimeReference). */
enum {
  HESAI_TIME_utc = 0,          /* ns since the Unix epoch, UTC */
  HESAI_TIME_hour_relative = 1 /* Pandar40 before its first GPS packet: ns since an unknown hour */
};

/* "crc_body", ...; "unknown" for a value that is no code. Never NULL. */
const char* hesai_error_name(hesai_error e) HESAI_NOEXCEPT;
/* "Pandar40", "Pandar40P", "Pandar64", "QT128C2X", "PandarQT64", "PandarXT16", "PandarXT32",
 * "PandarXT32M2X"; "unknown" otherwise. Never NULL. */
const char* hesai_model_name(hesai_model m) HESAI_NOEXCEPT;
/* Laser channels of the model: 40, 40, 64, 128, 64, 16, 32, 32 in the order above (0 for unknown). */
size_t hesai_model_channels(hesai_model m) HESAI_NOEXCEPT;
/* The most points one packet of the model holds, blocks x channels: 400, 400, 384, 256, 256,
 * 128, 256, 192 in the order above (0 for unknown). A point array of this many entries suffices for any packet of the model. */
size_t hesai_model_max_points(hesai_model m) HESAI_NOEXCEPT;

/* The most points of any model's packet (Pandar40: 10 blocks x 40 channels). */
#define HESAI_MAX_POINTS_PER_PACKET 400

/* ---- Storage ----------------------------------------------------------------------------- */

/* The aligned bytes a decoder lives in: same size on every target and in every version of this
 * major release (the library checks at compile time that its decoder fits; it needs about
 * 7 KiB). Initialise with hesai_decoder_init() before any other call. Copying one with memcpy
 * or assignment is not supported: initialise each. */
#define HESAI_DECODER_SIZE 8192
typedef struct hesai_decoder {
  union {
    unsigned char bytes[HESAI_DECODER_SIZE];
    long long align_ll;
    double align_d;
    void* align_p;
  } opaque;
} hesai_decoder;

/* Working memory of the calibration calls: the parsed file (angles: two doubles per channel;
 * firing times: two loops of doubles). Reusable at once; holds nothing after a call. */
#define HESAI_CALIBRATION_SCRATCH_SIZE 2312
typedef struct hesai_calibration_scratch {
  union {
    unsigned char bytes[HESAI_CALIBRATION_SCRATCH_SIZE];
    long long align_ll;
    double align_d;
    void* align_p;
  } opaque;
} hesai_calibration_scratch;

/* ---- Points and packet fields ------------------------------------------------------------ */

/* A measured point in the manuals' frame: Y axis at azimuth 0, azimuth clockwise seen from above,
 * Z up: x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e). The layout of hesai::Point. */
typedef struct hesai_point {
  float x;              /* metres */
  float y;              /* metres */
  float z;              /* metres */
  float distance_m;     /* range r along the beam, metres */
  float azimuth_deg;    /* horizontal angle a in [0, 360), firing-time correction included */
  float elevation_deg;  /* vertical angle e, degrees, up positive */
  int64_t time_ns;      /* firing time of this channel, ns since the Unix epoch (see time_reference) */
  uint8_t intensity;    /* reflectivity byte as sent (0..255) */
  uint8_t channel;      /* laser channel, 1-based as in the manuals */
  uint8_t return_index; /* 0 for single return; in dual return 0 = odd block, 1 = even block; triple: 0, 1, 2 */
  uint8_t confidence;   /* QT128 per-point confidence byte; 0 for other models */
  uint8_t block;        /* 0-based block index in the packet */
} hesai_point;

/* Caller-owned columns for one packet's points (hesai::PointColumns): element i of every array is
 * the point hesai_decoder_decode writes at points[i] for the same packet. Each pointer addresses
 * `capacity` elements. */
typedef struct hesai_point_columns {
  float* x;               /* metres */
  float* y;               /* metres */
  float* z;               /* metres */
  int32_t* time_ns;       /* firing time, ns from the packet time (hesai_packet_info.time_ns) */
  uint8_t* intensity;     /* as hesai_point.intensity */
  uint8_t* channel;       /* as hesai_point.channel (1-based) */
  uint8_t* return_index;  /* as hesai_point.return_index */
  size_t capacity;
} hesai_point_columns;

/* The packet-level structs, declared from hesai/packet_info_list.h (each member's meaning is
 * given there): hesai_date_time (a tail's date-time, UTC), hesai_functional_safety (the QT128
 * functional-safety section, header flags bit 2) and hesai_packet_info (hesai::PacketInfo: the
 * packet-level fields, filled by validate and decode). */
#define HESAI_DECLARE_FIELD(type, name) type name;
#define HESAI_DECLARE_ARRAY(type, name, count) type name[count];
#define HESAI_DECLARE_NESTED(type, name, list) type name;
typedef struct hesai_date_time {
  HESAI_DATE_TIME_LIST(HESAI_DECLARE_FIELD)
} hesai_date_time;
typedef struct hesai_functional_safety {
  HESAI_FUNCTIONAL_SAFETY_LIST(HESAI_DECLARE_FIELD)
} hesai_functional_safety;
typedef struct hesai_packet_info {
  HESAI_PACKET_INFO_LIST(HESAI_DECLARE_FIELD, HESAI_DECLARE_ARRAY, HESAI_DECLARE_NESTED)
} hesai_packet_info;
#undef HESAI_DECLARE_FIELD
#undef HESAI_DECLARE_ARRAY
#undef HESAI_DECLARE_NESTED

/* ---- Recognition ------------------------------------------------------------------------- */

/* Identifies a UDP payload by length, magic and header fields. On ok *model is a hesai_model
 * (HESAI_MODEL_unknown for a GPS packet) and *is_gps is 1 for a GPS packet, else 0.
 * Errors: bad_length, bad_magic, unsupported_version, unsupported_model, flags_length_mismatch. */
hesai_error hesai_identify(const uint8_t* payload, size_t size, uint8_t* model, uint8_t* is_gps) HESAI_NOEXCEPT;

/* ---- The decoder ------------------------------------------------------------------------- */

/* Makes *decoder a decoder for `model` with the manual's design angles and firing times, no key,
 * unsigned packets refused when a key is set, firing-time correction on. May be called again on
 * the same storage (it starts over). A value that is no hesai_model (or unknown): HESAI_ERROR_invalid_argument,
 * and the decoder refuses every packet (model_mismatch). */
hesai_error hesai_decoder_init(hesai_decoder* decoder, hesai_model model) HESAI_NOEXCEPT;
/* The decoder's model. */
hesai_model hesai_decoder_model(const hesai_decoder* decoder) HESAI_NOEXCEPT;

/* Calibration from the bytes of a vendor CSV file (UTF-8, LF or CRLF; see hesai/calibration.h
 * for the accepted text). On a parse error *line (when not NULL) gets the 1-based line of the
 * first bad row, else 0. Errors: calib_bad_header, calib_bad_row, calib_bad_number,
 * calib_bad_channel, calib_channel_count (another number of channels than the model, or a
 * one-loop firing-time file for the QT128), invalid_argument (an angle or firing time out of
 * range). On any error the decoder is unchanged. */
hesai_error hesai_decoder_set_angles_csv(hesai_decoder* decoder, const uint8_t* text, size_t size,
                                         hesai_calibration_scratch* scratch, uint32_t* line) HESAI_NOEXCEPT;
hesai_error hesai_decoder_set_firetimes_csv(hesai_decoder* decoder, const uint8_t* text, size_t size,
                                            hesai_calibration_scratch* scratch, uint32_t* line) HESAI_NOEXCEPT;

/* Calibration from arrays indexed by channel - 1, `channels` entries each (the model's count,
 * else calib_channel_count). Angles in degrees: elevation in [-90, 90], azimuth offset in
 * [-360, 360]. Firing times in microseconds, in [-1000, 1000], as the vendor files give them:
 * loop2_us NULL for the Pandars' one firing sequence, both loops for the QT128 (any value in
 * range, 0 say, where a channel rests). The QT128 arrays do not say which channels rest: the
 * manual's bank rule does (sequence 1 rests channels 1..32, sequence 2 channels 33..64; their
 * values are not used; a firetime CSV names them itself). invalid_argument for a value out of
 * range. On any error the decoder is unchanged. */
hesai_error hesai_decoder_set_angles(hesai_decoder* decoder, const double* elevation_deg, const double* azimuth_deg,
                                     size_t channels, hesai_calibration_scratch* scratch) HESAI_NOEXCEPT;
hesai_error hesai_decoder_set_firetimes(hesai_decoder* decoder, const double* loop1_us, const double* loop2_us,
                                        size_t channels, hesai_calibration_scratch* scratch) HESAI_NOEXCEPT;

/* Azimuth firing-time correction (on after init): adds firing time x spin rate to each point. */
hesai_error hesai_decoder_set_firetime_correction(hesai_decoder* decoder, int on) HESAI_NOEXCEPT;

/* The direction the unit spins seen from above (hesai::Rotation; clockwise after init). Azimuths
 * grow clockwise either way; the firing-time correction is subtracted for a counter-clockwise
 * unit. The packets carry no field for it: set it from the unit's configuration. Applies from the
 * next decode. invalid_argument for a value that is neither. */
enum {
  HESAI_ROTATION_clockwise = 0,
  HESAI_ROTATION_counterclockwise = 1
};
hesai_error hesai_decoder_set_rotation(hesai_decoder* decoder, int rotation) HESAI_NOEXCEPT;

/* QT128 channel customisation: the bytes of the unit's channel-configuration CSV (EEFF row,
 * "LaserNum,N,BlockNum,2", "Loop1[,Loop2]", then N rows of channels), which maps the units of
 * packets with header flags bit 6 to channels. Without one such packets are
 * channel_config_required; with one of another LaserNum than the packet's, channel_config_mismatch.
 * Errors: the parser's (as above; calib_bad_channel for a channel outside 1..128 or twice in a
 * loop), invalid_argument (not a QT128 decoder), channel_config_mismatch (a BlockNum other than
 * 2). On any error the decoder is unchanged. */
hesai_error hesai_decoder_set_channel_config_csv(hesai_decoder* decoder, const uint8_t* text, size_t size,
                                                 hesai_calibration_scratch* scratch, uint32_t* line) HESAI_NOEXCEPT;
/* Forgets the channel configuration. */
hesai_error hesai_decoder_clear_channel_config(hesai_decoder* decoder) HESAI_NOEXCEPT;

/* What hesai_point.intensity holds (hesai::Reflectivity): the reflectivity byte as sent (after
 * init), or, for a Pandar64 set to "Nonlinear Mapping", the manual's Appendix D percentage to the
 * nearest whole percent (255 stays 255). The packets do not say which mapping a unit uses.
 * invalid_argument for nonlinear on another model, or a value that is neither. */
enum {
  HESAI_REFLECTIVITY_raw = 0,
  HESAI_REFLECTIVITY_nonlinear = 1
};
hesai_error hesai_decoder_set_reflectivity(hesai_decoder* decoder, int mapping) HESAI_NOEXCEPT;

/* Verifies QT128 signatures (HMAC-SHA256) with this 32-byte session key; the decoder keeps its
 * own prepared copy, the caller may wipe `key` after the call. unsupported_feature (and no key)
 * in a core built with HESAI_SIGNATURE 0 (hesai/config.h). */
hesai_error hesai_decoder_set_session_key(hesai_decoder* decoder, const uint8_t key[32]) HESAI_NOEXCEPT;
/* Forgets the key and wipes the decoder's copy of it. */
hesai_error hesai_decoder_clear_session_key(hesai_decoder* decoder) HESAI_NOEXCEPT;
/* With a key: accept packets that carry no signature (signature = accepted_unsigned) instead of
 * refusing them with signature_missing. Off after init. */
hesai_error hesai_decoder_set_allow_unsigned(hesai_decoder* decoder, int allow) HESAI_NOEXCEPT;
/* The Hesai session key from the shared secret (8 to 32 bytes) and the two 32-byte randoms of the
 * key exchange: HKDF-SHA256, info "finish session key". invalid_argument for another secret
 * length (key untouched). */
hesai_error hesai_session_key_derive(const uint8_t* secret, size_t secret_size, const uint8_t lidar_random[32],
                                     const uint8_t client_random[32], uint8_t key[32]) HESAI_NOEXCEPT;

/* Pandar40: takes the date and hour from a GPS packet (512-byte payload) for the packets that
 * follow. Errors of the GPS packet: bad_length, bad_magic, bad_gps_field (decoder unchanged). */
hesai_error hesai_decoder_update_gps(hesai_decoder* decoder, const uint8_t* payload, size_t size) HESAI_NOEXCEPT;

/* Runs every check of a packet (length, header, flags, CRCs, signature, fields) and fills *info.
 * Errors: those of hesai_identify, model_mismatch, and every field, integrity and signature code. */
hesai_error hesai_decoder_validate(hesai_decoder* decoder, const uint8_t* payload, size_t size,
                                   hesai_packet_info* info) HESAI_NOEXCEPT;

/* Validates, then writes the packet's points to points[0 .. *count). A distance of 0 (QT128: 0
 * or 1) gives no point. `capacity` must be at least hesai_model_max_points() of the decoder's
 * model, else buffer_too_small before the packet is read (so a buffer sized for the model is
 * always enough); entries past *count may be overwritten too. *count is 0 on any error. `info`
 * may be NULL. */
hesai_error hesai_decoder_decode(hesai_decoder* decoder, const uint8_t* payload, size_t size, hesai_packet_info* info,
                                 hesai_point* points, size_t capacity, size_t* count) HESAI_NOEXCEPT;

/* hesai_decoder_decode into columns: the same points in the same order, on the vector path the
 * CPU has (x86-64 AVX2, AArch64 NEON) or the scalar one. columns->capacity below
 * hesai_model_max_points() of the decoder's model: buffer_too_small before the packet is read;
 * a NULL column, columns or count: invalid_argument. *count is 0 on any error; `info` may be NULL. */
hesai_error hesai_decoder_decode_columns(hesai_decoder* decoder, const uint8_t* payload, size_t size,
                                         hesai_packet_info* info, const hesai_point_columns* columns,
                                         size_t* count) HESAI_NOEXCEPT;

/* ---- Stream health (hesai/health.h) ------------------------------------------------------- */

/* A sensor's stream-health monitor in HESAI_HEALTH_SIZE aligned bytes (about 940 are used; the
 * library checks at compile time that it fits): loss from the block azimuth and the packet time,
 * clock stalls, jumps and the year-2000 virtual clock, the azimuth FOV, and from the units:
 * QT128C2X blockage markers per channel, repeated dual returns, points beyond the rated range.
 * One per sensor, fed its packets in arrival order by hesai_decoder_decode_health. */
#define HESAI_HEALTH_SIZE 1024
typedef struct hesai_health {
  union {
    unsigned char bytes[HESAI_HEALTH_SIZE];
    long long align_ll;
    double align_d;
    void* align_p;
  } opaque;
} hesai_health;

/* hesai::HealthCounts: every counter saturates. */
typedef struct hesai_health_counts {
  uint64_t packets;            /* packets observed */
  uint64_t lost;               /* missing by block azimuth and packet time, not (yet) arrived */
  uint64_t reordered;          /* arrived after a later one */
  uint64_t duplicates;         /* at the azimuth and time of one already seen */
  uint64_t time_stalls;        /* time not after the previous packet's, not a late packet */
  uint64_t time_virtual;       /* dated in the year 2000: the unit's free-running clock */
  uint64_t time_jumps;         /* time ahead by more than 1 s or than the azimuth allows: a clock step */
  uint64_t blockage_units;     /* QT128C2X units of distance 1 */
  uint64_t duplicate_returns;  /* dual-return pairs carrying the same echo twice */
  uint64_t beyond_rated_range; /* points farther than the model's rated range */
  uint32_t blockage_by_channel[128]; /* blockage units per channel - 1 */
  int fov_gap;                 /* 1: a gap recurred at the same azimuths (an azimuth FOV, not loss) */
  uint16_t fov_gap_from;       /* its edges, 0.01 degree, in the direction of rotation */
  uint16_t fov_gap_to;
} hesai_health_counts;

/* Which returns become points (hesai::Returns): all (default), or a repeated second return once. */
enum {
  HESAI_RETURNS_all = 0,
  HESAI_RETURNS_distinct = 1
};

/* A fresh monitor for a unit spinning `rotation` (HESAI_ROTATION_*). invalid_argument for a NULL
 * monitor or another rotation value. */
hesai_error hesai_health_init(hesai_health* health, int rotation) HESAI_NOEXCEPT;
/* hesai_decoder_decode, with `returns` (HESAI_RETURNS_*), then the packet and its units fed to
 * `health` (when not NULL; not on error; the units' scan is kept in `health`'s bytes, so the call
 * stays within the stack budget). *lost_before (when not NULL): the packets the monitor found
 * missing just before this one (0 on error). invalid_argument for a `returns` value that is
 * neither, or HESAI_RETURNS_distinct without a monitor. */
hesai_error hesai_decoder_decode_health(hesai_decoder* decoder, const uint8_t* payload, size_t size,
                                        hesai_packet_info* info, hesai_point* points, size_t capacity, size_t* count,
                                        int returns, hesai_health* health, uint32_t* lost_before) HESAI_NOEXCEPT;
/* The monitor's counters. invalid_argument for a NULL pointer. */
hesai_error hesai_health_counts_get(const hesai_health* health, hesai_health_counts* counts) HESAI_NOEXCEPT;

#ifdef __cplusplus
}
#endif

#endif /* HESAI_HESAI_H */
