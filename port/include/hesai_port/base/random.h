// Random bytes from the operating system, for session randoms and temporary file names.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::port {

/// Fills `out` with `n` bytes from /dev/urandom. False when they cannot be read.
bool random_bytes(std::uint8_t* out, std::size_t n);

}  // namespace hesai::port
