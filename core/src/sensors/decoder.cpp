// What every sensor shares: identification (the registry finds the sensor whose header a payload
// carries; its file holds the rule), decoder set-up from tables and calibration files, the
// per-spin-rate beam cache, and validate() and decode() by the sensor's descriptor. The
// per-point arithmetic is in block_points.h.
#include "hesai/decoder.h"

#include <cstddef>

#include "hesai/detail/math.h"
#include "../base/compiler.h"
#include "../kernels/beam_cache.h"
#include "../kernels/vector_isa.h"
#include "block_points.h"
#include "sensor.h"
#include "sensor_rules.h"

namespace hesai {

namespace {

/// Largest firing-time offset accepted, us: well beyond any block period of the manuals
/// (55.56 us Pandar, 111.11 us QT128); keeps the ns value in range of an int32.
constexpr double kMaxFiretimeUs = 1000.0;

}  // namespace

Error identify(ByteView p, Model& model, PacketKind& kind) noexcept {
  model = Model::unknown;
  kind = PacketKind::point_cloud;
  if (p.size < 4) return Error::bad_length;
  // Both GPS layouts start FF EE, as the Pandar40 family's first block does: 512 bytes tell them apart.
  if (is_gps_packet(p)) {
    kind = PacketKind::gps;
    return Error::ok;
  }
  if (const SensorDescriptor* s = sensor_claiming(p)) return s->identify(p, model);
  // EE FF headers name their point cloud protocol in bytes 2 (major) and 3 (minor).
  return p[0] == 0xEE && p[1] == 0xFF ? Error::unsupported_version : Error::bad_magic;
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
    case ReturnMode::first_last_strongest: return "first_last_strongest";
    case ReturnMode::strongest_second_strongest: return "strongest_second_strongest";
  }
  return "unknown";
}

Decoder::Decoder(Model model) noexcept : model_(model) {
  if (const SensorDescriptor* s = sensor_of(model)) s->design(*this);
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
  geo_.fire_ns[0][ch] = detail::round_to_int(loop1_us * 1000);
  geo_.fire_ns[1][ch] = detail::round_to_int(loop2_us * 1000);
  spin_.rpm = SpinCache::kStale;
}

void Decoder::find_resting_runs() noexcept {
  for (std::size_t loop = 0; loop < 2; ++loop) {
    std::size_t first = 0, count = 0, runs = 0;
    bool before = false;
    for (std::size_t ch = 0; ch < kMaxChannels; ++ch) {
      const bool rests = ((resting_[loop][ch / 8] >> (ch % 8)) & 1) != 0;
      if (rests && !before && runs++ == 0) first = ch;
      count += rests ? 1 : 0;
      before = rests;
    }
    resting_first_[loop] = static_cast<std::uint8_t>(first);
    resting_count_[loop] = runs <= 1 ? static_cast<std::uint8_t>(count) : kRestingScattered;
  }
}

void Decoder::set_rotation(Rotation rotation) noexcept {
  if (rotation == rotation_) return;
  rotation_ = rotation;
  spin_.rpm = SpinCache::kStale;
}


void Decoder::update_spin(std::uint16_t rpm, unsigned loops, DecodePath path) const noexcept {
  // Spin rate in radians per nanosecond: rpm x 2 pi / 60e9, negative for a counter-clockwise
  // unit: azimuths grow clockwise whichever way it spins (Pandar40 manual Section 4.2, item 6), so a
  // channel fired later lies further clockwise on a clockwise unit and further back on the other.
  const float turn = rotation_ == Rotation::clockwise ? 1.0f : -1.0f;
  const float omega = turn * static_cast<float>(rpm) * static_cast<float>(2 * kPi / 60e9);
  // The Pandars fire one sequence (both loops hold the same times); the QT128 alternates two.
  const SensorDescriptor* sensor = sensor_of(model_);
  const std::size_t firing_loops = sensor != nullptr ? sensor->firing_loops : 1;
  const std::size_t channels = channel_count(model_);
  const kernels::VectorIsa isa = kernels::vector_isa(path);
  const auto beams = [&](std::size_t loop) {
    return kernels::BeamLoop{geo_.fire_ns[loop].data(),         geo_.cos_el_cos_az.data(),
                             geo_.cos_el_sin_az.data(),         geo_.azimuth_deg.data(),
                             spin_.loop[loop].dir_cos.data(),   spin_.loop[loop].dir_sin.data(),
                             spin_.loop[loop].azimuth_deg.data()};
  };
  if (rpm == spin_.rpm) {  // the rate's spread is known: the arrays of the stale loops this packet uses
    for (std::size_t loop = 0; loop < firing_loops; ++loop) {
      const unsigned bit = 1u << loop;
      if ((spin_.stale_loops & loops & bit) == 0) continue;
      std::int32_t lo = 0, hi = 0;
      kernels::rebuild_beams(beams(loop), channels, omega, isa, lo, hi);
      spin_.stale_loops = static_cast<std::uint8_t>(spin_.stale_loops & ~bit);
    }
    return;
  }
  // A new rate: the spread of every loop, by the whole rebuild for the loops this packet uses and
  // by the azimuths alone for the others where the CPU path has that loop (the QT128 with a
  // rate change on every packet: 1.5 loops' work instead of 2).
  std::int32_t lo = kernels::order_key(180.0f), hi = kernels::order_key(-180.0f);
  unsigned stale = 0;
  for (std::size_t loop = 0; loop < firing_loops; ++loop) {
    const unsigned bit = 1u << loop;
    if ((loops & bit) == 0 && kernels::spread_of_beams(beams(loop), channels, omega, isa, lo, hi))
      stale |= bit;
    else
      kernels::rebuild_beams(beams(loop), channels, omega, isa, lo, hi);
  }
  spin_.spread = channels != 0 ? AzimuthSpread{kernels::from_order_key(lo), kernels::from_order_key(hi)} : AzimuthSpread{};
  spin_.rpm = rpm;
  spin_.stale_loops = static_cast<std::uint8_t>(stale);
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
  const SensorDescriptor* sensor = sensor_of(model_);
  const bool two_loops = sensor != nullptr && sensor->firing_loops == 2;
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
    if (two_loops)
      for (std::size_t loop = 0; loop < 2; ++loop) SensorBase::set_resting(*this, loop, i, !f.fires[loop][i]);
  }
  find_resting_runs();
  return Error::ok;
}

