// Capture files on disk: CaptureFile maps a file read-only, feeds a CaptureParser and hands
// the pages it has read back to the kernel (madvise MADV_DONTNEED) as it goes.
#include "hesai_port/capture/capture.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hesai::port {

// ---- CaptureFile --------------------------------------------------------------------------------

namespace {

const char* describe(CaptureError e) {
  switch (e) {
    case CaptureError::bad_magic: return "not a pcap, pcapng or MCAP file (or an unsupported version)";
    case CaptureError::truncated: return "the file ends inside a header, record or block";
    case CaptureError::bad_record: return "a record or block length that cannot be";
    case CaptureError::unsupported_link: return "a link type this reader does not unpack";
    case CaptureError::not_open: return "no capture open";
    case CaptureError::mcap_chunk_crc: return "the chunk's records do not match its CRC";
    case CaptureError::mcap_unknown_schema: return "a channel on a schema id that no Schema record defined";
    case CaptureError::mcap_unknown_channel: return "a message on a channel id that no Channel record defined";
    case CaptureError::mcap_bad_encoding:
      return "a pandar_msgs/msg/PandarScan channel whose message encoding is not cdr";
    case CaptureError::mcap_bad_cdr:
      return "a PandarScan message that is not little-endian CDR or too short for its packets";
    case CaptureError::mcap_bad_packet_size: return "a PandarPacket whose size is above its 1500 data bytes";
    case CaptureError::mcap_no_pandar_scan: return "no pandar_msgs/msg/PandarScan channel in the file";
    default: return capture_error_name(e);
  }
}

// The compression a chunk names, printable characters only, at most 32.
std::string printable(ByteView v) {
  std::string s;
  for (std::size_t i = 0; i < v.size && s.size() < 32; ++i) {
    const std::uint8_t c = v[i];
    s += c >= 0x20 && c < 0x7F ? static_cast<char>(c) : '?';
  }
  return s;
}

}  // namespace

CaptureFile::~CaptureFile() { close(); }

void CaptureFile::close() {
  if (map_ != nullptr) munmap(map_, size_);
  map_ = nullptr;
  size_ = 0;
  released_ = 0;
  parser_ = CaptureParser{};
  mcap_ = McapParser{};
  is_mcap_ = false;
}

CaptureStatus CaptureFile::next(UdpDatagram& out) {
  const CaptureStatus st = is_mcap_ ? mcap_.next(out) : parser_.next(out);
  if (st == CaptureStatus::datagram && out.file_offset - released_ >= kReleaseBytes) {
    // Up to the page that holds the current record: its payload stays mapped.
    const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t upto = static_cast<std::size_t>(out.file_offset) / page * page;
    // Advisory: should it fail, the pages merely stay resident.
    (void)madvise(static_cast<std::uint8_t*>(map_) + released_, upto - released_, MADV_DONTNEED);
    released_ = upto;
  }
  return st;
}

CaptureError CaptureFile::open(const std::string& path) {
  close();
  path_ = path;
  os_error_ = 0;
  os_what_.clear();
  auto os_fail = [this](const char* what, int err) {
    os_error_ = err;
    os_what_ = what;
    return CaptureError::io;
  };

  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return os_fail("open", errno);
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return os_fail("stat", err);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return os_fail("open", S_ISDIR(st.st_mode) ? EISDIR : EINVAL);
  }
  const std::size_t size = static_cast<std::size_t>(st.st_size);
  if (size > 0) {
    void* m = mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (m == MAP_FAILED) {
      const int err = errno;
      ::close(fd);
      return os_fail("mmap", err);
    }
    (void)madvise(m, size, MADV_SEQUENTIAL);
    map_ = m;
    size_ = size;
  }
  ::close(fd);
  if (McapParser::looks_like_mcap(bytes())) {
    is_mcap_ = true;
    return mcap_.open(bytes());
  }
  return parser_.open(bytes());
}

std::string CaptureFile::message() const {
  if (os_error_ != 0) return path_ + ": " + os_what_ + " failed: " + std::strerror(os_error_);
  const CaptureError e = error();
  if (e == CaptureError::ok) return std::string();
  if (e == CaptureError::truncated && size_ == 0 && !path_.empty()) return path_ + ": empty file";
  const std::uint64_t at = is_mcap_ ? mcap_.error_offset() : parser_.error_offset();
  const std::string where = path_ + ": " + capture_error_name(e) + " at byte " + std::to_string(at) + ": ";
  if (e == CaptureError::mcap_compressed_chunk) {
    return where + "a chunk compressed with '" + printable(mcap_.compression()) +
           "': only uncompressed MCAP is read. Rewrite the file uncompressed with the mcap CLI, "
           "mcap decompress IN.mcap -o OUT.mcap, or with ROS 2, ros2 bag convert -i IN.mcap -o out.yaml where "
           "out.yaml gives the output bag storage_id: mcap and a storage_config_uri file that holds "
           "compression: \"None\" (docs/CLI.md, Input formats)";
  }
  if (e == CaptureError::mcap_cut) {
    return where + "cut after record " + std::to_string(mcap_.records_whole()) + " at byte " + std::to_string(at) +
           ": the file ends without its Data End, Footer and closing magic (every packet before the cut was read)";
  }
  return where + describe(e);
}

}  // namespace hesai::port
