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
// One model's line of model_list.h.
struct Facts {
  const char* name;
  std::uint8_t channels, blocks;
  std::uint16_t firings;
  std::uint8_t ptc_product;
};
// Indexed by Model: entry 0 is `unknown`.
#define HESAI_MODEL_FACTS(id, name, channels, blocks, firings, ptc) Facts{name, channels, blocks, firings, ptc},
inline constexpr Facts kFacts[kModelCount] = {Facts{"unknown", 0, 0, 0, 255}, HESAI_MODEL_LIST(HESAI_MODEL_FACTS)};
#undef HESAI_MODEL_FACTS
// The line of `m`; `unknown`'s for a value that is no model.
constexpr const Facts& of(Model m) {
  const auto i = static_cast<std::size_t>(m);
  return kFacts[i < kModelCount ? i : 0];
}
}  // namespace model_facts

/// Display name: "Pandar40", "Pandar40P", "Pandar64", "QT128C2X", "PandarQT64", "PandarXT16",
/// "PandarXT32", "PandarXT32M2X" ("unknown", also for a value that is no model).
constexpr const char* model_name(Model m) { return model_facts::of(m).name; }

/// Laser channels of a model (0 for unknown).
constexpr std::size_t channel_count(Model m) { return model_facts::of(m).channels; }

/// Blocks (azimuth columns) per packet (0 for unknown).
constexpr std::size_t block_count(Model m) { return model_facts::of(m).blocks; }

/// Packets per rotation at 600 rpm with `returns` returns a firing (1, 2 or 3): the firings of a
/// rotation, `returns` blocks each, over the blocks of a packet, rounded up (the last packet of a
/// rotation may be partly of the next). Pandar64 in dual return: 1 800 x 2 / 6 = 600. At another
/// spin rate the azimuth step, and with it the count, scales with the rate. 0 for unknown.
constexpr std::size_t packets_per_rotation(Model m, std::size_t returns) {
  const model_facts::Facts& f = model_facts::of(m);
  return f.blocks == 0 ? 0 : (f.firings * returns + f.blocks - 1) / f.blocks;
}

/// The most points one packet of the model can hold: blocks x channels (400, 384, 256; 0 for
/// unknown). Storage for this many points suffices for any packet the model sends.
constexpr std::size_t max_points(Model m) { return block_count(m) * channel_count(m); }

/// The most channels of any model, the most blocks a packet holds (the Pandar40's 10) and the
/// most points one packet can hold (10 x 40).
inline constexpr std::size_t kMaxChannels = 128;
inline constexpr std::size_t kMaxBlocksPerPacket = 10;
inline constexpr std::size_t kMaxPointsPerPacket = 400;
constexpr bool every_model_fits() {
  for (std::size_t i = 0; i < kModelCount; ++i)
    if (model_facts::kFacts[i].channels > kMaxChannels || model_facts::kFacts[i].blocks > kMaxBlocksPerPacket ||
        max_points(static_cast<Model>(i)) > kMaxPointsPerPacket)
      return false;
  return true;
}
static_assert(every_model_fits(),
              "kMaxChannels, kMaxBlocksPerPacket and kMaxPointsPerPacket bound every model of model_list.h");

}  // namespace hesai
