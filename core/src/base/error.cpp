#include "hesai/error.h"

namespace hesai {

const char* error_name(Error e) noexcept {
#define HESAI_ERROR_NAME(name) #name,
  static constexpr const char* kNames[] = {HESAI_ERROR_LIST(HESAI_ERROR_NAME)};
#undef HESAI_ERROR_NAME
  static_assert(sizeof kNames / sizeof kNames[0] == kErrorCount);
  const auto i = static_cast<std::size_t>(e);
  return i < kErrorCount ? kNames[i] : "unknown";
}

}  // namespace hesai
