// Error codes of the core: one code per distinct cause. (The port has its own: capture files are
// read by port/, see hesai_port/capture/capture.h CaptureError.)
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/error_list.h"  // the codes, once for C++ and C (hesai.h)

namespace hesai {

/// Outcome of every fallible core operation. `ok` is zero; every other value names one cause
/// (the list and what each code means: hesai/error_list.h). Bad input is a normal outcome:
/// callers count it, nothing asserts or throws. [[nodiscard]]: a call whose Error is dropped does
/// not compile (warnings are errors).
enum class [[nodiscard]] Error : std::uint8_t {
#define HESAI_ERROR_ENUMERATOR(name) name,
  HESAI_ERROR_LIST(HESAI_ERROR_ENUMERATOR)
#undef HESAI_ERROR_ENUMERATOR
};

/// Number of codes, and the last one, for loops over every code.
#define HESAI_ERROR_PLUS_ONE(name) +1
inline constexpr std::size_t kErrorCount = 0 HESAI_ERROR_LIST(HESAI_ERROR_PLUS_ONE);
#undef HESAI_ERROR_PLUS_ONE
inline constexpr Error kLastError = static_cast<Error>(kErrorCount - 1);

/// Stable lower-case name of an error code, for logs and JSON ("crc_body"); "unknown" for a
/// value that is no code.
const char* error_name(Error e) noexcept;

}  // namespace hesai
