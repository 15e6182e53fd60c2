#include "hesai_port/base/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "hesai_port/base/random.h"

namespace hesai::port {

Status read_text_file(const std::string& path, std::string& out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return Status::input(path + ": " + std::strerror(errno));
  std::ostringstream ss;
  ss << f.rdbuf();
  out = ss.str();
  return {};
}

const char* file_kind(mode_t mode) {
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

Status AtomicFile::create() {
  struct stat st {};
  if (lstat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    return Status::input("refusing to write '" + path_ + "': it is " + file_kind(st.st_mode) +
                         ", not a regular file (nothing written, it is left as it is)");
  const std::size_t slash = path_.rfind('/');
  folder_ = slash == std::string::npos ? "" : path_.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path_ : path_.substr(slash + 1);
  std::uint8_t random[8];
  if (name.empty() || !random_bytes(random, sizeof random))
    return Status::input("cannot write '" + path_ + "': " +
                         (name.empty() ? "not a file name" : "no random name for the temporary file"));
  char suffix[24];
  std::snprintf(suffix, sizeof suffix, ".%02x%02x%02x%02x%02x%02x%02x%02x.tmp", random[0], random[1], random[2],
                random[3], random[4], random[5], random[6], random[7]);
  temp_ = folder_ + "." + name + suffix;
  fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd_ < 0) {
    const std::string why = std::strerror(errno);
    const std::string temp = temp_;
    temp_.clear();  // not ours to remove
    return Status::input("cannot write '" + path_ + "': cannot create '" + temp + "': " + why);
  }
  return {};
}

Status AtomicFile::commit(const std::uint8_t* bytes, std::size_t size, mode_t mode) {
  std::size_t done = 0;
  int err = fchmod(fd_, mode) == 0 ? 0 : errno;
  while (err == 0 && done < size) {
    const ssize_t n = ::write(fd_, bytes + done, size - done);
    if (n > 0) done += static_cast<std::size_t>(n);
    else if (n < 0 && errno != EINTR) err = errno;
  }
  if (err == 0 && fsync(fd_) != 0) err = errno;
  if (::close(fd_) != 0 && err == 0) err = errno;
  fd_ = -1;
  if (err == 0 && ::rename(temp_.c_str(), path_.c_str()) != 0) err = errno;
  if (err != 0) {
    discard();
    return Status::input("cannot write '" + path_ + "': " + std::strerror(err));
  }
  temp_.clear();
  // The rename itself lasts once the directory's entry is on disk (best effort).
  if (const int dir = ::open(folder_.empty() ? "." : folder_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
    (void)fsync(dir);
    ::close(dir);
  }
  return {};
}

void AtomicFile::discard() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temp_.empty()) ::unlink(temp_.c_str());
  temp_.clear();
}

Status write_file_atomic(const std::string& path, const std::uint8_t* bytes, std::size_t size, mode_t mode) {
  AtomicFile file(path);
  if (Status s = file.create(); !s.ok()) return s;
  return file.commit(bytes, size, mode);
}

}  // namespace hesai::port
