// Decoder set-up, identification and the per-block point computation shared by every model.
#include "hesai/decoder.h"

#include "hesai/math.h"
#include "hesai/pandar40_packet.h"
#include "hesai/pandar64_packet.h"
#include "hesai/qt128_packet.h"
#include "hesai/tables/pandar40_tables.h"
#include "hesai/tables/pandar64_tables.h"
#include "hesai/tables/block_times.h"
#include "hesai/tables/qt128_tables.h"

namespace hesai {

namespace {

constexpr std::size_t kGpsBytes = 512;
/// Largest firing-time offset accepted, us: well beyond any block period of the manuals
/// (55.56 us Pandar, 111.11 us QT128); keeps the ns value in range of an int32.
constexpr double kMaxFiretimeUs = 1000.0;

constexpr std::int32_t round_to_int(double v) {
  return static_cast<std::int32_t>(v < 0 ? v - 0.5 : v + 0.5);
}

// Block time offsets from t0 in ns (tables/block_times.h: end times for Pandar40/40P/64, start
// times for QT128), indexed [dual][block].
template <std::size_t N>
constexpr std::array<std::array<std::int64_t, N>, 2> block_ns(const std::array<double, N>& single,
                                                              const std::array<double, N>& dual) {
  std::array<std::array<std::int64_t, N>, 2> ns{};
  for (std::size_t b = 0; b < N; ++b) {
    ns[0][b] = round_to_int(single[b] * 1000);
    ns[1][b] = round_to_int(dual[b] * 1000);
  }
  return ns;
}
constexpr auto kPandar40BlockNs = block_ns(tables::pandar40_block_end_us_single, tables::pandar40_block_end_us_dual);
constexpr auto kPandar64BlockNs = block_ns(tables::pandar64_block_end_us_single, tables::pandar64_block_end_us_dual);
constexpr auto kQt128BlockNs = block_ns(tables::qt128_block_start_us_single, tables::qt128_block_start_us_dual);
// Pandar64 App. B.3: block 1 of 6 ends at t0 - 42.58 - 55.56 x 5 us, or x 2 in dual return.
static_assert(kPandar64BlockNs[0][0] == -320380 && kPandar64BlockNs[1][0] == -153700);
static_assert(kQt128BlockNs[0][1] == 120110 && kQt128BlockNs[1][1] == 9000);

}  // namespace

Error identify(ByteView p, Model& model, PacketKind& kind) noexcept {
  model = Model::unknown;
  kind = PacketKind::point_cloud;
  if (p.size < 4) return Error::bad_length;
  if (p[0] == 0xFF && p[1] == 0xEE) {
    // Pandar40 family (block preamble FF EE first) or a GPS packet.
    switch (p.size) {
      case kGpsBytes: kind = PacketKind::gps; return Error::ok;
      case pandar40::kPandar40Bytes: model = Model::pandar40; return Error::ok;
      case pandar40::kPandar40PBytes:
      case pandar40::kPandar40PSequenceBytes: model = Model::pandar40p; return Error::ok;
      default: return Error::bad_length;
    }
  }
  if (p[0] != 0xEE || p[1] != 0xFF) return Error::bad_magic;
  // Pandar64: EE FF, laser num 0x40, block num 0x06. QT128: EE FF, protocol 3.2, 0x80, 0x02.
  if (p[pandar64::kLaserNum] == 0x40 && p[pandar64::kBlockNum] == 0x06) {
    if (p.size != pandar64::kPacketBytes && p.size != pandar64::kSequencePacketBytes) return Error::bad_length;
    model = Model::pandar64;
    return Error::ok;
  }
  if (p[qt128::kVersionMajor] != 0x03 || p[qt128::kVersionMinor] != 0x02) return Error::unsupported_version;
  if (p.size < qt128::kHeaderEnd) return Error::bad_length;
  if (p[qt128::kLaserNum] != 0x80 || p[qt128::kBlockNum] != 0x02) return Error::unsupported_model;
  if (p.size != qt128::Layout::from_flags(p[qt128::kFlags]).total) return Error::flags_length_mismatch;
  model = Model::qt128c2x;
  return Error::ok;
}

const char* return_mode_name(std::uint8_t mode) noexcept {
  switch (static_cast<ReturnMode>(mode)) {
    case ReturnMode::first: return "first";
    case ReturnMode::second: return "second";
    case ReturnMode::strongest: return "strongest";
    case ReturnMode::last: return "last";
    case ReturnMode::last_strongest: return "last_strongest";
    case ReturnMode::first_second: return "first_second";
    case ReturnMode::first_last: return "first_last";
    case ReturnMode::first_strongest: return "first_strongest";
    case ReturnMode::strongest_second_strongest: return "strongest_second_strongest";
  }
  return "unknown";
}

Decoder::Decoder(Model model) noexcept : model_(model) {
  switch (model) {
    case Model::pandar40:
    case Model::pandar40p:
      for (std::size_t i = 0; i < pandar40::kChannels; ++i) {
        set_channel_angle(i, tables::pandar40_channel_angles[i].elevation_deg,
                          tables::pandar40_channel_angles[i].azimuth_deg);
        set_channel_firetime(i, tables::pandar40_firetime_us[i], tables::pandar40_firetime_us[i]);
      }
      break;
    case Model::pandar64:
      for (std::size_t i = 0; i < pandar64::kChannels; ++i) {
        set_channel_angle(i, tables::pandar64_channel_angles[i].elevation_deg,
                          tables::pandar64_channel_angles[i].azimuth_deg);
        set_channel_firetime(i, tables::pandar64_firetime_us[i], tables::pandar64_firetime_us[i]);
      }
      break;
    case Model::qt128c2x:
      for (std::size_t i = 0; i < qt128::kChannels; ++i) {
        set_channel_angle(i, tables::qt128_channel_angles[i].elevation_deg,
                          tables::qt128_channel_angles[i].azimuth_deg);
        set_channel_firetime(i, tables::qt128_firetime_us_loop1[i], tables::qt128_firetime_us_loop2[i]);
      }
      break;
    case Model::unknown: break;
  }
}

void Decoder::set_channel_angle(std::size_t ch, double elevation_deg, double azimuth_deg) noexcept {
  const SinCos e = sin_cos_deg(elevation_deg);
  const SinCos a = sin_cos_deg(azimuth_deg);
  geo_.cos_el_cos_az[ch] = static_cast<float>(e.cos * a.cos);
  geo_.cos_el_sin_az[ch] = static_cast<float>(e.cos * a.sin);
  geo_.sin_el[ch] = static_cast<float>(e.sin);
  geo_.elevation_deg[ch] = static_cast<float>(elevation_deg);
  geo_.azimuth_deg[ch] = static_cast<float>(azimuth_deg);
  spin_.rpm = SpinCache::kStale;
}

void Decoder::set_channel_firetime(std::size_t ch, double loop1_us, double loop2_us) noexcept {
  geo_.fire_ns[0][ch] = round_to_int(loop1_us * 1000);
  geo_.fire_ns[1][ch] = round_to_int(loop2_us * 1000);
  spin_.rpm = SpinCache::kStale;
}

void Decoder::update_spin(std::uint16_t rpm) noexcept {
  // Spin rate in radians per nanosecond: rpm x 2 pi / 60e9.
  const float omega = static_cast<float>(rpm) * static_cast<float>(2 * kPi / 60e9);
  constexpr float kRadToDeg = static_cast<float>(180.0 / kPi);
  // The Pandars fire one sequence (both loops hold the same times); the QT128 alternates two.
  const std::size_t loops = model_ == Model::qt128c2x ? 2 : 1;
  const std::size_t channels = channel_count(model_);
  for (std::size_t loop = 0; loop < loops; ++loop) {
    for (std::size_t ch = 0; ch < channels; ++ch) {
      // Beam azimuth b = azimuth offset + firing-time correction d (|d| < 0.01 rad: a short series).
      const float d = static_cast<float>(geo_.fire_ns[loop][ch]) * omega;
      const float cos_d = 1.0f - 0.5f * d * d;
      const float sin_d = d - d * d * d * (1.0f / 6.0f);
      const float cc = geo_.cos_el_cos_az[ch];
      const float cs = geo_.cos_el_sin_az[ch];
      spin_.dir_cos[loop][ch] = cc * cos_d - cs * sin_d;
      spin_.dir_sin[loop][ch] = cs * cos_d + cc * sin_d;
      // In [0, 360) (calibration offsets may be negative or reach 360 degrees).
      float az = geo_.azimuth_deg[ch] + d * kRadToDeg;
      while (az < 0) az += 360.0f;
      while (az >= 360.0f) az -= 360.0f;
      spin_.azimuth_deg[loop][ch] = az;
    }
  }
  spin_.rpm = rpm;
}

Error Decoder::set_angles(const AngleCorrection& angles) noexcept {
  if (angles.channels != channel_count(model_)) return Error::calib_channel_count;
  // Written so that NaN fails too. Checked before any change, so a refused file changes nothing.
  for (std::size_t i = 0; i < angles.channels; ++i) {
    if (!(angles.elevation_deg[i] >= -90.0 && angles.elevation_deg[i] <= 90.0)) return Error::invalid_argument;
    if (!(angles.azimuth_deg[i] >= -360.0 && angles.azimuth_deg[i] <= 360.0)) return Error::invalid_argument;
  }
  for (std::size_t i = 0; i < angles.channels; ++i) set_channel_angle(i, angles.elevation_deg[i], angles.azimuth_deg[i]);
  return Error::ok;
}

Error Decoder::set_firetimes(const FiretimeCorrection& f) noexcept {
  if (f.channels != channel_count(model_)) return Error::calib_channel_count;
  const bool two_loops = model_ == Model::qt128c2x;
  if (two_loops && f.loops != 2) return Error::calib_channel_count;
  for (std::size_t loop = 0; loop < f.loops && loop < 2; ++loop) {
    for (std::size_t i = 0; i < f.channels; ++i) {
      const double us = f.firetime_us[loop][i];
      if (f.fires[loop][i] && !(us >= -kMaxFiretimeUs && us <= kMaxFiretimeUs)) return Error::invalid_argument;
    }
  }
  for (std::size_t i = 0; i < f.channels; ++i) {
    std::array<double, 2> us{};
    for (std::size_t loop = 0; loop < 2; ++loop) {
      const std::size_t src = two_loops ? loop : 0;
      us[loop] = f.fires[src][i] ? f.firetime_us[src][i] : 0.0;
    }
    set_channel_firetime(i, us[0], us[1]);
  }
  return Error::ok;
}

void Decoder::set_session_key(const std::uint8_t key[32]) noexcept {
  key_.set(ByteView{key, 32});
  has_key_ = true;
}

void Decoder::clear_session_key() noexcept {
  key_.wipe();
  has_key_ = false;
}

void Decoder::update_gps(const GpsPacket& gps) noexcept {
  gps_time_ = gps.time;
  has_gps_ = true;
}

Error Decoder::validate(ByteView payload, PacketInfo& info) noexcept {
  info = PacketInfo{};
  Model m = Model::unknown;
  PacketKind kind = PacketKind::point_cloud;
  const Error e = identify(payload, m, kind);
  if (e != Error::ok) return e;
  if (kind != PacketKind::point_cloud || m != model_) return Error::model_mismatch;
  info.model = m;
  switch (m) {
    case Model::pandar40:
    case Model::pandar40p: return validate_pandar40(payload, info);
    case Model::pandar64: return validate_pandar64(payload, info);
    case Model::qt128c2x: return validate_qt128(payload, info);
    case Model::unknown: break;
  }
  return Error::unsupported_model;
}

template <std::size_t kPointBytes>
void Decoder::emit_block(const std::uint8_t* points, std::size_t channels, const PacketInfo& info,
                         std::size_t block, std::int64_t block_time_ns, std::size_t loop,
                         PacketPoints& out) const noexcept {
  const std::uint16_t block_azimuth = info.block_azimuth[block];
  const float block_deg = static_cast<float>(block_azimuth) * 0.01f;
  const SinCos ab = sin_cos_deg(static_cast<double>(block_azimuth) * 0.01);
  const float sin_a = static_cast<float>(ab.sin);
  const float cos_a = static_cast<float>(ab.cos);
  const float unit_m = static_cast<float>(info.dis_unit_mm) * 0.001f;
  const std::uint8_t return_index = info.returns == 2 ? static_cast<std::uint8_t>(block & 1) : 0;
  const std::uint8_t block_index = static_cast<std::uint8_t>(block);
  const std::uint16_t min_distance = model_ == Model::qt128c2x ? 2 : 1;  // QT128 reserves distance 1 as a marker
  const float* const dir_cos = spin_.dir_cos[loop].data();
  const float* const dir_sin = spin_.dir_sin[loop].data();
  const float* const azimuth_deg = spin_.azimuth_deg[loop].data();
  const float* const sin_el = geo_.sin_el.data();
  const float* const elevation_deg = geo_.elevation_deg.data();
  const std::int32_t* const fire_ns = geo_.fire_ns[loop].data();

  // Every channel's point is written at out.points[n] and kept (n advanced) only when its
  // distance is valid: no branch to mispredict. n <= the channels before this one, so the
  // write stays below blocks x channels <= kMaxPointsPerPacket.
  Point* const pts = out.points.data();
  std::size_t n = out.count;
  for (std::size_t ch = 0; ch < channels; ++ch) {
    const std::uint8_t* p = points + ch * kPointBytes;
    const std::uint16_t raw = load_le16(p);
    const float r = static_cast<float>(raw) * unit_m;
    // Point azimuth a + b by the angle-sum identities (dir_cos, dir_sin carry cos(e)).
    Point& o = pts[n];
    o.x = r * (sin_a * dir_cos[ch] + cos_a * dir_sin[ch]);
    o.y = r * (cos_a * dir_cos[ch] - sin_a * dir_sin[ch]);
    o.z = r * sin_el[ch];
    o.distance_m = r;
    // Both terms lie in [0, 360): one exact subtraction brings the sum into range.
    float az = block_deg + azimuth_deg[ch];
    if (az >= 360.0f) az -= 360.0f;
    o.azimuth_deg = az;
    o.elevation_deg = elevation_deg[ch];
    o.time_ns = block_time_ns + fire_ns[ch];
    o.intensity = p[2];
    o.channel = static_cast<std::uint8_t>(ch + 1);
    o.return_index = return_index;
    if constexpr (kPointBytes == 4) {
      o.confidence = p[3];
    } else {
      o.confidence = 0;
    }
    o.block = block_index;
    n += static_cast<std::size_t>(raw >= min_distance);
  }
  out.count = n;
}

Error Decoder::decode(ByteView payload, PacketInfo& info, PacketPoints& out) noexcept {
  out.count = 0;
  const Error e = validate(payload, info);
  if (e != Error::ok) return e;
  const std::uint16_t rpm = firetime_correction_ ? info.motor_rpm : 0;
  if (rpm != spin_.rpm) update_spin(rpm);
  const std::uint8_t* p = payload.data;
  const std::size_t dual = info.returns == 2 ? 1 : 0;
  switch (model_) {
    case Model::pandar40:
    case Model::pandar40p:
      for (std::size_t b = 0; b < pandar40::kBlocks; ++b)
        emit_block<pandar40::kPointBytes>(p + b * pandar40::kBlockBytes + pandar40::kBlockPoints, pandar40::kChannels,
                                          info, b, info.time_ns + kPandar40BlockNs[dual][b], 0, out);
      break;
    case Model::pandar64:
      for (std::size_t b = 0; b < pandar64::kBlocks; ++b)
        emit_block<pandar64::kPointBytes>(p + pandar64::kBody + b * pandar64::kBlockBytes + pandar64::kBlockPoints,
                                          pandar64::kChannels, info, b, info.time_ns + kPandar64BlockNs[dual][b], 0, out);
      break;
    case Model::qt128c2x: {
      // Mode flag bit 0: block 1 uses firing sequence 1 (loop 0) when set, sequence 2 otherwise;
      // in single return block 2 uses the other sequence, in dual return both blocks share one firing.
      const std::size_t loop1 = (info.mode_flag & 1) ? 0 : 1;
      for (std::size_t b = 0; b < qt128::kBlocks; ++b) {
        const std::size_t loop = (dual || b == 0) ? loop1 : 1 - loop1;
        emit_block<qt128::kPointBytes>(p + qt128::kBody + b * qt128::kBlockBytes + qt128::kBlockPoints,
                                       qt128::kChannels, info, b, info.time_ns + kQt128BlockNs[dual][b], loop, out);
      }
      break;
    }
    case Model::unknown: break;
  }
  return Error::ok;
}

}  // namespace hesai
