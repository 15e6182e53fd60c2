#include "hesai_port/formats/pointcloud2.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <limits>
#include <utility>

#include "hesai/bytes.h"
#include "le_store.h"

namespace hesai {
namespace port {

namespace {

// The .msg files verbatim: ros2/common_interfaces (sensor_msgs, std_msgs) and ros2/rcl_interfaces
// (builtin_interfaces), as installed in share/<package>/msg/ and read by rosbag2.
constexpr const char* kPointCloud2Msg =
    "# This message holds a collection of N-dimensional points, which may\n"
    "# contain additional information such as normals, intensity, etc. The\n"
    "# point data is stored as a binary blob, its layout described by the\n"
    "# contents of the \"fields\" array.\n"
    "#\n"
    "# The point cloud data may be organized 2d (image-like) or 1d (unordered).\n"
    "# Point clouds organized as 2d images may be produced by camera depth sensors\n"
    "# such as stereo or time-of-flight.\n"
    "\n"
    "# Time of sensor data acquisition, and the coordinate frame ID (for 3d points).\n"
    "std_msgs/Header header\n"
    "\n"
    "# 2D structure of the point cloud. If the cloud is unordered, height is\n"
    "# 1 and width is the length of the point cloud.\n"
    "uint32 height\n"
    "uint32 width\n"
    "\n"
    "# Describes the channels and their layout in the binary data blob.\n"
    "PointField[] fields\n"
    "\n"
    "bool    is_bigendian # Is this data bigendian?\n"
    "uint32  point_step   # Length of a point in bytes\n"
    "uint32  row_step     # Length of a row in bytes\n"
    "uint8[] data         # Actual point data, size is (row_step*height)\n"
    "\n"
    "bool is_dense        # True if there are no invalid points\n";
constexpr const char* kPointFieldMsg =
    "# This message holds the description of one point entry in the\n"
    "# PointCloud2 message format.\n"
    "uint8 INT8    = 1\n"
    "uint8 UINT8   = 2\n"
    "uint8 INT16   = 3\n"
    "uint8 UINT16  = 4\n"
    "uint8 INT32   = 5\n"
    "uint8 UINT32  = 6\n"
    "uint8 FLOAT32 = 7\n"
    "uint8 FLOAT64 = 8\n"
    "\n"
    "# Common PointField names are x, y, z, intensity, rgb, rgba\n"
    "string name      # Name of field\n"
    "uint32 offset    # Offset from start of point struct\n"
    "uint8  datatype  # Datatype enumeration, see above\n"
    "uint32 count     # How many elements in the field\n";
constexpr const char* kHeaderMsg =
    "# Standard metadata for higher-level stamped data types.\n"
    "# This is generally used to communicate timestamped data\n"
    "# in a particular coordinate frame.\n"
    "\n"
    "# Two-integer timestamp that is expressed as seconds and nanoseconds.\n"
    "builtin_interfaces/Time stamp\n"
    "\n"
    "# Transform frame with which this data is associated.\n"
    "string frame_id\n";
constexpr const char* kTimeMsg =
    "# This message communicates ROS Time defined here:\n"
    "# https://design.ros2.org/articles/clock_and_time.html\n"
    "\n"
    "# The seconds component, valid over all int32 values.\n"
    "int32 sec\n"
    "\n"
    "# The nanoseconds component, valid in the range [0, 1e9), to be added to the seconds component.\n"
    "# e.g.\n"
    "# The time -1.7 seconds is represented as {sec: -2, nanosec: 3e8}\n"
    "# The time 1.7 seconds is represented as {sec: 1, nanosec: 7e8}\n"
    "uint32 nanosec\n";

// CDR, little-endian; offsets count from after the 4-byte encapsulation header.
class Cdr {
 public:
  explicit Cdr(std::vector<std::uint8_t>& out) : out_(out) {
    for (const int b : {0x00, 0x01, 0x00, 0x00}) out_.push_back(static_cast<std::uint8_t>(b));  // CDR_LE, options 0
  }
  Cdr& u8(std::uint8_t v) {
    out_.push_back(v);
    return *this;
  }
  Cdr& u32(std::uint32_t v) {
    align(4);
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  // A string: its length with the terminating NUL, the bytes, the NUL.
  Cdr& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size() + 1));
    for (const char ch : s) out_.push_back(static_cast<std::uint8_t>(ch));
    return u8(0);
  }

