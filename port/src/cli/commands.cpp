#include "commands.h"

#include <cstdio>

namespace hesai::cli {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

int usage_error(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "hesai %s: %s\nRun 'hesai %s --help' for usage.\n", command.c_str(), message.c_str(), command.c_str());
  return kExitUsage;
}

int fail(const std::string& command, int status, const std::string& message) {
  if (status == kExitUsage) return usage_error(command, message);
  std::fprintf(stderr, "hesai %s: %s\n", command.c_str(), message.c_str());
  return status;
}

int exit_status(const port::Status& s) {
  switch (s.fault()) {
    case port::Fault::none: return kExitOk;
    case port::Fault::usage: return kExitUsage;
    case port::Fault::input: return kExitInput;
  }
  return kExitInput;
}

int report(const std::string& command, const port::Status& s) {
  if (s.ok()) return kExitOk;
  if (command.empty()) std::fprintf(stderr, "hesai: %s\n", s.message().c_str());
  else std::fprintf(stderr, "hesai %s: %s\n", command.c_str(), s.message().c_str());
  return exit_status(s);
}

bool open_capture(const std::string& path, port::CaptureFile& file) {
  if (file.open(path) == port::CaptureError::ok) return true;
  std::fprintf(stderr, "hesai: %s\n", file.message().c_str());
  return false;
}

}  // namespace hesai::cli
