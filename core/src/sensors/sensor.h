// The registry of sensors (internal to the core). Each sensor's file (pandar40.cpp, pandar64.cpp,
// qt128.cpp, qt64.cpp, xt.cpp) exports one SensorDescriptor: the models it decodes, how it
// recognises their packets, their design tables, validation and block walk. registry.cpp lists
// the descriptors, one line each; decoder.cpp, the C interface and the port ask the registry
// instead of naming models.
//
// A sensor's functions work on the decoder's state: they are the static members of
// SensorCode<the sensor's tag>, which Decoder befriends, and they share what SensorBase holds
// (the design-table set-up and the hand-over of a packet's blocks to the per-point code).
//
// Adding a sensor: its line in hesai/model_list.h, its file here with its descriptor, one line
// in registry.cpp (its descriptor and models; a model without one does not compile), and its
// tests (docs/DESIGN.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/decoder.h"
#include "hesai/detail/tables/table_types.h"
#include "hesai/error.h"
#include "hesai/model.h"
#include "../kernels/kernel_inputs.h"  // HESAI_KERNELS_ARMV7M

namespace hesai {

struct DecodeOutput;  // where a decode writes: Points or columns (block_points.h)

namespace kernels {
struct BlockRef;  // one block of a packet for the per-point code (kernels/kernel_inputs.h)
}

/// One sensor's code, as the registry lists it.
struct SensorDescriptor {
  /// The first bytes of this sensor's packets (magic, then protocol or lasers and blocks), of
  /// which the first `header_bytes` (2 or 4) are compared: a payload that starts so is this
  /// sensor's to identify (the sensors' headers do not overlap).
  std::uint8_t header[4];
  std::uint8_t header_bytes;
  /// The model of a claimed payload, from its length and header fields; identify()'s errors.
  Error (*identify)(ByteView p, Model& model) noexcept;
  /// Loads the manual's design angles and firing times for d.model() (the Decoder constructor).
  void (*design)(Decoder& d) noexcept;
  /// Every check and field of an identified packet of d.model() (Decoder::validate, after identify).
  Error (*validate)(Decoder& d, ByteView p, PacketInfo& info) noexcept;
  /// Hands a validated packet's blocks to the per-point code (SensorBase::emit_blocks).
  void (*walk)(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept;
  /// Where the UDP sequence number of an identified packet is (0: it has none), and, when the
  /// sensor seals its packets with CRCs, what rewrites them after a change (else nullptr).
  std::size_t (*sequence_at)(ByteView p) noexcept;
  Error (*seal)(std::uint8_t* payload, std::size_t size) noexcept;
  /// Firing sequences whose times differ (the QT128C2X alternates 2; the others fire 1).
  std::uint8_t firing_loops;
  /// Raw distances below it yield no point (the QT128C2X reserves distance 1 as a marker).
  std::uint16_t min_distance;
};

/// The registry (registry.cpp, which also names the models each file decodes): the descriptor of
/// `model`'s file (nullptr for unknown), and the descriptor whose header a payload of at least 4 bytes starts
/// with (nullptr: none's).
const SensorDescriptor* sensor_of(Model model) noexcept;
const SensorDescriptor* sensor_claiming(ByteView p) noexcept;

/// What every sensor's code shares; a friend of Decoder.
struct SensorBase {
  /// An EE FF header of point cloud protocol major.minor (bytes 2 and 3), as the QT128C2X, the
  /// PandarQT64 and the XT family send (the Pandar64 puts its laser and block counts there).
  static bool ee_ff_protocol(ByteView p, std::uint8_t major, std::uint8_t minor) noexcept {
    return p[0] == 0xEE && p[1] == 0xFF && p[2] == major && p[3] == minor;
  }
  /// Design tables: channel i's elevation and azimuth offset (degrees) and its firing time in
  /// each of the two loops (us).
  static void set_channel(Decoder& d, std::size_t ch, double elevation_deg, double azimuth_deg, double loop1_us,
                          double loop2_us) noexcept {
    d.set_channel_angle(ch, elevation_deg, azimuth_deg);
    d.set_channel_firetime(ch, loop1_us, loop2_us);
  }
  /// QT128C2X: marks 0-based channel `ch` as resting, or not, in firing sequence `loop` (0 or 1);
  /// Decoder::find_resting_runs() afterwards.
  static void set_resting(Decoder& d, std::size_t loop, std::size_t ch, bool rests) noexcept {
    auto& mask = d.resting_[loop];
    const auto bit = static_cast<unsigned>(1u << (ch % 8));
    mask[ch / 8] = static_cast<std::uint8_t>(rests ? mask[ch / 8] | bit : mask[ch / 8] & ~bit);
  }
  /// The manuals' design tables: each channel's angles and its firing time in each of the two
  /// loops (the same array twice for a sensor that fires one sequence).
  template <std::size_t N>
  static void set_design_tables(Decoder& d, const std::array<tables::ChannelAngle, N>& angles,
                                const std::array<double, N>& loop1_us, const std::array<double, N>& loop2_us) noexcept {
    for (std::size_t i = 0; i < N; ++i)
      set_channel(d, i, angles[i].elevation_deg, angles[i].azimuth_deg, loop1_us[i], loop2_us[i]);
  }
  /// The float design tables of the models without a manual here (PandarQT64, PandarXT): one
  /// firing sequence; azimuth_deg nullptr when every azimuth offset is 0.
  template <std::size_t N>
  static void set_design_tables(Decoder& d, const std::array<float, N>& elevation_deg, const float* azimuth_deg,
                                const std::array<float, N>& firetime_us) noexcept {
    for (std::size_t i = 0; i < N; ++i) {
      const auto us = static_cast<double>(firetime_us[i]);
      set_channel(d, i, static_cast<double>(elevation_deg[i]),
                  azimuth_deg != nullptr ? static_cast<double>(azimuth_deg[i]) : 0.0, us, us);
    }
  }
  /// The per-point code for a packet's blocks: block b is blocks[b], each of unit_count units of
  /// kUnitBytes (block_points.h).
  template <std::size_t kUnitBytes>
  static void emit_blocks(const Decoder& d, const kernels::BlockRef* blocks, std::size_t block_count,
                          std::size_t unit_count, const PacketInfo& info, DecodeOutput& out) noexcept;
#if defined(HESAI_KERNELS_ARMV7M)
  /// The same by the ARMv7E-M assembly loops (block_points.h).
  template <std::size_t kUnitBytes>
  static void emit_blocks_armv7m(const Decoder& d, const kernels::BlockRef* blocks, std::size_t block_count,
                                 std::size_t unit_count, float unit_m, std::uint16_t min_distance,
                                 const PacketInfo& info, DecodeOutput& out) noexcept;
#endif
};

/// A sensor's functions, declared once here and defined in the sensor's file for its own tag
/// (`template <> Error SensorCode<Qt128Tag>::validate(...)`), where descriptor() then makes its
/// SensorDescriptor. Each has the contract of the descriptor's member of the same name.
template <class Tag>
struct SensorCode : SensorBase {
  static Error identify(ByteView p, Model& model) noexcept;
  static void design(Decoder& d) noexcept;
  static Error validate(Decoder& d, ByteView p, PacketInfo& info) noexcept;
  static void walk(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept;
  static std::size_t sequence_at(ByteView p) noexcept;

  /// The descriptor of the functions above, with the sensor's header, seal (nullptr: none),
  /// firing sequences and smallest distance.
  static constexpr SensorDescriptor descriptor(std::array<std::uint8_t, 4> header, std::uint8_t header_bytes,
                                               Error (*seal)(std::uint8_t*, std::size_t) noexcept,
                                               std::uint8_t firing_loops, std::uint16_t min_distance) {
    return {{header[0], header[1], header[2], header[3]}, header_bytes, identify, design, validate, walk, sequence_at,
            seal, firing_loops, min_distance};
  }
};

}  // namespace hesai