 private:
  void align(std::size_t n) {
    while ((out_.size() - 4) % n != 0) out_.push_back(0);
  }
  std::vector<std::uint8_t>& out_;
};

struct Field {
  const char* name;
  std::uint32_t offset;
  std::uint8_t datatype;  // sensor_msgs/PointField: UINT8 2, UINT16 4, UINT32 6, FLOAT32 7
};
constexpr Field kFields[] = {
    {"x", 0, 7},         {"y", 4, 7},         {"z", 8, 7},          {"intensity", 12, 2}, {"return_type", 13, 2},
    {"channel", 14, 4},  {"azimuth", 16, 7},  {"elevation", 20, 7}, {"distance", 24, 7},  {"time_stamp", 28, 6},
};

constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;

}  // namespace

const std::string& pointcloud2_definition() {
  static const std::string text = [] {
    const std::string rule(80, '=');
    std::string t = kPointCloud2Msg;
    for (const auto& [name, msg] : {std::pair<const char*, const char*>{"sensor_msgs/PointField", kPointFieldMsg},
                                    {"std_msgs/Header", kHeaderMsg},
                                    {"builtin_interfaces/Time", kTimeMsg}})
      t += "\n" + rule + "\nMSG: " + name + "\n" + msg;
    return t;
  }();
  return text;
}

std::vector<std::uint8_t> pointcloud2_head(std::int64_t stamp_ns, const std::string& frame_id, std::uint32_t points) {
  std::int64_t sec = stamp_ns / 1000000000;
  std::int64_t nsec = stamp_ns % 1000000000;
  if (nsec < 0) {
    nsec += 1000000000;
    --sec;
  }
  std::vector<std::uint8_t> out;
  Cdr c(out);
  c.u32(static_cast<std::uint32_t>(static_cast<std::int32_t>(sec))).u32(static_cast<std::uint32_t>(nsec));
  c.str(frame_id).u32(1).u32(points);
  c.u32(static_cast<std::uint32_t>(sizeof kFields / sizeof kFields[0]));
  for (const Field& f : kFields) c.str(f.name).u32(f.offset).u8(f.datatype).u32(1);
  c.u8(0);  // is_bigendian
  c.u32(static_cast<std::uint32_t>(kPointStep)).u32(static_cast<std::uint32_t>(kPointStep * points));
  c.u32(static_cast<std::uint32_t>(kPointStep * points));  // data: its length, the bytes follow
  return out;
}