Error Decoder::set_session_key(const std::uint8_t key[32]) noexcept {
#if HESAI_SIGNATURE
  key_.set(ByteView{key, 32});
  has_key_ = true;
  return Error::ok;
#else
  (void)key;
  return Error::unsupported_feature;
#endif
}

void Decoder::clear_session_key() noexcept {
#if HESAI_SIGNATURE
  key_.wipe();
#endif
  has_key_ = false;
}

void Decoder::update_gps(const GpsPacket& gps) noexcept {
  gps_time_ = gps.time;
  has_gps_ = true;
}

Error Decoder::validate(ByteView payload, PacketInfo& info) noexcept {
  // Copied from a constant: on Cortex-M, assigning PacketInfo{} zeroed a temporary byte by byte
  // (picolibc's memset) before copying it, about 600 instructions.
  static constexpr PacketInfo kNoPacket{};
  info = kNoPacket;
  Model m = Model::unknown;
  PacketKind kind = PacketKind::point_cloud;
  const Error e = identify(payload, m, kind);
  if (e != Error::ok) return e;
  if (kind != PacketKind::point_cloud || m != model_) return Error::model_mismatch;
  info.model = m;
  return sensor_of(m)->validate(*this, payload, info);  // identify() named a model of the registry
}

Error Decoder::decode(ByteView payload, PacketInfo& info, PacketPoints& out, DecodePath path) noexcept {
  return decode(payload, info, out.points.data(), out.points.size(), out.count, path);
}

Error Decoder::decode(ByteView payload, PacketInfo& info, PacketPoints& out, UnitScan& scan, Returns returns,
                      DecodePath path) noexcept {
  return decode(payload, info, out.points.data(), out.points.size(), out.count, scan, returns, path);
}

