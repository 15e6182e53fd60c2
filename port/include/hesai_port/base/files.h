// Reading and writing whole files: the one place the port's file helpers live.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "hesai_port/base/status.h"

namespace hesai::port {

/// Reads the whole file at `path` into `out`. Status::input ("PATH: reason") when it cannot be read.
Status read_text_file(const std::string& path, std::string& out);

/// What lstat or fstat found that is not a regular file, for a refusal: "a symbolic link",
/// "a directory", "a FIFO", "a socket", "a device", or "not a regular file".
const char* file_kind(mode_t mode);

/// A file written atomically over `path`: create() makes a new file in the same directory (a
/// random name, O_CREAT | O_EXCL | O_NOFOLLOW, mode 0600), commit() sets its mode, writes it, fsyncs
/// it and renames it over `path`. A reader holding the old file open keeps the old bytes; a path
/// that exists and is not a regular file (a symbolic link, by lstat, a directory, a FIFO) is refused
/// and left as it is; a temporary file not committed is removed. Failures are Status::input.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path) : path_(std::move(path)) {}
  ~AtomicFile() { discard(); }
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  Status create();
  Status commit(const std::uint8_t* bytes, std::size_t size, mode_t mode);

 private:
  void discard();

  std::string path_, folder_, temp_;
  int fd_ = -1;
};

/// AtomicFile's create() and commit() in one.
Status write_file_atomic(const std::string& path, const std::uint8_t* bytes, std::size_t size, mode_t mode);

}  // namespace hesai::port
