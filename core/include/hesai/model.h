// The sensors this library decodes.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/model_list.h"  // the models, once for C++ and C (hesai.h)

namespace hesai {

/// A supported sensor model. Identified from a packet's length, magic and header fields. The
/// models, their names and their channel and block counts are listed once, in model_list.h.
enum class Model : std::uint8_t {
  unknown = 0,
#define HESAI_MODEL_ENUMERATOR(id, name, channels, blocks, firings, ptc) id,
  HESAI_MODEL_LIST(HESAI_MODEL_ENUMERATOR)
#undef HESAI_MODEL_ENUMERATOR
};

/// Number of models above, `unknown` included (for arrays indexed by Model).
#define HESAI_MODEL_PLUS_ONE(id, name, channels, blocks, firings, ptc) +1
inline constexpr std::size_t kModelCount = 1 HESAI_MODEL_LIST(HESAI_MODEL_PLUS_ONE);
#undef HESAI_MODEL_PLUS_ONE

namespace model_facts {
// Indexed by Model: entry 0 is `unknown`.
#define HESAI_MODEL_NAME(id, name, channels, blocks, firings, ptc) name,
inline constexpr const char* kNames[kModelCount] = {"unknown", HESAI_MODEL_LIST(HESAI_MODEL_NAME)};
#undef HESAI_MODEL_NAME
#define HESAI_MODEL_CHANNELS(id, name, channels, blocks, firings, ptc) channels,
inline constexpr std::uint8_t kChannels[kModelCount] = {0, HESAI_MODEL_LIST(HESAI_MODEL_CHANNELS)};
#undef HESAI_MODEL_CHANNELS
#define HESAI_MODEL_BLOCKS(id, name, channels, blocks, firings, ptc) blocks,
inline constexpr std::uint8_t kBlocks[kModelCount] = {0, HESAI_MODEL_LIST(HESAI_MODEL_BLOCKS)};
#undef HESAI_MODEL_BLOCKS
#define HESAI_MODEL_FIRINGS(id, name, channels, blocks, firings, ptc) firings,
inline constexpr std::uint16_t kFirings[kModelCount] = {0, HESAI_MODEL_LIST(HESAI_MODEL_FIRINGS)};
#undef HESAI_MODEL_FIRINGS
#define HESAI_MODEL_PTC(id, name, channels, blocks, firings, ptc) ptc,
inline constexpr std::uint8_t kPtcProduct[kModelCount] = {255, HESAI_MODEL_LIST(HESAI_MODEL_PTC)};
#undef HESAI_MODEL_PTC
}  // namespace model_facts

/// Display name: "Pandar40", "Pandar40P", "Pandar64", "QT128C2X", "PandarQT64", "PandarXT16",
/// "PandarXT32", "PandarXT32M2X" ("unknown", also for a value that is no model).
constexpr const char* model_name(Model m) {
  const auto i = static_cast<std::size_t>(m);
  return i < kModelCount ? model_facts::kNames[i] : "unknown";
}

/// Laser channels of a model (0 for unknown).
constexpr std::size_t channel_count(Model m) {
  const auto i = static_cast<std::size_t>(m);
  return i < kModelCount ? model_facts::kChannels[i] : 0;
}

/// Blocks (azimuth columns) per packet.
constexpr std::size_t block_count(Model m) {
  const auto i = static_cast<std::size_t>(m);
  return i < kModelCount ? model_facts::kBlocks[i] : 0;
}

/// Packets per rotation at 600 rpm with `returns` returns a firing (1, 2 or 3): the firings of a
/// rotation, `returns` blocks each, over the blocks of a packet, rounded up (the last packet of a
/// rotation may be partly of the next). Pandar64 in dual return: 1 800 x 2 / 6 = 600. Scales
/// inversely with the spin rate for the models whose azimuth step grows with it (all above). 0
/// for unknown.
constexpr std::size_t packets_per_rotation(Model m, std::size_t returns) {
  const auto i = static_cast<std::size_t>(m);
  if (i >= kModelCount || model_facts::kBlocks[i] == 0) return 0;
  return (model_facts::kFirings[i] * returns + model_facts::kBlocks[i] - 1) / model_facts::kBlocks[i];
}

/// The model byte a unit of this model reports in its PTC inventory (255: none, the Pandar40).
constexpr std::uint8_t ptc_product_number(Model m) {
  const auto i = static_cast<std::size_t>(m);
  return i < kModelCount ? model_facts::kPtcProduct[i] : 255;
}

/// The most points one packet of the model can hold: blocks x channels (400, 384, 256; 0 for
/// unknown). Storage for this many points suffices for any packet the model sends.
constexpr std::size_t max_points(Model m) { return block_count(m) * channel_count(m); }

/// The most channels of any model, and the most points one packet can hold (10 x 40).
inline constexpr std::size_t kMaxChannels = 128;
inline constexpr std::size_t kMaxPointsPerPacket = 400;
constexpr bool every_model_fits() {
  for (std::size_t i = 0; i < kModelCount; ++i)
    if (model_facts::kChannels[i] > kMaxChannels || max_points(static_cast<Model>(i)) > kMaxPointsPerPacket) return false;
  return true;
}
static_assert(every_model_fits(), "kMaxChannels and kMaxPointsPerPacket bound every model of model_list.h");

}  // namespace hesai
