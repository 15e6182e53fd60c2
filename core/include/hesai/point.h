// One decoded lidar point and the fixed-size storage for one packet's points; the columnar form
// of the same points (x, y, z, time, intensity, channel, return) in caller storage.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/model.h"

namespace hesai {

/// A measured point in the manuals' frame: Y axis at azimuth 0, azimuth clockwise seen from
/// above, Z up. x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e).
struct Point {
  float x = 0;              ///< metres
  float y = 0;              ///< metres
  float z = 0;              ///< metres
  float distance_m = 0;     ///< range along the beam, metres
  float azimuth_deg = 0;    ///< horizontal angle a in [0, 360): block + channel offset + firing-time correction
  float elevation_deg = 0;  ///< vertical angle e, degrees, up positive
  std::int64_t time_ns = 0; ///< firing time of this channel: ns since the Unix epoch (UTC), see PacketInfo::time_reference
  std::uint8_t intensity = 0;    ///< reflectivity byte as sent (0..255); Pandar64 with Reflectivity::nonlinear: percent (Appendix D)
  std::uint8_t channel = 0;      ///< laser channel, 1-based as in the manuals (customised QT128 units: mapped)
  std::uint8_t return_index = 0; ///< 0 for single return; in dual return 0 = odd block, 1 = even block; in triple return (PandarXT32M2X) 0, 1, 2 = blocks 1, 2, 3 of the firing
  std::uint8_t confidence = 0;   ///< QT128 confidence byte (units of 4 bytes, flags bit 4); 0 otherwise
  std::uint8_t block = 0;        ///< 0-based block index in the packet
};

/// Caller-owned storage for the points of one packet (at most 10 x 40 points). Only the first
/// `count` are points; decoding may overwrite the entries after them too.
struct PacketPoints {
  std::array<Point, kMaxPointsPerPacket> points;
  std::size_t count = 0;

  const Point* begin() const { return points.data(); }
  const Point* end() const { return points.data() + count; }
};

/// Caller-owned columns for one packet's points: the compact form firmware, GPUs and point-cloud
/// messages consume (19 bytes a point instead of a Point's 40). Column i of every array is the
/// same point as PacketPoints::points[i] of a decode of the same packet (the same order and count:
/// distance 0 yields no point); the fields a Point adds derive from these and the PacketInfo:
/// distance = |(x, y, z)|, block = by count per block, time_ns = info.time_ns + time_ns[i].
/// Each pointer addresses `capacity` elements; decode() needs capacity >= max_points(model) and
/// may overwrite every element below max_points(model), not only the first `count`.
struct PointColumns {
  float* x = nullptr;                     ///< metres (Point::x)
  float* y = nullptr;                     ///< metres
  float* z = nullptr;                     ///< metres
  std::int32_t* time_ns = nullptr;        ///< firing time, ns from the packet time PacketInfo::time_ns
  std::uint8_t* intensity = nullptr;      ///< as Point::intensity
  std::uint8_t* channel = nullptr;        ///< as Point::channel (1-based)
  std::uint8_t* return_index = nullptr;   ///< as Point::return_index
  std::size_t capacity = 0;
};

/// Columns with storage for N points inside: PacketColumns<max_points(Model::qt128c2x)> holds a
/// QT128 packet in 4 872 bytes on 64-bit targets (PacketPoints: 16 008). `count` is set by Decoder::decode.
template <std::size_t N>
struct PacketColumns {
  std::array<float, N> x, y, z;
  std::array<std::int32_t, N> time_ns;
  std::array<std::uint8_t, N> intensity, channel, return_index;
  std::size_t count = 0;

  PointColumns columns() noexcept {
    return {x.data(), y.data(), z.data(), time_ns.data(), intensity.data(), channel.data(), return_index.data(), N};
  }
};

/// Which per-point code decode() runs: the best the CPU has (x86-64, chosen at run time from
/// CPUID: AVX-512 where present, else AVX2; AArch64: NEON; Cortex-M4F and M7: the ARMv7E-M
/// assembly loops), the portable scalar code every target has (the only one on other Cortex-M
/// cores), or `avx2`: the AVX2 code even where AVX-512 is
/// present, for tests and benchmarks (elsewhere the same as `best`). Every path gives the same
/// points: the same float operations in the same order (tests/kernels/test_columns.cpp).
enum class DecodePath : std::uint8_t { best, portable, avx2 };

}  // namespace hesai
