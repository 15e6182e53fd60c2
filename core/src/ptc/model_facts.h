// What PTC may set on each model and how its answers read, from the one list of models
// (hesai/model_list.h HESAI_MODEL_PTC_LIST): the only place ptc/ learns a model's facts.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/model.h"

namespace hesai::ptc::detail {

struct PtcFacts {
  std::uint8_t spin_rates;      // a bit per rate: 1 = 300, 2 = 600, 4 = 1200 rpm
  bool spin_over_http;          // nebula sets the spin rate over HTTP, not 0x17
  bool fov;                     // takes a FOV (0x22)
  const char* return_codes;     // per code from 0: the name's index, '-' for none
  std::uint8_t temperatures;    // in the status (0x09)
};

// By model value; [0] is Model::unknown: every spin rate, over HTTP, FOV, the six return-mode
// codes of the XT and QT128 family and 8 temperatures (what the functions documented for it).
inline constexpr PtcFacts kPtcFacts[] = {
    {1 | 2 | 4, true, true, "012345", 8},
#define HESAI_PTC_FACTS_ROW(id, rates, http, fov, codes, temperatures) {rates, http != 0, fov != 0, codes, temperatures},
    HESAI_MODEL_PTC_LIST(HESAI_PTC_FACTS_ROW)
#undef HESAI_PTC_FACTS_ROW
};

// Each row at its model's value: the two lists in the same order.
constexpr bool rows_in_model_order() {
  std::size_t i = 1;
#define HESAI_PTC_FACTS_ORDER(id, ...) \
  if (static_cast<std::size_t>(Model::id) != i++) return false;
  HESAI_MODEL_PTC_LIST(HESAI_PTC_FACTS_ORDER)
#undef HESAI_PTC_FACTS_ORDER
  return i == sizeof kPtcFacts / sizeof kPtcFacts[0] && i == kModelCount;
}
static_assert(rows_in_model_order(), "HESAI_MODEL_PTC_LIST lists every model once, in the order of HESAI_MODEL_LIST");

inline const PtcFacts& facts(Model model) noexcept {
  const auto i = static_cast<std::size_t>(model);
  return i < sizeof kPtcFacts / sizeof kPtcFacts[0] ? kPtcFacts[i] : kPtcFacts[0];
}

}  // namespace hesai::ptc::detail
