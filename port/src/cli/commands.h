// The hesai subcommands and what they share (commands.cpp unless noted).
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "hesai_port/base/status.h"
#include "hesai_port/capture/capture.h"
#include "hesai_port/pipeline/run.h"
#include "options.h"

namespace hesai::cli {

/// Set by SIGINT/SIGTERM once a command installs on_signal.
extern std::atomic<bool> g_stop;
void on_signal(int);

/// Prints "hesai COMMAND: MESSAGE" and the hint to --help; returns kExitUsage.
int usage_error(const std::string& command, const std::string& message);
/// Reports a failure with exit status `status`: a usage error with the hint to --help, any other
/// with the message alone. Returns `status`.
int fail(const std::string& command, int status, const std::string& message);
/// The exit status of a port Status: kExitOk, kExitUsage or kExitInput (the one place a Status
/// becomes an exit code).
int exit_status(const port::Status& s);
/// As exit_status(), and a failure's message printed on stderr as "hesai COMMAND: MESSAGE"
/// ("hesai: MESSAGE" for an empty command), without the hint to --help.
int report(const std::string& command, const port::Status& s);
/// Opens a capture; false, after saying why, when it cannot be read.
bool open_capture(const std::string& path, port::CaptureFile& file);
/// The progress line of decode and stats on a terminal's stderr (none when quiet), for run_capture.
std::function<void(const port::CaptureFeed&)> progress_line(bool quiet);  ///< decode.cpp

int cmd_decode(Args& args);  ///< decode.cpp
int cmd_stats(Args& args);   ///< decode.cpp
int cmd_listen(Args& args);  ///< listen.cpp
int cmd_replay(Args& args);  ///< replay.cpp
int cmd_sensor(Args& args);  ///< sensor.cpp

}  // namespace hesai::cli
