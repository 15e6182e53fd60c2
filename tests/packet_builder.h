// Test-only builders of synthetic packets, field by field from the manuals' layouts.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "hesai/bytes.h"
#include "hesai/crc32.h"
#include "hesai/hmac.h"
#include "hesai/model.h"
#include "hesai/qt128_packet.h"

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

/// QT128C2X protocol 3.2 packet (manual 3.1.2) with the given flags; CRCs filled by qt128_seal().
inline std::vector<std::uint8_t> qt128_packet(std::uint8_t flags, std::uint8_t return_mode, std::uint8_t mode_flag,
                                              const Stamp& s, std::uint16_t rpm = 600, std::uint32_t seq = 0) {
  std::size_t len = 12 + 1028 + 4;
  const std::size_t fs = (flags & 4) ? len : 0;
  len += (flags & 4) ? 17u : 0u;
  const std::size_t tail = len;
  len += 26u + ((flags & 1) ? 4u : 0u) + 4u + ((flags & 8) ? 32u : 0u);
  std::vector<std::uint8_t> p(len, 0);
  p[0] = 0xEE; p[1] = 0xFF; p[2] = 3; p[3] = 2;
  p[6] = 0x80; p[7] = 0x02; p[9] = 0x04;
  const bool dual = return_mode == 0x39 || return_mode == 0x3A || return_mode == 0x3B || return_mode == 0x3C || return_mode == 0x3E;
  p[10] = dual ? 2 : 1;
  p[11] = flags;
  hesai::store_le16(&p[12], 30000);        // 300.00 degrees
  hesai::store_le16(&p[12 + 514], 30000);
  if (fs) p[fs] = 1;
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
inline void qt128_point(std::vector<std::uint8_t>& p, int block, int channel, std::uint16_t raw, std::uint8_t refl,
                        std::uint8_t confidence = 0) {
  const std::size_t at = 12 + 514 * static_cast<std::size_t>(block - 1) + 2 + 4 * static_cast<std::size_t>(channel - 1);
  hesai::store_le16(&p[at], raw);
  p[at + 2] = refl;
  p[at + 3] = confidence;
}
/// Offsets of a QT128 packet's sections from its flags (protocol notes table).
struct QtOffsets {
  std::size_t fs, tail, crc3, sig;
};
inline QtOffsets qt128_offsets(std::uint8_t flags) {
  QtOffsets o{};
  std::size_t at = 1044;
  o.fs = (flags & 4) ? at : 0;
  at += (flags & 4) ? 17 : 0;
  o.tail = at;
  o.crc3 = at + 26 + ((flags & 1) ? 4 : 0);
  o.sig = (flags & 8) ? o.crc3 + 4 : 0;
  return o;
}
/// Fills CRC1, CRC2 and CRC3 (hesai::qt128::seal, itself checked on the sensor's own packets in
/// test_decoder.cpp) and, with a key, the signature.
inline void qt128_seal(std::vector<std::uint8_t>& p, const std::uint8_t* key = nullptr) {
  ASSERT_EQ(hesai::qt128::seal(p.data(), p.size()), hesai::Error::ok) << "a QT128 packet of " << p.size() << " bytes";
  const QtOffsets o = qt128_offsets(p[11]);
  if (o.sig && key) hesai::hmac_sha256(hesai::ByteView{key, 32}, hesai::ByteView{p.data(), o.sig}, &p[o.sig]);
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

/// A real packet as a counter-clockwise unit would have sent it: each block azimuth a replaced by
/// 36000 - a (0 stays 0), so the azimuths fall packet after packet; the QT128's CRCs recomputed
/// (its signature bytes, all zero in the bundled capture, are left as they are). Block layouts:
/// Pandar40 manual Section 3.1.2 (10 blocks of 124 bytes, azimuth after the 2-byte preamble; the
/// 40P the same), Pandar64 manual Section 3.1.2 (8-byte header, 6 blocks of 194 bytes), QT128C2X
/// manual Section 3.1.2 (12-byte header, 2 blocks of 514 bytes).
inline std::vector<std::uint8_t> counterclockwise_copy(const std::vector<std::uint8_t>& packet, hesai::Model model) {
  std::vector<std::uint8_t> p = packet;
  std::size_t first = 2, stride = 124, blocks = 10;
  if (model == hesai::Model::pandar64) { first = 8; stride = 194; blocks = 6; }
  if (model == hesai::Model::qt128c2x) { first = 12; stride = 514; blocks = 2; }
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::uint16_t a = hesai::load_le16(&p[first + b * stride]);
    hesai::store_le16(&p[first + b * stride], static_cast<std::uint16_t>((36000 - a) % 36000));
  }
  if (model == hesai::Model::qt128c2x) qt128_seal(p);
  return p;
}

}  // namespace hesai_test
