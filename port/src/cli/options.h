// Command-line parsing shared by the hesai subcommands.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pipeline.h"

namespace hesai::cli {

/// Exit statuses: 0 success, 1 usage (or a calibration file the decoder cannot use), 2 unreadable
/// input or an output that cannot be written.
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 1;
inline constexpr int kExitInput = 2;

/// Output options of decode and listen.
struct OutputOptions {
  std::string format = "csv";  ///< csv | pcd | ply | png
  std::string out;             ///< --out PATH ("-" for stdout, CSV only); a directory with --per-frame
  bool per_frame = false;      ///< one file per frame: frame_000001.pcd ...
  float png_range_m = 60;      ///< --png-range: metres from the centre to the image edge
  bool png_height = false;     ///< --png-color height (default intensity)
};

/// Arguments left to right, consumed by the parsers below.
class Args {
 public:
  Args(int argc, char** argv, int first);
  bool empty() const { return pos_ >= args_.size(); }
  const std::string& peek() const { return args_[pos_]; }
  std::string take() { return args_[pos_++]; }
  /// The value of the option just taken; false (with a message) when missing.
  bool value(const std::string& option, std::string& out);

 private:
  std::vector<std::string> args_;
  std::size_t pos_ = 0;
};

/// Parses one decode/key/output option at the front of `args` if it is one; returns true when
/// it consumed it. `error` is set when the option is malformed.
bool parse_decode_option(Args& args, DecodeOptions& o, std::string& error);
bool parse_output_option(Args& args, OutputOptions& o, std::string& error);
/// Derives the session key once all options are read (--secret with the two randoms).
bool finish_key_options(DecodeOptions& o, std::string& error);

/// Help text of the decode options, the key options and the output options.
extern const char* const kDecodeOptionsHelp;
extern const char* const kKeyOptionsHelp;
extern const char* const kOutputOptionsHelp;

bool parse_u64(const std::string& s, std::uint64_t& out);
bool parse_float(const std::string& s, float& out);
bool parse_hex(const std::string& s, std::uint8_t* out, std::size_t n);

}  // namespace hesai::cli
