// The hesai subcommands and what they share (defined in main.cpp unless noted).
#pragma once

#include <atomic>
#include <string>

#include "hesai_port/capture/capture.h"
#include "options.h"

namespace hesai::cli {

/// Set by SIGINT/SIGTERM once a command installs on_signal.
extern std::atomic<bool> g_stop;
void on_signal(int);

/// Prints "hesai COMMAND: MESSAGE" and the hint to --help; returns kExitUsage.
int usage_error(const std::string& command, const std::string& message);
/// Opens a capture; false, after saying why, when it cannot be read.
bool open_capture(const std::string& path, port::CaptureFile& file);

int cmd_replay(Args& args);  ///< replay.cpp
int cmd_sensor(Args& args);  ///< sensor.cpp

}  // namespace hesai::cli
