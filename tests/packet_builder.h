// Test-only builders of synthetic packets, field by field from the manuals' layouts.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "hesai/bytes.h"
#include "hesai/hmac.h"
#include "hesai/model.h"
#include "hesai/detail/qt128_packet.h"

namespace hesai_test {

struct Stamp {
  int year = 2024, month = 5, day = 17, hour = 8, minute = 30, second = 15;
  std::uint32_t us = 250000;
};

/// Pandar64 packet (section 3.1.2): all distances 0 unless set with set_point().
inline std::vector<std::uint8_t> pandar64_packet(std::uint8_t return_mode, const Stamp& s, std::uint16_t rpm = 600,
                                                 bool with_sequence = false, std::uint32_t seq = 0) {
  std::vector<std::uint8_t> p(with_sequence ? 1198 : 1194, 0);
  p[0] = 0xEE; p[1] = 0xFF; p[2] = 0x40; p[3] = 0x06; p[5] = 0x04;
  for (std::size_t b = 0; b < 6; ++b) hesai::store_le16(&p[8 + 194 * b], 10000);  // 100.00 degrees
  const std::size_t t = 1172;
  hesai::store_le16(&p[t + 8], rpm);
  hesai::store_le32(&p[t + 10], s.us);
  p[t + 14] = return_mode;
  p[t + 15] = 0x42;
  const int dt[6] = {s.year - 2000, s.month, s.day, s.hour, s.minute, s.second};
  for (std::size_t i = 0; i < 6; ++i) p[t + 16 + i] = static_cast<std::uint8_t>(dt[i]);
  if (with_sequence) hesai::store_le32(&p[1194], seq);
  return p;
}
inline void pandar64_point(std::vector<std::uint8_t>& p, int block, int channel, std::uint16_t raw, std::uint8_t refl) {
  const std::size_t at = 8 + 194 * static_cast<std::size_t>(block - 1) + 2 + 3 * static_cast<std::size_t>(channel - 1);
  hesai::store_le16(&p[at], raw);
  p[at + 2] = refl;
}
inline void pandar64_azimuth(std::vector<std::uint8_t>& p, int block, std::uint16_t cdeg) {
  hesai::store_le16(&p[8 + 194 * static_cast<std::size_t>(block - 1)], cdeg);
}

/// Pandar40 (1256) or Pandar40P (1262/1266) packet (Pandar40 manual 3.1.2).
inline std::vector<std::uint8_t> pandar40_packet(bool plus, std::uint8_t return_mode, const Stamp& s,
                                                 std::uint32_t timestamp_us, std::uint16_t rpm = 600) {
  std::vector<std::uint8_t> p(plus ? 1262 : 1256, 0);
  for (int b = 0; b < 10; ++b) {
    p[124 * static_cast<std::size_t>(b)] = 0xFF;
    p[124 * static_cast<std::size_t>(b) + 1] = 0xEE;
    hesai::store_le16(&p[124 * static_cast<std::size_t>(b) + 2], 20000);  // 200.00 degrees
  }
  hesai::store_le16(&p[1248], rpm);
  hesai::store_le32(&p[1250], timestamp_us);
  p[1254] = return_mode;
  p[1255] = 0x42;
  if (plus) {
    const int dt[6] = {s.year - 2000, s.month, s.day, s.hour, s.minute, s.second};
    for (int i = 0; i < 6; ++i) p[1256 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(dt[i]);
  }
  return p;
}
inline void pandar40_point(std::vector<std::uint8_t>& p, int block, int channel, std::uint16_t raw, std::uint8_t refl) {
  const std::size_t at = 124 * static_cast<std::size_t>(block - 1) + 4 + 3 * static_cast<std::size_t>(channel - 1);
  hesai::store_le16(&p[at], raw);
  p[at + 2] = refl;
}

/// Offsets of a QT128 packet's sections from its header's laser num N and flags (protocol notes
/// table): units of 3 bytes (distance, reflectivity), 4 with flags bit 4 (a confidence byte; the
/// vendor SDK's unitSize()); blocks of azimuth + N units; then CRC1, the functional-safety
/// section (bit 2), the 26-byte tail, the UDP sequence (bit 0), CRC3, the signature (bit 3).
struct QtOffsets {
  std::size_t unit, block, crc1, fs, tail, crc3, sig, total;
};
inline QtOffsets qt128_offsets(std::size_t lasers, std::uint8_t flags) {
  QtOffsets o{};
  o.unit = (flags & 0x10) ? 4 : 3;
  o.block = 2 + lasers * o.unit;
  o.crc1 = 12 + 2 * o.block;
  std::size_t at = o.crc1 + 4;
  o.fs = (flags & 4) ? at : 0;
  at += (flags & 4) ? 17 : 0;
  o.tail = at;
  o.crc3 = at + 26 + ((flags & 1) ? 4 : 0);
  o.sig = (flags & 8) ? o.crc3 + 4 : 0;
  o.total = o.crc3 + 4 + ((flags & 8) ? 32 : 0);
  return o;
}
/// The offsets of this packet, from its own header (bytes 6 and 11).
inline QtOffsets qt128_offsets(const std::vector<std::uint8_t>& p) { return qt128_offsets(p[6], p[11]); }

/// QT128C2X protocol 3.2 packet (manual 3.1.2) with the given flags, 128 units per block; CRCs
/// filled by qt128_seal().
inline std::vector<std::uint8_t> qt128_packet(std::uint8_t flags, std::uint8_t return_mode, std::uint8_t mode_flag,
                                              const Stamp& s, std::uint16_t rpm = 600, std::uint32_t seq = 0) {
  const QtOffsets o = qt128_offsets(128, flags);
  std::vector<std::uint8_t> p(o.total, 0);
  p[0] = 0xEE; p[1] = 0xFF; p[2] = 3; p[3] = 2;
  p[6] = 0x80; p[7] = 0x02; p[9] = 0x04;
  const bool dual = return_mode == 0x39 || return_mode == 0x3A || return_mode == 0x3B || return_mode == 0x3C || return_mode == 0x3E;
  p[10] = dual ? 2 : 1;
  p[11] = flags;
  hesai::store_le16(&p[12], 30000);        // 300.00 degrees
  hesai::store_le16(&p[12 + o.block], 30000);
  if (o.fs) p[o.fs] = 1;
  const std::size_t tail = o.tail;
  p[tail + 5] = mode_flag;
  p[tail + 12] = return_mode;
  hesai::store_le16(&p[tail + 13], rpm);
  const int dt[6] = {s.year - 1900, s.month, s.day, s.hour, s.minute, s.second};
  for (std::size_t i = 0; i < 6; ++i) p[tail + 15 + i] = static_cast<std::uint8_t>(dt[i]);
  hesai::store_le32(&p[tail + 21], s.us);
  p[tail + 25] = 0x42;
  if (flags & 1) hesai::store_le32(&p[tail + 26], seq);
  return p;
}
/// Sets unit `channel` (1-based position) of `block` (1-based); the confidence byte only with 4-byte units.
inline void qt128_point(std::vector<std::uint8_t>& p, int block, int channel, std::uint16_t raw, std::uint8_t refl,
                        std::uint8_t confidence = 0) {
  const QtOffsets o = qt128_offsets(p);
  const std::size_t at = 12 + o.block * static_cast<std::size_t>(block - 1) + 2 + o.unit * static_cast<std::size_t>(channel - 1);
  hesai::store_le16(&p[at], raw);
  p[at + 2] = refl;
  if (o.unit == 4) p[at + 3] = confidence;
}
/// CRC-32/MPEG-2 of n bytes by its definition, one bit at a time (QT128C2X manual, Section 3.1.2,
/// "CRC 1": poly 0x04C11DB7, init 0xFFFFFFFF, most significant bit first, no final xor), written
/// here so that the CRCs of built packets come from neither the core's CRC code nor its QT128 layout.
constexpr std::uint32_t crc32_mpeg2_reference(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= std::uint32_t{p[i]} << 24;
    for (int b = 0; b < 8; ++b) c = (c & 0x80000000u) ? (c << 1) ^ 0x04C11DB7u : c << 1;
  }
  return c;
}
inline constexpr std::uint8_t kCrcCheckString[9] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
static_assert(crc32_mpeg2_reference(kCrcCheckString, 9) == 0x0376E6E7u, "the CRC catalogue's check value");

/// Fills CRC1, CRC2 and CRC3 at this file's own offsets (qt128_offsets), with this file's own CRC,
/// and, with a key, the signature. What each covers (QT128C2X manual, Section 3.1.2, and
/// docs/protocol-notes.md of the shared project notes): CRC1 the body, bytes 12 up to CRC1; CRC2 the 12
/// functional-safety bytes after FS Version (Lidar State up to the reserved bytes); CRC3 the tail
/// up to CRC3 (the UDP sequence included). hesai::qt128::seal is compared with this in test_decoder.cpp.
inline void qt128_seal(std::vector<std::uint8_t>& p, const std::uint8_t* key = nullptr) {
  const QtOffsets o = qt128_offsets(p);
  ASSERT_EQ(p.size(), o.total) << "a QT128 packet of " << p.size() << " bytes for its laser num and flags";
  hesai::store_le32(&p[o.crc1], crc32_mpeg2_reference(&p[12], o.crc1 - 12));
  if (o.fs) hesai::store_le32(&p[o.fs + 13], crc32_mpeg2_reference(&p[o.fs + 1], 12));
  hesai::store_le32(&p[o.crc3], crc32_mpeg2_reference(&p[o.tail], o.crc3 - o.tail));
  if (o.sig && key) hesai::hmac_sha256(hesai::ByteView{key, 32}, hesai::ByteView{p.data(), o.sig}, &p[o.sig]);
}

/// A QT128 packet rebuilt byte for byte with other units: header byte 6 (laser num) and 11 (flags)
/// replaced, block b keeping the units at 0-based positions keep[b] of `p` (in that order), each
/// cut to the unit size the new flags give (3 bytes: distance and reflectivity; 4: and the
/// confidence byte); the sections after the body copied in order; then re-sealed. Only bits 4 and 6
/// may differ between the flags (the other sections stay). A signature is copied, not re-signed.
inline std::vector<std::uint8_t> qt128_rebuild(const std::vector<std::uint8_t>& p, std::uint8_t laser_num,
                                               std::uint8_t flags, const std::vector<std::size_t> (&keep)[2]) {
  const QtOffsets from = qt128_offsets(p);
  const QtOffsets to = qt128_offsets(laser_num, flags);
  std::vector<std::uint8_t> q(p.begin(), p.begin() + 12);
  q[6] = laser_num;
  q[11] = flags;
  for (std::size_t b = 0; b < 2; ++b) {
    const std::size_t block = 12 + b * from.block;
    q.insert(q.end(), p.begin() + static_cast<long>(block), p.begin() + static_cast<long>(block + 2));  // azimuth
    for (std::size_t u : keep[b]) {
      const std::size_t at = block + 2 + u * from.unit;
      for (std::size_t i = 0; i < to.unit; ++i) q.push_back(i < from.unit ? p[at + i] : 0);
    }
  }
  q.insert(q.end(), p.begin() + static_cast<long>(from.crc1), p.end());  // CRC1 (recomputed below) and after
  qt128_seal(q);
  return q;
}
/// Positions 0..n-1, for qt128_rebuild.
inline std::vector<std::size_t> first_units(std::size_t n) {
  std::vector<std::size_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

/// Rewrites a QT128 tail's date-time into the form of a year byte 0: bytes 0 and 1 zero, bytes
/// 2..5 `seconds` since the Unix epoch, big-endian (vendor SDK GetMicroLidarTimeU64); re-sealed.
inline void qt128_set_unix_time(std::vector<std::uint8_t>& p, std::uint32_t seconds) {
  const std::size_t dt = qt128_offsets(p).tail + 15;
  p[dt] = 0;
  p[dt + 1] = 0;
  hesai::store_be32(&p[dt + 2], seconds);
  qt128_seal(p);
}

// ---- GPS packets, both layouts (offsets typed in from the manuals, not from hesai/gps.h) ----
//   Pandar40 (manual Section 3.2.2, Table 3.6): FF EE | date 6 @2 | time 6 @8 | us time u32 @14 | GPRMC 77 @18 |
//     411 x 0xDF @95 | location valid @506 | PPS lock @507 | reserved 4 @508
//   Pandar64 (manual Section 3.2.2 "GPS UDP data"): FF EE | date 6 @2 | time 6 @8 | reserved 4 @14 | NMEA 84 @18 |
//     404 x 0xDF @102 | positioning status @506 | PPS lock @507 | reserved 4 @508
using GpsBytes = std::array<std::uint8_t, 512>;

/// The Pandar64 manual's GPRMC example sentence (Section 3.2.2.1), as printed.
inline const char* const kGpsRmc67 = "$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W*67";
/// 2017-06-16 07:22:42 (the date and time of kGpsRmc67): year "17", month "06", day "16",
/// second "42", minute "22", hour "07", each units digit first ("lower byte first").
inline constexpr char kGpsTime20170616[13] = "716061242270";

/// Header and filler of a Pandar40 GPS packet; everything else 0.
inline GpsBytes gps_base40() {
  GpsBytes p{};
  p[0] = 0xFF;
  p[1] = 0xEE;
  for (std::size_t i = 95; i < 506; ++i) p[i] = 0xDF;
  return p;
}
/// Header and filler of a Pandar64 GPS packet; everything else 0.
inline GpsBytes gps_base64() {
  GpsBytes p{};
  p[0] = 0xFF;
  p[1] = 0xEE;
  for (std::size_t i = 102; i < 506; ++i) p[i] = 0xDF;
  return p;
}
/// 12 date/time bytes at offset 2, exactly as they appear on the wire.
inline void gps_put_time(GpsBytes& p, const char (&wire)[13]) {
  for (std::size_t i = 0; i < 12; ++i) p[2 + i] = static_cast<std::uint8_t>(wire[i]);
}
inline void gps_put_sentence(GpsBytes& p, const char* s) { std::memcpy(p.data() + 18, s, std::strlen(s)); }

/// A Pandar64 GPS packet with kGpsRmc67, status 'A', PPS locked.
inline GpsBytes gps_rmc64() {
  GpsBytes p = gps_base64();
  gps_put_time(p, kGpsTime20170616);
  gps_put_sentence(p, kGpsRmc67);
  p[506] = 'A';
  p[507] = 1;
  return p;
}
/// A Pandar40 GPS packet with kGpsRmc67, status 'A', PPS locked.
inline GpsBytes gps_rmc40() {
  GpsBytes p = gps_base40();
  gps_put_time(p, kGpsTime20170616);
  // us time (22 * 60 + 42) * 1e6 = 1 362 000 000 = 0x512E_7880, little-endian.
  p[14] = 0x80;
  p[15] = 0x78;
  p[16] = 0x2E;
  p[17] = 0x51;
  gps_put_sentence(p, kGpsRmc67);
  p[506] = 'A';
  p[507] = 1;
  return p;
}

/// Where a model's block azimuths lie: the first at `first`, then one every `stride` bytes.
/// Pandar40 manual Section 3.1.2 (10 blocks of 124 bytes, azimuth after the 2-byte preamble; the
/// 40P the same), Pandar64 manual Section 3.1.2 (8-byte header, 6 blocks of 194 bytes), QT128C2X
/// manual Section 3.1.2 (12-byte header, 2 blocks of 514 bytes), PandarQT64 protocol 3.1 (12-byte
/// header, 4 blocks of 2 + 64 x 4 bytes), PandarXT protocol 6.1 (12-byte header, blocks of 2 +
/// lasers x 4 bytes: 8 of 66 on the XT16, 8 of 130 on the XT32, 6 of 130 on the XT32M2X).
struct BlockLayout {
  std::size_t first, stride, blocks;
};
inline BlockLayout block_layout(hesai::Model model) {
  switch (model) {
    case hesai::Model::pandar64: return {8, 194, 6};
    case hesai::Model::qt128c2x: return {12, 514, 2};
    case hesai::Model::pandar_qt64: return {12, 258, 4};
    case hesai::Model::pandar_xt16: return {12, 66, 8};
    case hesai::Model::pandar_xt32: return {12, 130, 8};
    case hesai::Model::pandar_xt32m2x: return {12, 130, 6};
    default: return {2, 124, 10};  // Pandar40, Pandar40P
  }
}

/// A packet's block azimuths, 0.01 degree, read from its bytes.
inline std::vector<std::uint16_t> block_azimuths(const std::vector<std::uint8_t>& packet, hesai::Model model) {
  const BlockLayout l = block_layout(model);
  std::vector<std::uint16_t> out;
  for (std::size_t b = 0; b < l.blocks; ++b) out.push_back(hesai::load_le16(&packet[l.first + b * l.stride]));
  return out;
}

/// A real packet as a counter-clockwise unit would have sent it: each block azimuth a replaced by
/// 36000 - a (0 stays 0), so the azimuths fall packet after packet; the QT128's CRCs recomputed
/// (its signature bytes, all zero in the bundled capture, are left as they are; the PandarQT64's
/// protocol 3.1 and the PandarXT's 6.1 have no CRC). Layouts: block_layout().
inline std::vector<std::uint8_t> counterclockwise_copy(const std::vector<std::uint8_t>& packet, hesai::Model model) {
  std::vector<std::uint8_t> p = packet;
  const BlockLayout l = block_layout(model);
  for (std::size_t b = 0; b < l.blocks; ++b) {
    const std::uint16_t a = hesai::load_le16(&p[l.first + b * l.stride]);
    hesai::store_le16(&p[l.first + b * l.stride], static_cast<std::uint16_t>((36000 - a) % 36000));
  }
  if (model == hesai::Model::qt128c2x) qt128_seal(p);
  return p;
}

}  // namespace hesai_test
