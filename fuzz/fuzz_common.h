// Shared helpers of the libFuzzer harnesses: invariant checks that abort (__builtin_trap) on
// violation, an exactly-sized copy of the input, and the packet-decode checks every decoder
// harness runs. Hosted code (fuzz only): <cmath> and <vector> are fine here.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/error.h"

namespace hesai_fuzz {

/// Aborts the run when an invariant does not hold (a crash libFuzzer reports).
inline void check(bool ok) {
  if (!ok) __builtin_trap();
}

/// An error code must have a name.
inline void check_named(hesai::Error e) { check(std::strcmp(hesai::error_name(e), "unknown") != 0); }

/// The input copied into a heap buffer of exactly its size, so ASan sees any read past it.
struct ExactCopy {
  std::vector<std::uint8_t> bytes;
  ExactCopy(const std::uint8_t* data, std::size_t size) : bytes(data, data + size) {}
  hesai::ByteView view() const { return {bytes.empty() ? nullptr : bytes.data(), bytes.size()}; }
};

/// Bitwise equality of two values (floats compared as bits, so NaN == NaN).
template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

/// PacketInfo field by field (padding bytes excluded).
inline bool same_info(const hesai::PacketInfo& a, const hesai::PacketInfo& b) {
  const hesai::DateTime& da = a.date_time;
  const hesai::DateTime& db = b.date_time;
  const hesai::FunctionalSafety& fa = a.safety;
  const hesai::FunctionalSafety& fb = b.safety;
  return a.model == b.model && a.return_mode == b.return_mode && a.returns == b.returns && a.blocks == b.blocks &&
         a.dis_unit_mm == b.dis_unit_mm && a.motor_rpm == b.motor_rpm && a.block_azimuth == b.block_azimuth &&
         a.time_ns == b.time_ns && a.time_reference == b.time_reference && da.year == db.year &&
         da.month == db.month && da.day == db.day && da.hour == db.hour && da.minute == db.minute &&
         da.second == db.second && a.timestamp_us == b.timestamp_us && a.has_sequence == b.has_sequence &&
         a.sequence == b.sequence && a.high_temperature == b.high_temperature && a.factory_info == b.factory_info &&
         a.flags == b.flags && a.mode_flag == b.mode_flag && a.signature == b.signature &&
         fa.present == fb.present && fa.version == fb.version && fa.lidar_state == fb.lidar_state &&
         fa.fault_code_type == fb.fault_code_type && fa.rolling_counter == fb.rolling_counter &&
         fa.total_fault_codes == fb.total_fault_codes && fa.fault_code_id == fb.fault_code_id &&
         fa.fault_code == fb.fault_code;
}

/// Point field by field (floats as bits).
inline bool same_point(const hesai::Point& a, const hesai::Point& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z) && same_bits(a.distance_m, b.distance_m) &&
         same_bits(a.azimuth_deg, b.azimuth_deg) && same_bits(a.elevation_deg, b.elevation_deg) &&
         a.time_ns == b.time_ns && a.intensity == b.intensity && a.channel == b.channel &&
         a.return_index == b.return_index && a.confidence == b.confidence && a.block == b.block;
}

/// Checks one decoded packet against its layout and the physics of the sensor.
inline void check_points(hesai::Model model, const hesai::PacketInfo& info, const hesai::PacketPoints& out) {
  const std::size_t blocks = hesai::block_count(model);
  const std::size_t channels = hesai::channel_count(model);
  check(info.model == model);
  check(info.blocks <= blocks);
  check(info.returns >= 1 && info.returns <= 3 && info.blocks % info.returns == 0);  // 3: XT32M2X triple
  check(info.dis_unit_mm > 0);
  check(out.count <= blocks * channels && out.count <= hesai::kMaxPointsPerPacket);
  check(std::strcmp(hesai::return_mode_name(info.return_mode), "unknown") != 0);
  for (std::size_t b = 0; b < info.blocks; ++b) check(info.block_azimuth[b] < 36000);
  // Largest range: 65535 distance steps of dis_unit_mm (the decoder works in float: allow for
  // its rounding, a few ulp, e.g. 11534.1611 m for 65535 x 176 mm).
  const double max_range_m = 65535.0 * info.dis_unit_mm / 1000.0 * (1 + 1e-5) + 1e-3;
  for (std::size_t i = 0; i < out.count; ++i) {
    const hesai::Point& p = out.points[i];
    check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    check(std::isfinite(p.distance_m) && std::isfinite(p.azimuth_deg) && std::isfinite(p.elevation_deg));
    check(p.distance_m > 0 && p.distance_m <= max_range_m);
    const double r = std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
    check(std::fabs(r - p.distance_m) <= 1e-3 * p.distance_m + 1e-3);  // a point lies at its range
    check(p.azimuth_deg >= 0.0f && p.azimuth_deg <= 360.0f);
    check(p.elevation_deg >= -90.0f && p.elevation_deg <= 90.0f);
    check(p.channel >= 1 && p.channel <= channels);
    check(p.block < info.blocks);
    check(p.return_index < info.returns && p.return_index == p.block % info.returns);
    // Every channel fires within one packet period (well under 1 ms) of the packet time.
    const std::int64_t dt = p.time_ns - info.time_ns;
    check(dt > -2000000 && dt < 2000000);
  }
}

/// Decodes `payload` twice with `decoder` and checks every invariant. Returns the error.
[[nodiscard]] inline hesai::Error decode_checked(hesai::Decoder& decoder, hesai::ByteView payload) {
  static hesai::PacketPoints out1, out2;  // 16 KiB each: off the stack
  hesai::PacketInfo info1, info2, info3;
  out1.count = 12345;
  const hesai::Error e1 = decoder.decode(payload, info1, out1);
  const hesai::Error e2 = decoder.decode(payload, info2, out2);
  const hesai::Error e3 = decoder.validate(payload, info3);
  // survey(): the same verdict and info, and as many points as decode() made, none made.
  hesai::PacketInfo info4;
  hesai::UnitScan scan;
  std::size_t surveyed = 12345;
  const hesai::Error e4 = decoder.survey(payload, info4, scan, surveyed);
  check_named(e1);
  check(e1 == e2 && e1 == e3 && e1 == e4);
  if (e1 != hesai::Error::ok) {
    check(out1.count == 0 && out2.count == 0 && surveyed == 0);
    return e1;
  }
  check(same_info(info1, info2) && same_info(info1, info3) && same_info(info1, info4));
  check(out1.count == out2.count && surveyed == out1.count);
  for (std::size_t i = 0; i < out1.count; ++i) check(same_point(out1.points[i], out2.points[i]));
  check_points(decoder.model(), info1, out1);
  // A packet that decodes is one identify() recognises as this model.
  hesai::Model m = hesai::Model::unknown;
  hesai::PacketKind kind = hesai::PacketKind::gps;
  check(hesai::identify(payload, m, kind) == hesai::Error::ok);
  check(kind == hesai::PacketKind::point_cloud && m == decoder.model());
  return e1;
}

}  // namespace hesai_fuzz
