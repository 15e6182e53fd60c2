// What the file writers of formats/ share (writers.cpp, csv.cpp). Private to formats/.
#pragma once

#include <cstddef>
#include <cstring>
#include <string>

namespace hesai::port {

/// The block a writer fills before each write to its file.
inline constexpr std::size_t kBlockBytes = 1u << 20;

/// "cannot open 'out.csv': No such file or directory".
inline std::string os_message(const char* what, const std::string& name, int err) {
  return std::string(what) + " '" + name + "': " + std::strerror(err);
}

}  // namespace hesai::port
