// The C interface (hesai/hesai.h): hesai::Decoder built in the caller's hesai_decoder bytes, behind
// extern "C" functions that check every pointer and cannot throw (the core has no exceptions).
// What the C declarations promise about sizes, layouts and values is checked here at compile time.
#include "hesai/hesai.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <new>
#include <type_traits>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/gps.h"
#include "hesai/health.h"
#include "hesai/hkdf.h"
#include "hesai/model.h"
#include "hesai/point.h"
#include "hesai/detail/tables/qt128_tables.h"

namespace {

using hesai::ByteView;
using hesai::Decoder;
using hesai::Error;
using hesai::Model;

// ---- The storage contract -------------------------------------------------------------------

template <class T, class Storage>
constexpr bool fits() {
  return sizeof(T) <= sizeof(Storage::opaque.bytes) && alignof(T) <= alignof(Storage);
}
// There is no release call: the storage may be dropped without running ~Decoder(), whose only
// effect is wiping the key (hesai_decoder_clear_session_key() does that).
static_assert(fits<Decoder, hesai_decoder>(), "hesai::Decoder must fit in HESAI_DECODER_SIZE aligned bytes");
static_assert(std::is_trivially_destructible_v<hesai::HealthMonitor> && std::is_trivially_destructible_v<hesai::UnitScan>);
static_assert(HESAI_RETURNS_all == static_cast<int>(hesai::Returns::all) &&
              HESAI_RETURNS_distinct == static_cast<int>(hesai::Returns::distinct));
static_assert(sizeof(hesai_health_counts::blockage_by_channel) / sizeof(std::uint32_t) == hesai::kMaxChannels);
static_assert(fits<hesai::AngleCorrection, hesai_calibration_scratch>() &&
                  fits<hesai::FiretimeCorrection, hesai_calibration_scratch>() &&
                  fits<hesai::ChannelConfig, hesai_calibration_scratch>(),
              "every parsed calibration file must fit in HESAI_CALIBRATION_SCRATCH_SIZE aligned bytes");
static_assert(std::is_trivially_destructible_v<hesai::AngleCorrection> &&
              std::is_trivially_destructible_v<hesai::FiretimeCorrection> &&
              std::is_trivially_destructible_v<hesai::ChannelConfig>);

// ---- Values the C enums share with C++ --------------------------------------------------------

// hesai_error is made from the same list as hesai::Error (hesai/error_list.h); checked anyway.
#define HESAI_SAME_ERROR(name) static_assert(HESAI_ERROR_##name == static_cast<int>(Error::name));
HESAI_ERROR_LIST(HESAI_SAME_ERROR)
#undef HESAI_SAME_ERROR
static_assert(HESAI_ERROR_COUNT == hesai::kErrorCount);

// hesai_model is made from the same list as hesai::Model (hesai/model_list.h); checked anyway.
#define HESAI_SAME_MODEL(id, name, channels, blocks, firings, ptc) static_assert(HESAI_MODEL_##id == static_cast<int>(Model::id));
HESAI_MODEL_LIST(HESAI_SAME_MODEL)
#undef HESAI_SAME_MODEL
static_assert(HESAI_MODEL_unknown == static_cast<int>(Model::unknown) && HESAI_MODEL_COUNT == hesai::kModelCount);
static_assert(HESAI_ROTATION_clockwise == static_cast<int>(hesai::Rotation::clockwise) &&
              HESAI_ROTATION_counterclockwise == static_cast<int>(hesai::Rotation::counterclockwise));
static_assert(HESAI_SIGNATURE_not_signed == static_cast<int>(hesai::SignatureStatus::not_signed) &&
              HESAI_SIGNATURE_unverified == static_cast<int>(hesai::SignatureStatus::unverified) &&
              HESAI_SIGNATURE_valid == static_cast<int>(hesai::SignatureStatus::valid) &&
              HESAI_SIGNATURE_accepted_unsigned == static_cast<int>(hesai::SignatureStatus::accepted_unsigned));
static_assert(HESAI_TIME_utc == static_cast<int>(hesai::TimeReference::utc) &&
              HESAI_TIME_hour_relative == static_cast<int>(hesai::TimeReference::hour_relative));
static_assert(HESAI_MAX_POINTS_PER_PACKET == hesai::kMaxPointsPerPacket);
static_assert(HESAI_REFLECTIVITY_raw == static_cast<int>(hesai::Reflectivity::raw) &&
              HESAI_REFLECTIVITY_nonlinear == static_cast<int>(hesai::Reflectivity::nonlinear));

// ---- hesai_point is hesai::Point's layout ------------------------------------------------------

// The decoder writes hesai::Point values straight into the caller's hesai_point array (there is
// no room for a copy: a packet's points are 10 to 16 KiB). Both are standard-layout structs of
// the same members, types and offsets, checked here member by member; the array is written only
// inside the library, and the caller reads it after the call returns.
static_assert(std::is_standard_layout_v<hesai::Point> && std::is_trivially_copyable_v<hesai::Point>);
static_assert(sizeof(hesai_point) == sizeof(hesai::Point) && alignof(hesai_point) == alignof(hesai::Point));
#define HESAI_SAME_MEMBER(m)                                                         \
  static_assert(offsetof(hesai_point, m) == offsetof(hesai::Point, m) &&             \
                    std::is_same_v<decltype(hesai_point::m), decltype(hesai::Point::m)>, \
                "hesai_point::" #m " differs from hesai::Point::" #m);
HESAI_SAME_MEMBER(x)
HESAI_SAME_MEMBER(y)
HESAI_SAME_MEMBER(z)
HESAI_SAME_MEMBER(distance_m)
HESAI_SAME_MEMBER(azimuth_deg)
HESAI_SAME_MEMBER(elevation_deg)
HESAI_SAME_MEMBER(time_ns)
HESAI_SAME_MEMBER(intensity)
HESAI_SAME_MEMBER(channel)
HESAI_SAME_MEMBER(return_index)
HESAI_SAME_MEMBER(confidence)
HESAI_SAME_MEMBER(block)
#undef HESAI_SAME_MEMBER

// ---- hesai_packet_info's layout ----------------------------------------------------------------

// The offsets compiled C callers rely on, worked out by hand from the C layout rules (each member
// at the next multiple of its alignment): a reordered or retyped member in
// hesai/packet_info_list.h breaks them, and with them binary compatibility.
static_assert(offsetof(hesai_date_time, year) == 0 && offsetof(hesai_date_time, month) == 4 &&
              offsetof(hesai_date_time, day) == 5 && offsetof(hesai_date_time, hour) == 6 &&
              offsetof(hesai_date_time, minute) == 7 && offsetof(hesai_date_time, second) == 8 &&
              sizeof(hesai_date_time) == 12 && alignof(hesai_date_time) == 4);
static_assert(offsetof(hesai_functional_safety, present) == 0 && offsetof(hesai_functional_safety, version) == 1 &&
              offsetof(hesai_functional_safety, lidar_state) == 2 &&
              offsetof(hesai_functional_safety, fault_code_type) == 3 &&
              offsetof(hesai_functional_safety, rolling_counter) == 4 &&
              offsetof(hesai_functional_safety, total_fault_codes) == 5 &&
              offsetof(hesai_functional_safety, fault_code_id) == 6 &&
              offsetof(hesai_functional_safety, fault_code) == 8 && sizeof(hesai_functional_safety) == 10);
static_assert(offsetof(hesai_packet_info, time_ns) == 0 && offsetof(hesai_packet_info, date_time) == 8 &&
              offsetof(hesai_packet_info, timestamp_us) == 20 && offsetof(hesai_packet_info, sequence) == 24 &&
              offsetof(hesai_packet_info, motor_rpm) == 28 && offsetof(hesai_packet_info, block_azimuth) == 30 &&
              offsetof(hesai_packet_info, model) == 50 && offsetof(hesai_packet_info, return_mode) == 51 &&
              offsetof(hesai_packet_info, returns) == 52 && offsetof(hesai_packet_info, blocks) == 53 &&
              offsetof(hesai_packet_info, dis_unit_mm) == 54 && offsetof(hesai_packet_info, time_reference) == 55 &&
              offsetof(hesai_packet_info, has_sequence) == 56 && offsetof(hesai_packet_info, high_temperature) == 57 &&
              offsetof(hesai_packet_info, factory_info) == 58 && offsetof(hesai_packet_info, flags) == 59 &&
              offsetof(hesai_packet_info, mode_flag) == 60 && offsetof(hesai_packet_info, signature) == 61 &&
              offsetof(hesai_packet_info, safety) == 62 && sizeof(hesai_packet_info) == 72);
// Every C member has a C++ member of the same name and a type that holds its values.
#define HESAI_WIDE_ENOUGH(c_type, cpp_type)                                                        \
  (std::is_same_v<cpp_type, bool> ||                                                                \
   (std::is_enum_v<cpp_type> && sizeof(cpp_type) <= sizeof(c_type)) ||                             \
   (std::is_integral_v<cpp_type> && std::numeric_limits<cpp_type>::digits <= std::numeric_limits<c_type>::digits && \
    std::is_signed_v<cpp_type> == std::is_signed_v<c_type>))
#define HESAI_FITS_DATE_TIME(type, name) \
  static_assert(HESAI_WIDE_ENOUGH(type, decltype(hesai::DateTime::name)), "hesai_date_time::" #name);
#define HESAI_FITS_SAFETY(type, name) \
  static_assert(HESAI_WIDE_ENOUGH(type, decltype(hesai::FunctionalSafety::name)), "hesai_functional_safety::" #name);
#define HESAI_FITS_INFO(type, name) \
  static_assert(HESAI_WIDE_ENOUGH(type, decltype(hesai::PacketInfo::name)), "hesai_packet_info::" #name);
#define HESAI_FITS_INFO_ARRAY(type, name, count) \
  static_assert(HESAI_WIDE_ENOUGH(type, decltype(hesai::PacketInfo::name)::value_type), "hesai_packet_info::" #name);
#define HESAI_FITS_NESTED(type, name, list) \
  static_assert(sizeof(decltype(hesai::PacketInfo::name)) > 0, "hesai_packet_info::" #name);
HESAI_DATE_TIME_LIST(HESAI_FITS_DATE_TIME)
HESAI_FUNCTIONAL_SAFETY_LIST(HESAI_FITS_SAFETY)
HESAI_PACKET_INFO_LIST(HESAI_FITS_INFO, HESAI_FITS_INFO_ARRAY, HESAI_FITS_NESTED)
#undef HESAI_FITS_DATE_TIME
#undef HESAI_FITS_SAFETY
#undef HESAI_FITS_INFO
#undef HESAI_FITS_INFO_ARRAY
#undef HESAI_FITS_NESTED
#undef HESAI_WIDE_ENOUGH

// ---- Helpers -----------------------------------------------------------------------------------

// The decoder hesai_decoder_init() built in the storage (at its start, aligned as checked above).
Decoder& decoder_in(hesai_decoder* d) noexcept { return *std::launder(static_cast<Decoder*>(static_cast<void*>(d))); }
const Decoder& decoder_in(const hesai_decoder* d) noexcept {
  return *std::launder(static_cast<const Decoder*>(static_cast<const void*>(d)));
}

hesai_error c_error(Error e) noexcept { return static_cast<hesai_error>(e); }

// What hesai_health_init() builds in the storage: the monitor, and the scan of the packet being
// decoded (kept there, not on the stack: the call stays within the 1 KiB stack budget).
struct HealthStorage {
  hesai::HealthMonitor monitor;
  hesai::UnitScan scan;
};
HealthStorage& health_in(hesai_health* h) noexcept {
  return *std::launder(static_cast<HealthStorage*>(static_cast<void*>(h)));
}
const HealthStorage& health_in(const hesai_health* h) noexcept {
  return *std::launder(static_cast<const HealthStorage*>(static_cast<const void*>(h)));
}

// A byte range the caller passed: NULL only when empty.
bool bytes_ok(const std::uint8_t* p, std::size_t size) noexcept { return p != nullptr || size == 0; }

// A parsed-file struct, value-initialised in the scratch bytes.
template <class T>
T& fresh_in(hesai_calibration_scratch* s) noexcept {
  return *::new (static_cast<void*>(s)) T{};
}

// A calibration file's bytes parsed into the scratch for the decoder's channel count, then given
// to the decoder: the CSV setters of hesai.h.
template <class Parsed>
hesai_error set_from_csv(hesai_decoder* decoder, const std::uint8_t* text, std::size_t size,
                         hesai_calibration_scratch* scratch, std::uint32_t* line,
                         hesai::ParseResult (*parse)(ByteView, std::size_t, Parsed&) noexcept,
                         Error (Decoder::*apply)(const Parsed&) noexcept) noexcept {
  if (line != nullptr) *line = 0;
  if (decoder == nullptr || scratch == nullptr || !bytes_ok(text, size)) return HESAI_ERROR_invalid_argument;
  Decoder& d = decoder_in(decoder);
  Parsed& parsed = fresh_in<Parsed>(scratch);
  const hesai::ParseResult r = parse(ByteView{text, size}, hesai::channel_count(d.model()), parsed);
  if (r.error != Error::ok) {
    if (line != nullptr) *line = r.line;
    return c_error(r.error);
  }
  return c_error((d.*apply)(parsed));
}

// parse_channel_config_csv in set_from_csv's form: the file states its own LaserNum, so the
// decoder's channel count is not an input.
hesai::ParseResult parse_channel_config(ByteView text, std::size_t, hesai::ChannelConfig& out) noexcept {
  return hesai::parse_channel_config_csv(text, out);
}

// The C structs from the C++ ones, member by member as hesai/packet_info_list.h lists them: each
// C member from the C++ member of the same name, converted to the C type (enums to their value,
// bools to 0 or 1).
#define HESAI_COPY_FIELD(type, name) o.name = static_cast<type>(i.name);
#define HESAI_COPY_ARRAY(type, name, count)                                   \
  static_assert(std::tuple_size_v<decltype(i.name)> == (count));              \
  for (std::size_t k = 0; k < (count); ++k) o.name[k] = static_cast<type>(i.name[k]);
#define HESAI_COPY_NESTED(type, name, list) copy_info(i.name, o.name);
void copy_info(const hesai::DateTime& i, hesai_date_time& o) noexcept { HESAI_DATE_TIME_LIST(HESAI_COPY_FIELD) }
void copy_info(const hesai::FunctionalSafety& i, hesai_functional_safety& o) noexcept {
  HESAI_FUNCTIONAL_SAFETY_LIST(HESAI_COPY_FIELD)
}
void copy_info(const hesai::PacketInfo& i, hesai_packet_info& o) noexcept {
  HESAI_PACKET_INFO_LIST(HESAI_COPY_FIELD, HESAI_COPY_ARRAY, HESAI_COPY_NESTED)
}
#undef HESAI_COPY_FIELD
#undef HESAI_COPY_ARRAY
#undef HESAI_COPY_NESTED

bool known_model(hesai_model m) noexcept {
  return m > HESAI_MODEL_unknown && static_cast<std::size_t>(m) < hesai::kModelCount;
}

Model cpp_model(hesai_model m) noexcept { return known_model(m) ? static_cast<Model>(m) : Model::unknown; }

}  // namespace

extern "C" {

const char* hesai_error_name(hesai_error e) noexcept {
  // Values outside the uint8_t range must not wrap onto a code.
  const auto v = static_cast<long long>(e);
  return v >= 0 && v < HESAI_ERROR_COUNT ? hesai::error_name(static_cast<Error>(v)) : "unknown";
}

const char* hesai_model_name(hesai_model m) noexcept { return hesai::model_name(cpp_model(m)); }

std::size_t hesai_model_channels(hesai_model m) noexcept { return hesai::channel_count(cpp_model(m)); }

std::size_t hesai_model_max_points(hesai_model m) noexcept { return hesai::max_points(cpp_model(m)); }

hesai_error hesai_identify(const std::uint8_t* payload, std::size_t size, std::uint8_t* model,
                           std::uint8_t* is_gps) noexcept {
  if (!bytes_ok(payload, size) || model == nullptr || is_gps == nullptr) return HESAI_ERROR_invalid_argument;
  Model m = Model::unknown;
  hesai::PacketKind kind = hesai::PacketKind::point_cloud;
  const Error e = hesai::identify(ByteView{payload, size}, m, kind);
  *model = static_cast<std::uint8_t>(m);
  *is_gps = kind == hesai::PacketKind::gps ? 1 : 0;
  return c_error(e);
}

hesai_error hesai_decoder_init(hesai_decoder* decoder, hesai_model model) noexcept {
  if (decoder == nullptr) return HESAI_ERROR_invalid_argument;
  ::new (static_cast<void*>(decoder)) Decoder(cpp_model(model));
  return known_model(model) ? HESAI_ERROR_ok : HESAI_ERROR_invalid_argument;
}

hesai_model hesai_decoder_model(const hesai_decoder* decoder) noexcept {
  if (decoder == nullptr) return HESAI_MODEL_unknown;
  return static_cast<hesai_model>(decoder_in(decoder).model());
}

hesai_error hesai_decoder_set_angles_csv(hesai_decoder* decoder, const std::uint8_t* text, std::size_t size,
                                         hesai_calibration_scratch* scratch, std::uint32_t* line) noexcept {
  return set_from_csv<hesai::AngleCorrection>(decoder, text, size, scratch, line, hesai::parse_angle_csv,
                                              &Decoder::set_angles);
}

hesai_error hesai_decoder_set_firetimes_csv(hesai_decoder* decoder, const std::uint8_t* text, std::size_t size,
                                            hesai_calibration_scratch* scratch, std::uint32_t* line) noexcept {
  return set_from_csv<hesai::FiretimeCorrection>(decoder, text, size, scratch, line, hesai::parse_firetime_csv,
                                                 &Decoder::set_firetimes);
}

hesai_error hesai_decoder_set_angles(hesai_decoder* decoder, const double* elevation_deg, const double* azimuth_deg,
                                     std::size_t channels, hesai_calibration_scratch* scratch) noexcept {
  if (decoder == nullptr || scratch == nullptr || elevation_deg == nullptr || azimuth_deg == nullptr)
    return HESAI_ERROR_invalid_argument;
  Decoder& d = decoder_in(decoder);
  if (channels != hesai::channel_count(d.model())) return HESAI_ERROR_calib_channel_count;
  auto& angles = fresh_in<hesai::AngleCorrection>(scratch);
  angles.channels = static_cast<std::uint16_t>(channels);
  for (std::size_t i = 0; i < channels; ++i) {
    angles.elevation_deg[i] = elevation_deg[i];
    angles.azimuth_deg[i] = azimuth_deg[i];
  }
  return c_error(d.set_angles(angles));
}

hesai_error hesai_decoder_set_firetimes(hesai_decoder* decoder, const double* loop1_us, const double* loop2_us,
                                        std::size_t channels, hesai_calibration_scratch* scratch) noexcept {
  if (decoder == nullptr || scratch == nullptr || loop1_us == nullptr) return HESAI_ERROR_invalid_argument;
  Decoder& d = decoder_in(decoder);
  if (channels != hesai::channel_count(d.model())) return HESAI_ERROR_calib_channel_count;
  auto& firetimes = fresh_in<hesai::FiretimeCorrection>(scratch);
  firetimes.channels = static_cast<std::uint16_t>(channels);
  firetimes.loops = loop2_us != nullptr ? 2 : 1;
  const double* const loops[2] = {loop1_us, loop2_us};
  // The arrays do not say which channels rest: for the QT128 the manual's bank rule does.
  const bool qt128 = d.model() == hesai::Model::qt128c2x;
  for (std::size_t loop = 0; loop < firetimes.loops; ++loop) {
    for (std::size_t i = 0; i < channels; ++i) {
      firetimes.firetime_us[loop][i] = loops[loop][i];
      firetimes.fires[loop][i] = !qt128 || (loop == 0 ? hesai::tables::qt128_fires_in_loop1[i]
                                                       : hesai::tables::qt128_fires_in_loop2[i]);
    }
  }
  return c_error(d.set_firetimes(firetimes));
}

hesai_error hesai_decoder_set_firetime_correction(hesai_decoder* decoder, int on) noexcept {
  if (decoder == nullptr) return HESAI_ERROR_invalid_argument;
  decoder_in(decoder).set_firetime_correction(on != 0);
  return HESAI_ERROR_ok;
}

hesai_error hesai_decoder_set_rotation(hesai_decoder* decoder, int rotation) noexcept {
  if (decoder == nullptr) return HESAI_ERROR_invalid_argument;
  switch (rotation) {
    case HESAI_ROTATION_clockwise: decoder_in(decoder).set_rotation(hesai::Rotation::clockwise); break;
    case HESAI_ROTATION_counterclockwise: decoder_in(decoder).set_rotation(hesai::Rotation::counterclockwise); break;
    default: return HESAI_ERROR_invalid_argument;
  }
  return HESAI_ERROR_ok;
}

hesai_error hesai_decoder_set_channel_config_csv(hesai_decoder* decoder, const std::uint8_t* text, std::size_t size,
                                                 hesai_calibration_scratch* scratch, std::uint32_t* line) noexcept {
  return set_from_csv<hesai::ChannelConfig>(decoder, text, size, scratch, line, parse_channel_config,
                                            &Decoder::set_channel_config);
}

hesai_error hesai_decoder_clear_channel_config(hesai_decoder* decoder) noexcept {
  if (decoder == nullptr) return HESAI_ERROR_invalid_argument;
  decoder_in(decoder).clear_channel_config();
  return HESAI_ERROR_ok;
}

hesai_error hesai_decoder_set_reflectivity(hesai_decoder* decoder, int mapping) noexcept {
  if (decoder == nullptr || (mapping != HESAI_REFLECTIVITY_raw && mapping != HESAI_REFLECTIVITY_nonlinear))
    return HESAI_ERROR_invalid_argument;
  return c_error(decoder_in(decoder).set_reflectivity(static_cast<hesai::Reflectivity>(mapping)));
}

hesai_error hesai_decoder_set_session_key(hesai_decoder* decoder, const std::uint8_t key[32]) noexcept {
  if (decoder == nullptr || key == nullptr) return HESAI_ERROR_invalid_argument;
  return c_error(decoder_in(decoder).set_session_key(key));
}

hesai_error hesai_decoder_clear_session_key(hesai_decoder* decoder) noexcept {
  if (decoder == nullptr) return HESAI_ERROR_invalid_argument;
  decoder_in(decoder).clear_session_key();
  return HESAI_ERROR_ok;
}

hesai_error hesai_decoder_set_allow_unsigned(hesai_decoder* decoder, int allow) noexcept {
  if (decoder == nullptr) return HESAI_ERROR_invalid_argument;
  decoder_in(decoder).set_allow_unsigned(allow != 0);
  return HESAI_ERROR_ok;
}

hesai_error hesai_session_key_derive(const std::uint8_t* secret, std::size_t secret_size,
                                     const std::uint8_t lidar_random[32], const std::uint8_t client_random[32],
                                     std::uint8_t key[32]) noexcept {
  if (!bytes_ok(secret, secret_size) || lidar_random == nullptr || client_random == nullptr || key == nullptr)
    return HESAI_ERROR_invalid_argument;
  return c_error(hesai::hesai_session_key(ByteView{secret, secret_size}, lidar_random, client_random, key));
}

hesai_error hesai_decoder_update_gps(hesai_decoder* decoder, const std::uint8_t* payload, std::size_t size) noexcept {
  if (decoder == nullptr || !bytes_ok(payload, size)) return HESAI_ERROR_invalid_argument;
  hesai::GpsPacket gps;
  const Error e = hesai::parse_gps_packet(ByteView{payload, size}, gps);
  if (e == Error::ok) decoder_in(decoder).update_gps(gps);
  return c_error(e);
}

hesai_error hesai_decoder_validate(hesai_decoder* decoder, const std::uint8_t* payload, std::size_t size,
                                   hesai_packet_info* info) noexcept {
  if (decoder == nullptr || info == nullptr || !bytes_ok(payload, size)) return HESAI_ERROR_invalid_argument;
  hesai::PacketInfo i;
  const Error e = decoder_in(decoder).validate(ByteView{payload, size}, i);
  copy_info(i, *info);
  return c_error(e);
}

hesai_error hesai_decoder_decode(hesai_decoder* decoder, const std::uint8_t* payload, std::size_t size,
                                 hesai_packet_info* info, hesai_point* points, std::size_t capacity,
                                 std::size_t* count) noexcept {
  if (count != nullptr) *count = 0;
  if (decoder == nullptr || points == nullptr || count == nullptr || !bytes_ok(payload, size))
    return HESAI_ERROR_invalid_argument;
  hesai::PacketInfo i;
  const Error e = decoder_in(decoder).decode(ByteView{payload, size}, i, reinterpret_cast<hesai::Point*>(points),
                                             capacity, *count);
  if (info != nullptr) copy_info(i, *info);
  return c_error(e);
}

hesai_error hesai_decoder_decode_columns(hesai_decoder* decoder, const std::uint8_t* payload, std::size_t size,
                                         hesai_packet_info* info, const hesai_point_columns* columns,
                                         std::size_t* count) noexcept {
  if (count != nullptr) *count = 0;
  if (decoder == nullptr || columns == nullptr || count == nullptr || !bytes_ok(payload, size))
    return HESAI_ERROR_invalid_argument;
  const hesai::PointColumns c{columns->x,         columns->y,       columns->z,
                              columns->time_ns,   columns->intensity, columns->channel,
                              columns->return_index, columns->capacity};
  hesai::PacketInfo i;
  const Error e = decoder_in(decoder).decode(ByteView{payload, size}, i, c, *count);
  if (info != nullptr) copy_info(i, *info);
  return c_error(e);
}

static_assert(fits<HealthStorage, hesai_health>(), "the monitor and a unit scan must fit in HESAI_HEALTH_SIZE aligned bytes");

hesai_error hesai_health_init(hesai_health* health, int rotation) noexcept {
  if (health == nullptr || (rotation != HESAI_ROTATION_clockwise && rotation != HESAI_ROTATION_counterclockwise))
    return HESAI_ERROR_invalid_argument;
  HealthStorage* h = ::new (static_cast<void*>(health)) HealthStorage{};
  h->monitor.set_rotation(static_cast<hesai::Rotation>(rotation));
  return HESAI_ERROR_ok;
}

hesai_error hesai_decoder_decode_health(hesai_decoder* decoder, const std::uint8_t* payload, std::size_t size,
                                        hesai_packet_info* info, hesai_point* points, std::size_t capacity,
                                        std::size_t* count, int returns, hesai_health* health,
                                        std::uint32_t* lost_before) noexcept {
  if (count != nullptr) *count = 0;
  if (lost_before != nullptr) *lost_before = 0;
  if (decoder == nullptr || points == nullptr || count == nullptr || !bytes_ok(payload, size) ||
      (returns != HESAI_RETURNS_all && returns != HESAI_RETURNS_distinct) ||
      (returns == HESAI_RETURNS_distinct && health == nullptr))
    return HESAI_ERROR_invalid_argument;
  hesai::PacketInfo i;
  Error e;
  if (health == nullptr) {
    e = decoder_in(decoder).decode(ByteView{payload, size}, i, reinterpret_cast<hesai::Point*>(points), capacity, *count);
  } else {
    HealthStorage& h = health_in(health);
    e = decoder_in(decoder).decode(ByteView{payload, size}, i, reinterpret_cast<hesai::Point*>(points), capacity, *count,
                                   h.scan, static_cast<hesai::Returns>(returns));
    if (e == Error::ok) {
      const std::uint32_t lost = h.monitor.observe(i);
      h.monitor.observe_units(h.scan);
      if (lost_before != nullptr) *lost_before = lost;
    }
  }
  if (info != nullptr) copy_info(i, *info);
  return c_error(e);
}

hesai_error hesai_health_counts_get(const hesai_health* health, hesai_health_counts* counts) noexcept {
  if (health == nullptr || counts == nullptr) return HESAI_ERROR_invalid_argument;
  const hesai::HealthCounts& h = health_in(health).monitor.counts();
  counts->packets = h.packets;
  counts->lost = h.lost;
  counts->reordered = h.reordered;
  counts->duplicates = h.duplicates;
  counts->time_stalls = h.time_stalls;
  counts->time_virtual = h.time_virtual;
  counts->time_jumps = h.time_jumps;
  counts->blockage_units = h.blockage_units;
  counts->duplicate_returns = h.duplicate_returns;
  counts->beyond_rated_range = h.beyond_rated_range;
  for (std::size_t ch = 0; ch < hesai::kMaxChannels; ++ch) counts->blockage_by_channel[ch] = h.blockage_by_channel[ch];
  counts->fov_gap = h.fov_gap ? 1 : 0;
  counts->fov_gap_from = h.fov_gap_from;
  counts->fov_gap_to = h.fov_gap_to;
  return HESAI_ERROR_ok;
}

}  // extern "C"
