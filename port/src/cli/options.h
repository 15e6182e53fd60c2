// Command-line parsing shared by the hesai subcommands.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hesai_port/net/tls.h"
#include "hesai_port/pipeline/pipeline.h"
#include "hesai_port/pipeline/sinks.h"

namespace hesai::cli {

/// Exit statuses: 0 success, 1 usage (or a calibration file the decoder cannot use), 2 unreadable
/// input or an output that cannot be written.
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 1;
inline constexpr int kExitInput = 2;

// The engine's names the commands use (hesai_port/pipeline/).
using port::DecodeOptions;
using port::OutputOptions;
using port::OutputSink;
using port::Pipeline;
using port::with_sensor;

/// Arguments left to right, consumed by the parsers below.
class Args {
 public:
  Args(int argc, char** argv, int first);
  bool empty() const { return pos_ >= args_.size(); }
  const std::string& peek() const { return args_[pos_]; }
  std::string take() { return args_[pos_++]; }
  /// The value of the option just taken; false (with a message) when missing.
  bool value(const std::string& option, std::string& out);
  /// As value(), for key material: the copy here and the program's argv string are wiped
  /// (so /proc/PID/cmdline no longer shows it, though it did until now).
  bool secret_value(std::string& out);

 private:
  std::vector<std::string> args_;
  char** argv_;
  int first_;
  std::size_t pos_ = 0;
};

/// Parses one decode/key/output option at the front of `args` if it is one; returns true when
/// it consumed it. `error` is set when the option is malformed.
bool parse_decode_option(Args& args, DecodeOptions& o, std::string& error);
bool parse_output_option(Args& args, OutputOptions& o, std::string& error);
// ---- Key material (key_options.cpp) ----

/// Parses one key option at the front of `args` (--session-key, --session-key-file, --secret,
/// --secret-file, --lidar-random, --client-random) if it is one, held until finish_key_options();
/// returns true when it consumed it. parse_decode_option() calls it.
bool parse_key_option(Args& args, std::string& error);
/// Sets the session key once all options are read, from one source in this order of precedence:
/// a key option (--session-key-file, --secret-file, --session-key or --secret, at most one), else
/// the environment (HESAI_SESSION_KEY or HESAI_SECRET, not both); a secret with --lidar-random and
/// --client-random. Warns on stderr about a key on the command line and about a key file that
/// group or others may read; wipes the text it read. Returns kExitOk, kExitUsage (a malformed or
/// ambiguous key) or kExitInput (a key file that cannot be read), with a message that never holds
/// key material.
int finish_key_options(DecodeOptions& o, std::string& error);
/// Wipes the session key and the session secret of `o` (once the pipeline holds its copy).
void wipe_key(DecodeOptions& o);
/// Wipes all of `s`'s storage (its capacity, not only its size: a string moved from keeps its old
/// bytes in its small-string buffer) and empties it.
void wipe_secret(std::string& s);
/// Wipes a command's key material (wipe_key, and a secret it holds apart) when it goes out of
/// scope: on every return path.
class KeyWipe {
 public:
  explicit KeyWipe(DecodeOptions& o, std::string* secret = nullptr) : o_(o), secret_(secret) {}
  ~KeyWipe() {
    wipe_key(o_);
    if (secret_ != nullptr) wipe_secret(*secret_);
  }
  KeyWipe(const KeyWipe&) = delete;
  KeyWipe& operator=(const KeyWipe&) = delete;

 private:
  DecodeOptions& o_;
  std::string* secret_;
};
/// The shared secret of a signature session, from `secret_file` (its first line) when given, else
/// from HESAI_SECRET; 8 to 32 characters. Returns an exit status, with a message that never holds
/// the secret.
int read_secret(const std::string& secret_file, std::string& secret, std::string& error);

// ---- PTCS (options.cpp) ----

/// PTCS options of 'sensor' and 'listen --sensor': --tls, --ca, --cert, --key, --insecure,
/// --expect-serial.
struct TlsOptions {
  bool tls = false;
  port::TlsClientOptions client;
};
/// Parses one TLS option at the front of `args` if it is one; returns true when it consumed it.
/// `error` is set when the option is malformed, and for --tls in a build without TLS.
bool parse_tls_option(Args& args, TlsOptions& o, std::string& error);
/// Once all options are read: checks that they go together (kExitUsage), warns about --insecure,
/// and makes the context (null without --tls): kExitInput with a message for a CA, certificate or
/// key file that cannot be used (a key that group or others may access, or that is not a regular
/// file, is refused).
int finish_tls_options(const TlsOptions& o, std::shared_ptr<port::TlsContext>& context, std::string& error);
extern const char* const kTlsOptionsHelp;

/// Help text of the decode options, the key options and the output options.
extern const char* const kDecodeOptionsHelp;
extern const char* const kKeyOptionsHelp;
extern const char* const kOutputOptionsHelp;

bool parse_u64(const std::string& s, std::uint64_t& out);
bool parse_float(const std::string& s, float& out);
bool parse_hex(const std::string& s, std::uint8_t* out, std::size_t n);

}  // namespace hesai::cli
