// The per-point arithmetic every sensor shares: one block's units to points (internal to the
// core; each sensor's file walks its own block layout and calls Decoder::emit_block per block).
// A unit is one channel's measurement; unit j is channel j, except in QT128 packets with
// customised channels, where the channel configuration maps it.
//
// x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e), with a = block azimuth + the channel's
// beam azimuth (offset + firing-time correction, cached per spin rate in Decoder::SpinCache).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "../base/compiler.h"
#include "hesai/decoder.h"
#include "hesai/math.h"

namespace hesai {

// Optimising for size (-Os, the firmware builds), every sensor calls one shared copy per unit
// size: inlined into each sensor's block walk it took 0.8 KB more flash on the Cortex-M0+.
// Optimising for speed it is inlined, where the constant channel count and the absent map of the
// Pandars make a shorter loop (8% fewer instructions per Pandar64 packet under callgrind).
template <std::size_t kUnitBytes>
HESAI_NOINLINE_FOR_SIZE void Decoder::emit_block(const std::uint8_t* units, std::size_t unit_count,
                                                 const std::uint8_t* channel_of, const PacketInfo& info,
                                                 std::size_t block, std::int64_t block_time_ns, std::size_t loop,
                                                 Point* out, std::size_t& count) const noexcept {
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

  // Every unit's point is written at out[n] and kept (n advanced) only when its distance is
  // valid: no branch to mispredict. n <= the units before this one, so the write stays below
  // blocks x channels = max_points(model_), the capacity decode() checked.
  Point* const pts = out;
  std::size_t n = count;
  // The loop twice: with a map (customised QT128 channels), and without, where unit j is
  // channel j and one induction variable walks every array (an identity map, or a test per
  // unit, cost 21-28% more instructions per packet under callgrind).
  const auto walk = [&](auto mapped) {
    for (std::size_t j = 0; j < unit_count; ++j) {
      const std::uint8_t* p = units + j * kUnitBytes;
      std::size_t ch = j;
      if constexpr (decltype(mapped)::value) ch = channel_of[j];
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
      if constexpr (kUnitBytes == 4) {
        o.confidence = p[3];
      } else {
        o.confidence = 0;
      }
      o.block = block_index;
      n += static_cast<std::size_t>(raw >= min_distance);
    }
  };
  if (channel_of != nullptr) walk(std::true_type{});
  else walk(std::false_type{});
  count = n;
}

}  // namespace hesai