namespace {

// Each unit against the other returns of its firing, raw (ReturnComparison, decoder.h), into the
// ReturnComparison at `into`, which the caller reset; every block's points are made too. Reached
// only through the decode() form that takes a ReturnComparison.
std::size_t compare_returns(const kernels::BlockRef* blocks, std::size_t block_count, std::size_t unit_count,
                            std::size_t unit_bytes, const PacketInfo& info, void* into) noexcept {
  ReturnComparison& compare = *static_cast<ReturnComparison*>(into);
  const std::size_t returns = info.returns;
  if (returns < 2 || block_count > kMaxBlocksPerPacket) return block_count;
  for (std::size_t first = 0; first + returns <= block_count; first += returns) {
    for (std::size_t b = first; b < first + returns; ++b) {
      const std::uint8_t* u = blocks[b].units;
      for (std::size_t j = 0; j < unit_count; ++j, u += unit_bytes) {
        bool same = false, below = false;
        for (std::size_t o = first; o < first + returns; ++o) {
          if (o == b) continue;
          const std::uint8_t* v = blocks[o].units + j * unit_bytes;
          same = same || (load_le16(u) == load_le16(v) && u[2] == v[2]);
          below = below || u[2] < v[2];
        }
        const std::uint8_t ch = blocks[b].channel_of != nullptr ? blocks[b].channel_of[j] : static_cast<std::uint8_t>(j);
        const std::size_t byte = (ch % kMaxChannels) / 8;
        const auto bit = static_cast<std::uint8_t>(1u << (ch % 8));
        if (same) compare.identical[b][byte] |= bit;
        if (below) compare.weaker[b][byte] |= bit;
      }
    }
  }
  return block_count;
}

// The units whose distance makes a point (raw >= the model's smallest, as the kernels keep them).
template <std::size_t kUnitBytes>
std::size_t count_kept(const kernels::BlockRef* blocks, std::size_t block_count, std::size_t unit_count,
                       std::uint32_t min_distance) noexcept {
  std::size_t n = 0;
  for (std::size_t b = 0; b < block_count; ++b) {
    const std::uint8_t* u = blocks[b].units;
    for (std::size_t j = 0; j < unit_count; ++j, u += kUnitBytes) n += load_le16(u) >= min_distance ? 1u : 0u;
  }
  return n;
}

// What survey() asks of a packet's units: the scan (reset by the caller) and the point count.
struct Survey {
  UnitScan* scan;
  std::size_t points;
  DecodePath path;
};

// The unit scan and the points decode() (Returns::all) would make of the packet, into the Survey
// at `into`; no point made (no block left). Reached only through survey().
std::size_t survey_units(const kernels::BlockRef* blocks, std::size_t block_count, std::size_t unit_count,
                         std::size_t unit_bytes, const PacketInfo& info, void* into) noexcept {
  Survey& s = *static_cast<Survey*>(into);
  const std::uint16_t min_distance = sensor_of(info.model)->min_distance;  // validate() named the model
  // Every sensor's units are 3 or 4 bytes (emit_blocks' instances): the scan and the count want it known.
  if (unit_bytes == 3) {
    scan_packet<3>(blocks, block_count, unit_count, info, min_distance, s.path, *s.scan);
    s.points = count_kept<3>(blocks, block_count, unit_count, min_distance);
  } else {
    scan_packet<4>(blocks, block_count, unit_count, info, min_distance, s.path, *s.scan);
    s.points = count_kept<4>(blocks, block_count, unit_count, min_distance);
  }
  return 0;
}

// `scan = UnitScan{}`, by word stores on the ARMv7E-M: the assignment is a memset call, which
// picolibc runs a byte at a time (214 bytes: 856 instructions a packet on the Cortex-M4F, 1.5 times
// what the scan folded into the assembly loops costs). Elsewhere as it is (the Cortex-M0+ flash).
HESAI_ALWAYS_INLINE inline void reset_scan(UnitScan& scan) noexcept {
#if defined(HESAI_KERNELS_ARMV7M)
  // The arrays as one run of bytes, four unaligned word stores a step (ARMv7-M has them; `scan`
  // is 2-byte aligned).
  constexpr std::size_t kFirst = offsetof(UnitScan, blockage_by_channel), kBytes = sizeof(UnitScan) - kFirst;
  static_assert(offsetof(UnitScan, repeated) == kFirst + kMaxChannels && kBytes % 16 == 0, "the arrays, one run");
  const std::uint32_t zero = 0;
  scan.blockage_units = scan.duplicate_returns = scan.beyond_rated_range = 0;
  std::uint8_t* const bytes = reinterpret_cast<std::uint8_t*>(&scan) + kFirst;
  for (std::size_t i = 0; i < kBytes; i += 16) {
    __builtin_memcpy(bytes + i, &zero, 4), __builtin_memcpy(bytes + i + 4, &zero, 4);
    __builtin_memcpy(bytes + i + 8, &zero, 4), __builtin_memcpy(bytes + i + 12, &zero, 4);
  }
#else
  scan = UnitScan{};
#endif
}

// With Returns::distinct, the second returns the scan found repeated left out of points[0, count),
// keeping the order of the rest; the new count. Inlined into both callers (the M0+ flash budget).
HESAI_ALWAYS_INLINE inline std::size_t leave_out_repeats(Point* points, std::size_t count, const UnitScan& scan,
                                                         Returns returns) noexcept {
  if (returns != Returns::distinct || scan.duplicate_returns == 0) return count;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Point& p = points[i];
    const std::size_t firing = p.block / 2u, ch = static_cast<std::size_t>(p.channel - 1u) % kMaxChannels;
    const bool repeated = p.block % 2u == 1u && firing < kMaxDualFirings &&
                          (static_cast<unsigned>(scan.repeated[firing][ch / 8]) >> (ch % 8) & 1u) != 0;
    if (!repeated) points[kept++] = p;
  }
  return kept;
}

}  // namespace

