#include "hesai_port/base/random.h"

#include <fcntl.h>
#include <unistd.h>

namespace hesai::port {

bool random_bytes(std::uint8_t* out, std::size_t n) {
  const int fd = ::open("/dev/urandom", O_RDONLY | O_CLOEXEC);
  std::size_t done = 0;
  while (fd >= 0 && done < n) {
    const ssize_t got = ::read(fd, out + done, n - done);
    if (got <= 0) break;
    done += static_cast<std::size_t>(got);
  }
  if (fd >= 0) ::close(fd);
  return done == n;
}

}  // namespace hesai::port
