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
//   offset 13 return_type UINT8    Point::return_index (0 single / first block of a firing, 1, 2):
//                                  not nebula's ReturnType code, which needs the return mode
//   offset 14 channel     UINT16   0-based laser channel as nebula numbers them (Point::channel - 1)
//   offset 16 azimuth     FLOAT32  radians, [0, 2 pi) (nebula: azimuth_rad; Point::azimuth_deg)
//   offset 20 elevation   FLOAT32  radians, up positive (nebula: elevation_rad)
//   offset 24 distance    FLOAT32  metres
//   offset 28 time_stamp  UINT32   ns after header.stamp (clamped to 0 .. 2^32 - 1)
// point_step 32, row_step 32 * width, height 1, is_bigendian false, is_dense true.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

/// One point record (the layout above); `stamp_ns` is the message's header.stamp.
void encode_point(const Point& p, std::int64_t stamp_ns, std::uint8_t out[kPointStep]);

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