// Return-mode bytes: Pandar40 manual 3.1.2, Table 3.3 note and "Return Mode Information"
// (0x37 strongest, 0x38 last, 0x39 dual: odd block last, even block strongest); Pandar64 manual
// 3.1.2.2 Body, the return-mode table (0x39: odd-numbered block last, even-numbered strongest,
// "If the last return is also the strongest, then the even-numbered block stores the second
// strongest return") and 3.1.2.3 Tail; QT128C2X manual 3.1.2.2 Body, the table "Return Mode
// field / Block 1 / Block 2 / Note" (0x39 last/strongest, 0x3B first/last, 0x3C first/strongest,
// 0x3E strongest/second strongest, 0x3A first/second) and 3.1.2 Tail (0x33 first, 0x34 second,
// 0x37, 0x38). 0x3D (triple: first, last, strongest) has no manual here: nebula hesai_packet.hpp.
//
// The ReturnType of each block is nebula's (hesai_sensor.hpp, get_return_type):
// - a unit equal to another return of its firing (distance and reflectivity) is IDENTICAL, in
//   every mode and block, before anything else. nebula then keeps only the last block's point of
//   such a group (hesai_decoder.hpp, convert_returns); we keep both, labelled IDENTICAL, so that
//   the message has the CSV's points (a contract), and --returns distinct leaves out the repeat
//   as in every other format;
// - "strongest" in the two modes that pair a return with the strongest (0x39, 0x3C) is nebula's
//   test: no other return of the firing has a higher reflectivity (a tie counts as strongest);
// - the PandarXT16 and XT32 send 0x3B with last in the first block (nebula pandar_xt16.hpp and
//   pandar_xt32.hpp swap FIRST and LAST for them); the XT32M2X keeps the base order (nebula
//   pandar_xt32m.hpp does not override it).
// nebula's other dual-return filter, dropping the earlier of two returns closer than its
// dual_return_distance_threshold parameter, removes points and sets no label: not mirrored.
namespace {
// The ReturnType of a return of a dual or triple mode by its block alone (nebula's rule, above);
// unknown for any other mode.
NebulaReturnType dual_return_type(Model model, ReturnMode mode, std::uint8_t return_index, bool weaker) noexcept {
  using T = NebulaReturnType;
  const bool first_block = return_index == 0;
  switch (mode) {
    case ReturnMode::last_strongest:
      if (first_block) return weaker ? T::last : T::last_strongest;
      return weaker ? T::second_strongest : T::strongest;
    case ReturnMode::first_second: return first_block ? T::first : T::second;
    case ReturnMode::first_last: {
      const bool last_first = model == Model::pandar_xt16 || model == Model::pandar_xt32;
      return first_block != last_first ? T::first : T::last;
    }
    case ReturnMode::first_strongest:
      if (first_block) return weaker ? T::first : T::first_strongest;
      return weaker ? T::second_strongest : T::strongest;
    case ReturnMode::first_last_strongest:
      return return_index == 0 ? T::first : return_index == 1 ? T::last : return_index == 2 ? T::strongest : T::unknown;
    case ReturnMode::strongest_second_strongest: return first_block ? T::strongest : T::second_strongest;
    default: return T::unknown;
  }
}
}  // namespace

NebulaReturnType nebula_return_type(Model model, std::uint8_t return_mode, std::uint8_t return_index, bool identical,
                                    bool weaker) noexcept {
  using T = NebulaReturnType;
  switch (static_cast<ReturnMode>(return_mode)) {
    case ReturnMode::first: return T::first;
    case ReturnMode::second: return T::second;
    case ReturnMode::strongest: return T::strongest;
    case ReturnMode::last: return T::last;
    default: break;
  }
  // A dual or triple mode: a return equal to another of its firing is IDENTICAL, whatever its block.
  const T by_block = dual_return_type(model, static_cast<ReturnMode>(return_mode), return_index, weaker);
  return identical && by_block != T::unknown ? T::identical : by_block;
}

NebulaReturnType nebula_return_type(const PacketInfo& info, const ReturnComparison& compare, const Point& p) noexcept {
  const std::size_t ch = static_cast<std::size_t>(p.channel > 0 ? p.channel - 1 : 0);
  return nebula_return_type(info.model, info.return_mode, p.return_index, compare.is_identical(p.block, ch),
                            compare.is_weaker(p.block, ch));
}

