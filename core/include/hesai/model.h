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
#define HESAI_MODEL_ENUMERATOR(id, name, channels, blocks) id,
  HESAI_MODEL_LIST(HESAI_MODEL_ENUMERATOR)
#undef HESAI_MODEL_ENUMERATOR
};

/// Number of models above, `unknown` included (for arrays indexed by Model).
#define HESAI_MODEL_PLUS_ONE(id, name, channels, blocks) +1
inline constexpr std::size_t kModelCount = 1 HESAI_MODEL_LIST(HESAI_MODEL_PLUS_ONE);
#undef HESAI_MODEL_PLUS_ONE

namespace model_facts {
// Indexed by Model: entry 0 is `unknown`.
#define HESAI_MODEL_NAME(id, name, channels, blocks) name,
inline constexpr const char* kNames[kModelCount] = {"unknown", HESAI_MODEL_LIST(HESAI_MODEL_NAME)};
#undef HESAI_MODEL_NAME
#define HESAI_MODEL_CHANNELS(id, name, channels, blocks) channels,
inline constexpr std::uint8_t kChannels[kModelCount] = {0, HESAI_MODEL_LIST(HESAI_MODEL_CHANNELS)};
#undef HESAI_MODEL_CHANNELS
#define HESAI_MODEL_BLOCKS(id, name, channels, blocks) blocks,
inline constexpr std::uint8_t kBlocks[kModelCount] = {0, HESAI_MODEL_LIST(HESAI_MODEL_BLOCKS)};
#undef HESAI_MODEL_BLOCKS
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
