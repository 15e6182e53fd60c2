// One decoded lidar point and the fixed-size storage for one packet's points.
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
  std::uint8_t return_index = 0; ///< 0 for single return; in dual return 0 = odd block, 1 = even block
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

}  // namespace hesai
