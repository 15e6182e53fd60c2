// ROS 2 sensor_msgs/msg/PointCloud2 messages, serialised as CDR, for MCAP files (profile ros2).
//
// The encoding: little-endian plain CDR (XCDR1) with its 4-byte encapsulation header 00 01 00 00;
// each primitive aligned to its size, counted from the first byte after the encapsulation header.
//
// The points, one 32-byte record each, laid out as nebula's PointXYZIRCAEDT (tier4/nebula,
// nebula_common point_types.hpp; Autoware's default point type), field by field:
//   offset  0 x           FLOAT32  metres  \  the manuals' frame, as nebula's Hesai decoders:
//   offset  4 y           FLOAT32  metres   | Y axis at azimuth 0, azimuth clockwise seen from
//   offset  8 z           FLOAT32  metres  /  above, Z up (Point::x, y, z)
//   offset 12 intensity   UINT8    the reflectivity byte (Point::intensity)
//   offset 13 return_type UINT8    nebula's ReturnType of the point (nebula_return_type below), by
//                                  the packet's return mode and the other returns of its firing
//   offset 14 channel     UINT16   0-based laser channel as nebula numbers them (Point::channel - 1)
//   offset 16 azimuth     FLOAT32  radians, [0, 2 pi) (nebula: azimuth_rad; Point::azimuth_deg)
//   offset 20 elevation   FLOAT32  radians, up positive (nebula: elevation_rad)
//   offset 24 distance    FLOAT32  metres
//   offset 28 time_stamp  UINT32   ns after header.stamp (clamped to 0 .. 2^32 - 1)
// point_step 32, row_step 32 * width, height 1, is_bigendian false, is_dense true.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/point.h"

namespace hesai {
namespace port {

/// Schema name and encodings of the MCAP channel.
inline constexpr const char* kPointCloud2Schema = "sensor_msgs/msg/PointCloud2";
inline constexpr const char* kRos2MsgEncoding = "ros2msg";
inline constexpr const char* kCdrEncoding = "cdr";
/// Bytes of one point record.
inline constexpr std::size_t kPointStep = 32;

/// The full message definition as rosbag2 stores it: PointCloud2.msg, then each dependency
/// (sensor_msgs/PointField, std_msgs/Header, builtin_interfaces/Time, in rosbag2's order) after
/// a line of 80 '=' and "MSG: <type>". The .msg texts are those of ROS 2 common_interfaces and
/// rcl_interfaces.
const std::string& pointcloud2_definition();

/// The CDR bytes of a PointCloud2 up to its point data: encapsulation header, header (stamp from
/// `stamp_ns`, ns since the Unix epoch, as builtin_interfaces/Time's int32 seconds and uint32
/// nanoseconds: dates after 2038-01-19 wrap, as they do in ROS 2, and `frame_id`), height 1, width `points`, the ten fields
/// above, is_bigendian, point_step, row_step and the data's length. The data (kPointStep bytes a
/// point) follows, then the one byte of is_dense (kPointCloud2Tail).
std::vector<std::uint8_t> pointcloud2_head(std::int64_t stamp_ns, const std::string& frame_id, std::uint32_t points);
inline constexpr std::uint8_t kPointCloud2Tail = 1;  // is_dense: true

/// Total message bytes for a head of `head_bytes` and `points` points.
inline std::uint64_t pointcloud2_size(std::size_t head_bytes, std::uint64_t points) {
  return head_bytes + points * kPointStep + 1;
}

/// nebula's ReturnType (tier4/nebula, nebula_core_common/nebula_common.hpp, enum ReturnType), the
/// values of the PointCloud2 `return_type` byte. 0 is UNKNOWN, which Autoware reads as invalid.
enum class NebulaReturnType : std::uint8_t {
  unknown = 0,
  last = 1,
  first = 2,
  strongest = 3,
  first_weak = 4,
  last_weak = 5,
  identical = 6,
  second = 7,
  second_strongest = 8,
  first_strongest = 9,
  last_strongest = 10,
};

/// The ReturnType nebula's Hesai decoder gives a point (nebula hesai_sensor.hpp, get_return_type,
/// and the overrides in pandar_xt16.hpp and pandar_xt32.hpp): `return_mode` is the tail's byte,
/// `return_index` the point's block within its firing (Point::return_index), `identical` whether
/// its unit equals another return of the firing in distance and reflectivity, `weaker` whether
/// its reflectivity is below another return's (ReturnComparison). The table, with the
/// manuals' block orders, is in docs/CLI.md (MCAP). A mode byte no manual names: unknown.
NebulaReturnType nebula_return_type(Model model, std::uint8_t return_mode, std::uint8_t return_index, bool identical,
                                    bool weaker) noexcept;
/// The same for a decoded point of the packet `info`, its returns compared in `compare`.
NebulaReturnType nebula_return_type(const PacketInfo& info, const ReturnComparison& compare, const Point& p) noexcept;

/// nebula_return_type() for the points of one packet, from a table of the packet's 16 cases
/// (return_index 0..3, identical, weaker) made once: a point costs two bit reads and a load.
class PacketReturnTypes {
 public:
  PacketReturnTypes() = default;  ///< no packet: every point unknown
  explicit PacketReturnTypes(const PacketInfo& info) noexcept;
  /// nebula_return_type(info, compare, p) for a point of the packet, its returns compared in `compare`.
  NebulaReturnType operator()(const ReturnComparison& compare, const Point& p) const noexcept {
    const std::size_t ch = static_cast<std::size_t>(p.channel > 0 ? p.channel - 1 : 0);
    const bool identical = compare.is_identical(p.block, ch), weaker = compare.is_weaker(p.block, ch);
    if (p.return_index > 3) return nebula_return_type(model_, return_mode_, p.return_index, identical, weaker);
    return table_[static_cast<std::size_t>(p.return_index) * 4 + (identical ? 2u : 0u) + (weaker ? 1u : 0u)];
  }
  /// The same for `count` points into `out`; fastest for the points of one block (one block and
  /// return index: their comparison rows and table row are read once).
  void of_block(const ReturnComparison& compare, const Point* points, std::size_t count,
                NebulaReturnType* out) const noexcept;