Error Decoder::decode(ByteView payload, PacketInfo& info, PacketPoints& out, UnitScan& scan,
                      ReturnComparison& compare, Returns returns, DecodePath path) noexcept {
  // decode_into()'s steps with the comparison handed to the walk. It is not a parameter of
  // decode_into(): every other form would pass it, 130 bytes more on the Cortex-M0+.
  reset_scan(scan);
  compare = ReturnComparison{};
  out.count = 0;
  const Error e = validate(payload, info);  // PacketPoints holds any model's points
  if (e != Error::ok) return e;
  DecodeOutput o;
  o.points = out.points.data();
  o.path = path;
  o.scan = &scan;
  o.units = UnitPass{&compare, compare_returns};
  sensor_of(model_)->walk(*this, payload.data, info, o);  // validate() found model_'s packet
  out.count = leave_out_repeats(out.points.data(), o.count, scan, returns);
  return Error::ok;
}

Error Decoder::decode(ByteView payload, PacketInfo& info, Point* points, std::size_t capacity, std::size_t& count,
                      UnitScan& scan, Returns returns, DecodePath path) noexcept {
  reset_scan(scan);
  if (points == nullptr) {
    count = 0;
    return Error::invalid_argument;
  }
  const Error e = decode_into(payload, info, points, nullptr, capacity, count, path, &scan);
  if (e == Error::ok) count = leave_out_repeats(points, count, scan, returns);
  return e;
}


Error Decoder::decode(ByteView payload, PacketInfo& info, Point* points, std::size_t capacity, std::size_t& count,
                      DecodePath path) noexcept {
  return decode_into(payload, info, points, nullptr, capacity, count, path);
}

Error Decoder::decode(ByteView payload, PacketInfo& info, const PointColumns& columns, std::size_t& count,
                      DecodePath path) noexcept {
  if (columns.x == nullptr || columns.y == nullptr || columns.z == nullptr || columns.time_ns == nullptr ||
      columns.intensity == nullptr || columns.channel == nullptr || columns.return_index == nullptr) {
    count = 0;
    return Error::invalid_argument;
  }
  return decode_into(payload, info, nullptr, &columns, columns.capacity, count, path);
}

Error Decoder::decode(ByteView payload, PacketInfo& info, const PointColumns& columns, std::size_t& count,
                      UnitScan& scan, DecodePath path) noexcept {
  reset_scan(scan);
  if (columns.x == nullptr || columns.y == nullptr || columns.z == nullptr || columns.time_ns == nullptr ||
      columns.intensity == nullptr || columns.channel == nullptr || columns.return_index == nullptr) {
    count = 0;
    return Error::invalid_argument;
  }
  return decode_into(payload, info, nullptr, &columns, columns.capacity, count, path, &scan);
}

Error Decoder::survey(ByteView payload, PacketInfo& info, UnitScan& scan, std::size_t& points,
                      DecodePath path) noexcept {
  reset_scan(scan);
  points = 0;
  const Error e = validate(payload, info);
  if (e != Error::ok) return e;
  // The spread at the packet's rate, as decode() would leave it, without the per-rate arrays
  // where the CPU path computes the spread alone (elsewhere update_spin() rebuilds them whole):
  // the loops left stale are rebuilt by the next decode() that uses them (the same bits). The walk
  // sees none stale, so that it does not rebuild them now.
  const std::uint16_t rpm = firetime_correction_ ? info.motor_rpm : 0;
  if (rpm != spin_.rpm) update_spin(rpm, 0, path);
  const std::uint8_t stale = spin_.stale_loops;
  spin_.stale_loops = 0;
  Survey survey{&scan, 0, path};
  DecodeOutput o;
  o.units = UnitPass{&survey, survey_units};
  sensor_of(model_)->walk(*this, payload.data, info, o);  // validate() found model_'s packet
  spin_.stale_loops = stale;
  points = survey.points;
  return Error::ok;
}

bool decode_simd_available() noexcept {
  const kernels::VectorIsa isa = kernels::vector_isa(DecodePath::best);
  return isa != kernels::VectorIsa::none && isa != kernels::VectorIsa::armv7m;  // the ARMv7E-M loops are scalar
}
const char* decode_simd_name() noexcept { return kernels::vector_isa_name(kernels::vector_isa(DecodePath::best)); }

Error Decoder::decode_into(ByteView payload, PacketInfo& info, Point* points, const PointColumns* columns,
                           std::size_t capacity, std::size_t& count, DecodePath path, UnitScan* scan) noexcept {
  count = 0;
  if (capacity < max_points(model_)) return Error::buffer_too_small;
  const Error e = validate(payload, info);
  if (e != Error::ok) return e;
  DecodeOutput out;
  out.points = points;
  if (columns != nullptr) out.columns = *columns;
  out.path = path;
  out.scan = scan;
  sensor_of(model_)->walk(*this, payload.data, info, out);  // validate() found model_'s packet
  count = out.count;
  return Error::ok;
}

}  // namespace hesai
