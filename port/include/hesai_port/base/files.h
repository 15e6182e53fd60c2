// Reading and writing whole files: the one place the port's file helpers live.
#pragma once

#include <string>

#include "hesai_port/base/status.h"

namespace hesai::port {

/// Reads the whole file at `path` into `out`. Status::input ("PATH: reason") when it cannot be read.
Status read_text_file(const std::string& path, std::string& out);

}  // namespace hesai::port
