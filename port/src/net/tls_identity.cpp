// What PTCS checks that needs no OpenSSL: the private key file's rule and which unit a
// certificate's subject names (declared in hesai_port/net/tls.h). Built with or without TLS.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hesai/ct.h"
#include "hesai_port/base/files.h"
#include "hesai_port/base/text.h"
#include "hesai_port/net/tls.h"

namespace hesai::port {
namespace {

constexpr std::size_t kMaxKeyBytes = 64 * 1024;

}  // namespace

bool read_private_key_file(const std::string& path, std::string& pem, std::string& error) {
  pem.clear();
  // O_NONBLOCK: a FIFO opens at once (and is refused below) instead of waiting for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    error = "cannot open the key file '" + path + "': " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    error = "cannot stat the key file '" + path + "': " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = "the key file '" + path + "' is " + file_kind(st.st_mode) + ", not a regular file: refused";
    ::close(fd);
    return false;
  }
  if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    error = "the key file '" + path + "' is accessible by group or others (mode " + mode +
            "): refused, as ssh refuses such a key; chmod 600 '" + path + "'";
    ::close(fd);
    return false;
  }
  if (static_cast<std::uint64_t>(st.st_size) > kMaxKeyBytes) {
    error = "the key file '" + path + "' is larger than 64 KiB: not a key";
    ::close(fd);
    return false;
  }
  pem.resize(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  while (done < pem.size()) {
    const ssize_t n = ::read(fd, &pem[done], pem.size() - done);
    if (n > 0) done += static_cast<std::size_t>(n);
    else if (n == 0) break;
    else if (errno != EINTR) {
      error = "cannot read the key file '" + path + "': " + std::strerror(errno);
      ::close(fd);
      secure_wipe(&pem[0], pem.size());
      pem.clear();
      return false;
    }
  }
  ::close(fd);
  pem.resize(done);
  return true;
}

bool subject_names_serial(const std::vector<SubjectName>& names, const std::string& serial) {
  if (serial.empty()) return false;
  // The one name the certificate gives: its serialNumber where it has one, else its CN; two of
  // the field that decides name no one unit.
  std::size_t serial_numbers = 0, cns = 0;
  const SubjectName* serial_number = nullptr;
  const SubjectName* cn = nullptr;
  for (const SubjectName& n : names) {
    if (n.field == "serialNumber") {
      ++serial_numbers;
      serial_number = &n;
    } else if (n.field == "CN") {
      ++cns;
      cn = &n;
    }
  }
  if (serial_numbers > 0) return serial_numbers == 1 && serial_number->value == serial;
  return cns == 1 && cn->value == serial;
}

std::string subject_text(const std::vector<SubjectName>& names) {
  if (names.empty()) return "no CN and no serialNumber";
  std::string out;
  for (const SubjectName& n : names) out += (out.empty() ? "" : ", ") + n.field + "=" + terminal_text(n.value);
  return out;
}

}  // namespace hesai::port
