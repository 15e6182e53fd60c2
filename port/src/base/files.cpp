#include "hesai_port/base/files.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace hesai::port {

Status read_text_file(const std::string& path, std::string& out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return Status::input(path + ": " + std::strerror(errno));
  std::ostringstream ss;
  ss << f.rdbuf();
  out = ss.str();
  return {};
}

}  // namespace hesai::port