namespace {
static_assert(offsetof(Point, y) == offsetof(Point, x) + 4 && offsetof(Point, z) == offsetof(Point, x) + 8,
              "Point::x, y, z consecutive");

// One record with `time` in its time_stamp, each field one fixed-size little-endian store.
inline void encode_record(const Point& p, NebulaReturnType return_type, std::uint32_t time, std::uint8_t* out) {
  if constexpr (kLittleEndianHost) {
    std::memcpy(out, &p.x, 12);
  } else {
    store_le(out + 0, p.x);
    store_le(out + 4, p.y);
    store_le(out + 8, p.z);
  }
  out[12] = p.intensity;
  out[13] = static_cast<std::uint8_t>(return_type);
  store_le(out + 14, static_cast<std::uint16_t>(p.channel > 0 ? p.channel - 1 : 0));
  store_le(out + 16, static_cast<float>(p.azimuth_deg * kRadPerDeg));
  store_le(out + 20, static_cast<float>(p.elevation_deg * kRadPerDeg));
  store_le(out + 24, p.distance_m);
  store_le(out + 28, time);
}

// b - a for a <= b, exact whatever the two (their difference as int64 may overflow).
inline std::uint64_t span(std::int64_t a, std::int64_t b) {
  return static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a);
}

// time_stamp: the time after the stamp, clamped to 0 .. 2^32 - 1.
inline std::uint32_t time_after(std::int64_t time_ns, std::int64_t stamp_ns) {
  if (time_ns <= stamp_ns) return 0;
  const std::uint64_t dt = span(stamp_ns, time_ns);
  return dt >= 0xFFFFFFFFu ? 0xFFFFFFFFu : static_cast<std::uint32_t>(dt);
}

constexpr std::uint64_t kNarrowSpan = std::uint64_t{1} << 31;  // wrapping 32-bit offsets are exact below it
constexpr std::size_t kTimeAt = 28;                            // time_stamp's offset in a record
}  // namespace

PacketReturnTypes::PacketReturnTypes(const PacketInfo& info) noexcept
    : model_(info.model), return_mode_(info.return_mode) {
  for (std::size_t k = 0; k < 16; ++k)
    table_[k] = nebula_return_type(info.model, info.return_mode, static_cast<std::uint8_t>(k / 4), (k & 2) != 0,
                                   (k & 1) != 0);
}

void PacketReturnTypes::of_block(const ReturnComparison& compare, const Point* points, std::size_t count,
                                 NebulaReturnType* out) const noexcept {
  if (count == 0) return;
  const std::uint8_t block = points[0].block, index = points[0].return_index;
  if (block >= kMaxBlocksPerPacket || index > 3) {
    for (std::size_t i = 0; i < count; ++i) out[i] = (*this)(compare, points[i]);
    return;
  }
  const std::uint8_t* identical = compare.identical[block].data();
  const std::uint8_t* weaker = compare.weaker[block].data();
  const NebulaReturnType* row = table_ + 4 * static_cast<std::size_t>(index);
  for (std::size_t i = 0; i < count; ++i) {
    const Point& p = points[i];
    const unsigned ch = p.channel > 0 ? p.channel - 1u : 0u;
    if (p.block != block || p.return_index != index || ch >= kMaxChannels) {
      out[i] = (*this)(compare, p);
      continue;
    }
    const unsigned bit = ch % 8;
    out[i] = row[(static_cast<unsigned>(identical[ch / 8]) >> bit & 1u) * 2 + (static_cast<unsigned>(weaker[ch / 8]) >> bit & 1u)];
  }
}

void encode_point(const Point& p, NebulaReturnType return_type, std::int64_t stamp_ns, std::uint8_t out[kPointStep]) {
  encode_record(p, return_type, time_after(p.time_ns, stamp_ns), out);
}

void PointCloud2Data::reserve(std::size_t points) {
  if (points <= capacity_) return;
  std::unique_ptr<std::uint8_t[]> bigger(new std::uint8_t[points * kPointStep]);  // not zeroed: written before read
  if (count_ != 0) std::memcpy(bigger.get(), bytes_.get(), count_ * kPointStep);
  bytes_ = std::move(bigger);
  capacity_ = points;
}

