// The NEON kernels' shared parts (internal to the core; neon_columns.cpp and neon_points.cpp):
// the loads that turn a block's units into lanes of x, y, z and the kept mask, eight units a step
// as two vectors of four (EightUnits), and the byte shuffles that pack kept lanes. Compiled for
// every little-endian AArch64 target (NEON is part of ARMv8-A); empty on other targets.
#pragma once

#include "../base/compiler.h"
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_NEON)

#include <arm_neon.h>

#include <array>
#include <cstddef>
#include <cstdint>

namespace hesai::kernels {

// For each 4-bit mask of kept 32-bit lanes, the byte shuffle that packs them to the front.
constexpr std::array<std::array<std::uint8_t, 16>, 16> compress4_table() {
  std::array<std::array<std::uint8_t, 16>, 16> t{};
  for (std::size_t m = 0; m < 16; ++m) {
    for (auto& b : t[m]) b = 0xFF;  // out of range: vqtbl1q gives 0
    unsigned k = 0;
    for (unsigned lane = 0; lane < 4; ++lane) {
      if (!(m & (1u << lane))) continue;
      for (unsigned b = 0; b < 4; ++b) t[m][4 * k + b] = static_cast<std::uint8_t>(4 * lane + b);
      ++k;
    }
  }
  return t;
}
inline constexpr std::array<std::array<std::uint8_t, 16>, 16> kCompress4 = compress4_table();

inline uint8x16_t load_shuffle(const std::int8_t* p) noexcept { return vreinterpretq_u8_s8(vld1q_s8(p)); }

// 32-bit lanes kept by `keep` stored packed at `to`.
inline void store_packed(std::uint8_t* to, uint8x16_t lanes, unsigned keep) noexcept {
  vst1q_u8(to, vqtbl1q_u8(lanes, vld1q_u8(kCompress4[keep].data())));
}

// Whether the NEON kernels take k: `isa` is NEON and its blocks are whole steps of eight units.
inline bool neon_fits(const PacketConstants& k, VectorIsa isa) noexcept {
  return isa == VectorIsa::neon && k.units % 8 == 0;
}

// The channels 1..8 of the first eight units, as bytes.
HESAI_ALWAYS_INLINE inline uint8x8_t first_channels() noexcept {
  const std::uint8_t channels[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  return vld1_u8(channels);
}

// Eight units of a block, as both NEON loops read them, in two halves of four ([0]: units j ..
// j + 3): their fields and which are kept.
struct Eight {
  uint32x4_t raw[2];                // distances
  uint32x4_t kept[2];               // all ones where the distance is valid
  uint8x8_t intensity, confidence;  // unit i in byte i (confidence 0 for 3-byte units)
};

// The positions of one half of an Eight: the scalar loop's operations in its order
// (scalar_loops.h unit_xyz), no fused multiply-add.
struct Four {
  float32x4_t r, x, y, z;  // distance and x, y, z, metres
};

// The packet's constants as vectors (set up once per packet), the block's (once per block), and
// the steps from units to Eight and Four. A local object: its members stay in registers, where k
// may be aliased by the kernels' stores (k is read again once per block).
class EightUnits {
 public:
  HESAI_ALWAYS_INLINE explicit EightUnits(const PacketConstants& k) noexcept
      : k_(k), unit_bytes_(k.unit_bytes), sin_el_(k.sin_el), unit_m_(vdupq_n_f32(k.unit_m)),
        min_distance_(vdupq_n_u32(k.min_distance)) {
    const std::size_t wide = k.unit_bytes == 4 ? 1 : 0;
    second_ = kSecond[wide];
    const UnitShuffle& lo = kShuffle[wide][0];
    const UnitShuffle& hi = kShuffle[wide][1];
    lo_[0] = load_shuffle(lo.distance), lo_[1] = load_shuffle(lo.intensity), lo_[2] = load_shuffle(lo.confidence);
    hi_[0] = load_shuffle(hi.distance), hi_[1] = load_shuffle(hi.intensity), hi_[2] = load_shuffle(hi.confidence);
  }

  // Block b, with the sine and cosine of its azimuth.
  HESAI_ALWAYS_INLINE void start(const BlockRef& b, float sin_a, float cos_a) noexcept {
    units_ = b.units;
    sin_a_ = vdupq_n_f32(sin_a), cos_a_ = vdupq_n_f32(cos_a);
    dir_cos_ = k_.dir_cos[b.loop], dir_sin_ = k_.dir_sin[b.loop];
  }

  // Units j .. j + 7 of the block.
  HESAI_ALWAYS_INLINE Eight at(std::size_t j) const noexcept {
    const std::uint8_t* p = units_ + j * unit_bytes_;
    const uint8x16_t a = vld1q_u8(p);
    const uint8x16_t b = vld1q_u8(p + second_);
    Eight e;
    e.raw[0] = vreinterpretq_u32_u8(vqtbl1q_u8(a, lo_[0]));
    e.raw[1] = vreinterpretq_u32_u8(vqtbl1q_u8(b, hi_[0]));
    e.intensity = vorr_u8(vget_low_u8(vqtbl1q_u8(a, lo_[1])), vget_low_u8(vqtbl1q_u8(b, hi_[1])));
    e.confidence = vorr_u8(vget_low_u8(vqtbl1q_u8(a, lo_[2])), vget_low_u8(vqtbl1q_u8(b, hi_[2])));
    for (std::size_t h = 0; h < 2; ++h) e.kept[h] = vcgeq_u32(e.raw[h], min_distance_);
    return e;
  }

  // Half h of e, the Eight at units j .. j + 7: units j + 4h .. j + 4h + 3 (called where its
  // values are stored: both halves at once would hold eight more vectors).
  HESAI_ALWAYS_INLINE Four half(const Eight& e, std::size_t j, std::size_t h) const noexcept {
    const std::size_t c = j + 4 * h;
    Four f;
    f.r = vmulq_f32(vcvtq_f32_u32(e.raw[h]), unit_m_);
    const float32x4_t dc = vld1q_f32(dir_cos_ + c);
    const float32x4_t ds = vld1q_f32(dir_sin_ + c);
    f.x = vmulq_f32(f.r, vaddq_f32(vmulq_f32(sin_a_, dc), vmulq_f32(cos_a_, ds)));
    f.y = vmulq_f32(f.r, vsubq_f32(vmulq_f32(cos_a_, dc), vmulq_f32(sin_a_, ds)));
    f.z = vmulq_f32(f.r, vld1q_f32(sin_el_ + c));
    return f;
  }

 private:
  const PacketConstants& k_;
  std::size_t unit_bytes_, second_;
  const float* sin_el_;
  uint8x16_t lo_[3], hi_[3];  // byte shuffles: distance, intensity, confidence
  float32x4_t unit_m_;
  uint32x4_t min_distance_;
  // The block's.
  const std::uint8_t* units_ = nullptr;
  const float* dir_cos_ = nullptr;
  const float* dir_sin_ = nullptr;
  float32x4_t sin_a_, cos_a_;
};

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_NEON