 private:
  Model model_ = Model::unknown;
  std::uint8_t return_mode_ = 0;
  NebulaReturnType table_[16] = {};
};

/// One point record (the layout above); `stamp_ns` is the message's header.stamp, `return_type`
/// the point's nebula ReturnType.
void encode_point(const Point& p, NebulaReturnType return_type, std::int64_t stamp_ns, std::uint8_t out[kPointStep]);

/// The data of one PointCloud2 message, its records (the layout above) encoded as the points come.
/// Its header.stamp, the earliest point's time, is known only once the last point has come: until
/// then each record holds its point's time after that of the earliest point of the first add(),
/// and finish() makes them offsets from stamp_ns() (a store a record only when a later point was
/// earlier still). Memory: kPointStep bytes a point, and 8 more a point in a message
/// whose points' times span 2^31 ns (2.1 s) or more; clear() keeps the storage for the next one.
/// Not copyable.
class PointCloud2Data {
 public:
  PointCloud2Data() = default;
  PointCloud2Data(PointCloud2Data&&) = default;
  PointCloud2Data& operator=(PointCloud2Data&&) = default;

  /// Appends the records of `count` points; `types`: their return types (null: unknown).
  void add(const Point* points, const NebulaReturnType* types, std::size_t count);
  /// Room for `points` records in all without growing.
  void reserve(std::size_t points);
  /// Points added.
  std::size_t size() const { return count_; }
  /// Room for this many points without growing.
  std::size_t capacity() const { return capacity_; }
  /// header.stamp: the earliest point's time, ns since the Unix epoch (0 without points).
  std::int64_t stamp_ns() const { return count_ != 0 ? min_ : 0; }
  /// Finishes the records up to `end` (<= size()) and returns them all, kPointStep bytes each: those
  /// before `end` byte for byte encode_point(point, its type, stamp_ns()). A record is finished
  /// once, whatever the calls: finish(end) in pieces lets each piece be used while it is in cache.
  /// add() after finish() is not allowed until clear().
  const std::uint8_t* finish(std::size_t end);
  const std::uint8_t* finish() { return finish(count_); }
  /// No points; the storage stays.
  void clear();

 private:
  std::unique_ptr<std::uint8_t[]> bytes_;  // capacity_ records, count_ of them written
  std::size_t capacity_ = 0;
  std::size_t count_ = 0;
  // The records' time_stamp: the point's time minus base_, as a wrapping 32-bit number (exact
  // while the times span less than 2^31 ns); min_ and max_: the earliest and latest time.
  std::int64_t base_ = 0, min_ = 0, max_ = 0;
  // Each point's time, from the first add() that made the span 2^31 ns or more (wide_) on.
  std::vector<std::int64_t> times_;
  bool wide_ = false;
  std::size_t finished_ = 0;  // records finished (finish())
};

/// `name` as a bag records a topic: checked against ROS 2's topic-name rules (rcl's
/// validate_topic_name, for a name whose substitutions are done): only letters, digits, '_' and
/// '/'; not empty; no token (the text between slashes) starting with a digit; no "//", no "__";
/// no trailing '/'. '~' (the node's private namespace) and other "{...}" substitutions are refused:
/// a file has no node to resolve them against. A relative name is made fully qualified ("/" + it).
/// Returns the fully qualified name, or "" with the broken rule in `why`.
std::string ros2_topic(const std::string& name, std::string& why);
/// Whether `token` is a ROS 2 name token: letters, digits and '_', not starting with a digit,
/// no "__", not empty.
bool ros2_token(const std::string& token);

}  // namespace port
}  // namespace hesai