void PointCloud2Data::add(const Point* points, const NebulaReturnType* types, std::size_t count) {
  if (count == 0) return;
  if (count > capacity_ - count_) reserve(std::max(count_ + count, 2 * capacity_));
  if (count_ == 0) base_ = min_ = max_ = points[0].time_ns;
  // Each record's time_stamp: its time after base_, wrapping at 32 bits.
  std::uint8_t* out = bytes_.get() + count_ * kPointStep;
  const auto base = static_cast<std::uint64_t>(base_);
  std::int64_t lo = min_, hi = max_;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int64_t t = points[i].time_ns;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
    encode_record(points[i], types != nullptr ? types[i] : NebulaReturnType::unknown,
                  static_cast<std::uint32_t>(static_cast<std::uint64_t>(t) - base), out + i * kPointStep);
  }
  if (!wide_ && span(lo, hi) >= kNarrowSpan) {
    // The span reaches 2^31 ns: the offsets no longer tell the times. Those of the records before
    // these, all within 2^31 ns of base_ (it lies in their span), come back from them.
    wide_ = true;
    times_.resize(count_);
    for (std::size_t i = 0; i < count_; ++i)
      times_[i] = base_ + static_cast<std::int32_t>(load_le32(bytes_.get() + i * kPointStep + kTimeAt));
  }
  if (wide_)
    for (std::size_t i = 0; i < count; ++i) times_.push_back(points[i].time_ns);
  min_ = lo;
  max_ = hi;
  count_ += count;
}

const std::uint8_t* PointCloud2Data::finish(std::size_t end) {
  std::uint8_t* t = bytes_.get() + kTimeAt;
  if (wide_) {
    for (std::size_t i = finished_; i < end; ++i) store_le(t + i * kPointStep, time_after(times_[i], min_));
  } else if (base_ != min_) {  // every offset grows by base_ - min_ (< 2^31: no clamp)
    const auto shift = static_cast<std::uint32_t>(span(min_, base_));
    for (std::size_t i = finished_; i < end; ++i) store_le(t + i * kPointStep, load_le32(t + i * kPointStep) + shift);
  }
  if (end > finished_) finished_ = end;
  return bytes_.get();
}

void PointCloud2Data::clear() {
  count_ = 0;
  base_ = min_ = max_ = 0;
  times_.clear();
  wide_ = false;
  finished_ = 0;
}

namespace {
bool token_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}
bool digit(char c) { return c >= '0' && c <= '9'; }
}  // namespace

bool ros2_token(const std::string& token) {
  if (token.empty() || digit(token[0]) || token.find("__") != std::string::npos) return false;
  for (const char c : token)
    if (!token_char(c)) return false;
  return true;
}

std::string ros2_topic(const std::string& name, std::string& why) {
  if (name.empty()) {
    why = "a topic name cannot be empty";
    return "";
  }
  for (const char c : name) {
    if (c == '~') {
      why = "'~' (a node's private namespace) has no node to resolve it in a file";
      return "";
    }
    if (c == '{' || c == '}') {
      why = "only the {sensor} substitution is known";
      return "";
    }
    if (!token_char(c) && c != '/') {
      why = std::string("'") + c + "' is not allowed: only letters, digits, '_' and '/'";
      return "";
    }
  }
  const std::string full = name[0] == '/' ? name : "/" + name;
  if (full.size() > 1 && full.back() == '/') {
    why = "a topic name cannot end with '/'";
    return "";
  }
  if (full.find("//") != std::string::npos) {
    why = "a topic name cannot hold '//'";
    return "";
  }
  if (full.find("__") != std::string::npos) {
    why = "a topic name cannot hold '__'";
    return "";
  }
  if (full == "/") {
    why = "'/' names no topic";
    return "";
  }
  for (std::size_t i = 0; i + 1 < full.size(); ++i) {
    if (full[i] == '/' && digit(full[i + 1])) {
      why = "a name token cannot start with a digit";
      return "";
    }
  }
  return full;
}

}  // namespace port
}  // namespace hesai
