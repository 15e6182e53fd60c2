// The port's one error type for calls that can fail in more than one way a caller must tell apart.
//
// The core has one `Error` code per cause; the port's callers need less: whether the request was
// wrong (fix the options or the file's content) or the input and output failed (a file that cannot
// be read or written, damage). A `Status` says which, with a message for a person. Only the command
// boundary turns it into an exit status (port/src/cli/options.h `exit_status`: usage 1, input 2),
// and the C library into its return values (hesai_capture.h, the same numbers): the engine and the
// layers under it never see exit codes. docs/DESIGN.md, "Errors", says which older port calls still
// have their own result types and why.
#pragma once

#include <string>
#include <utility>

namespace hesai::port {

/// What kind of failure a Status reports.
enum class Fault : unsigned char {
  none,   ///< success
  usage,  ///< the request cannot be done as asked: a bad option or value, a calibration file the
          ///< decoder cannot use, an output that cannot be what was asked (a pipe for PCD)
  input,  ///< an input that cannot be read (a missing file, a damaged capture) or an output that
          ///< cannot be written
};

/// Success (default-constructed), or a Fault with its message. [[nodiscard]]: no failure is ever
/// dropped silently.
class [[nodiscard]] Status {
 public:
  Status() = default;
  static Status usage(std::string message) { return Status(Fault::usage, std::move(message)); }
  static Status input(std::string message) { return Status(Fault::input, std::move(message)); }

  bool ok() const { return fault_ == Fault::none; }
  Fault fault() const { return fault_; }
  const std::string& message() const { return message_; }

 private:
  Status(Fault fault, std::string message) : fault_(fault), message_(std::move(message)) {}
  Fault fault_ = Fault::none;
  std::string message_;
};

}  // namespace hesai::port
