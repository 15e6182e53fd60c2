// The sensors this library decodes.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai {

/// A supported sensor model. Identified from a packet's length, magic and header fields.
enum class Model : std::uint8_t {
  unknown = 0,
  pandar40,   ///< Pandar40, older firmware: 1256-byte packets, 16-byte tail without date
  pandar40p,  ///< Pandar40P: 1262 bytes, 1266 with UDP sequence
  pandar64,   ///< Pandar64: 1194 bytes, 1198 with UDP sequence
  qt128c2x,   ///< QT128C2X, point cloud protocol 3.2: up to 1127 bytes
  pandar_qt64,     ///< PandarQT64, point cloud protocol 3.1
  pandar_xt16,     ///< PandarXT16, point cloud protocol 6.1
  pandar_xt32,     ///< PandarXT32, point cloud protocol 6.1
  pandar_xt32m2x,  ///< PandarXT32M2X, point cloud protocol 6.1
};

/// Number of models above, `unknown` included (for arrays indexed by Model).
inline constexpr std::size_t kModelCount = 9;

/// Display name: "Pandar40", "Pandar40P", "Pandar64", "QT128C2X", "PandarQT64", "PandarXT16",
/// "PandarXT32", "PandarXT32M2X" ("unknown").
constexpr const char* model_name(Model m) {
  switch (m) {
    case Model::pandar40: return "Pandar40";
    case Model::pandar40p: return "Pandar40P";
    case Model::pandar64: return "Pandar64";
    case Model::qt128c2x: return "QT128C2X";
    case Model::pandar_qt64: return "PandarQT64";
    case Model::pandar_xt16: return "PandarXT16";
    case Model::pandar_xt32: return "PandarXT32";
    case Model::pandar_xt32m2x: return "PandarXT32M2X";
    case Model::unknown: break;
  }
  return "unknown";
}

/// Laser channels of a model (0 for unknown).
constexpr std::size_t channel_count(Model m) {
  switch (m) {
    case Model::pandar40:
    case Model::pandar40p: return 40;
    case Model::pandar64:
    case Model::pandar_qt64: return 64;
    case Model::qt128c2x: return 128;
    case Model::pandar_xt16: return 16;
    case Model::pandar_xt32:
    case Model::pandar_xt32m2x: return 32;
    case Model::unknown: break;
  }
  return 0;
}

/// Blocks (azimuth columns) per packet.
constexpr std::size_t block_count(Model m) {
  switch (m) {
    case Model::pandar40:
    case Model::pandar40p: return 10;
    case Model::pandar64:
    case Model::pandar_xt32m2x: return 6;
    case Model::qt128c2x: return 2;
    case Model::pandar_qt64: return 4;
    case Model::pandar_xt16:
    case Model::pandar_xt32: return 8;
    case Model::unknown: break;
  }
  return 0;
}

/// The most points one packet of the model can hold: blocks x channels (400, 384, 256; 0 for
/// unknown). Storage for this many points suffices for any packet the model sends.
constexpr std::size_t max_points(Model m) { return block_count(m) * channel_count(m); }

/// The most channels of any model, and the most points one packet can hold (10 x 40).
inline constexpr std::size_t kMaxChannels = 128;
inline constexpr std::size_t kMaxPointsPerPacket = 400;
static_assert(max_points(Model::pandar40) <= kMaxPointsPerPacket && max_points(Model::pandar40p) <= kMaxPointsPerPacket &&
              max_points(Model::pandar64) <= kMaxPointsPerPacket && max_points(Model::qt128c2x) <= kMaxPointsPerPacket);

}  // namespace hesai
