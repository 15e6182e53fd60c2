// GPS packet tests. The captures hold no GPS packets, so every packet here is built by hand from
// the manuals' tables (here and in packet_builder.h), with offsets typed in from them (not taken
// from hesai/gps.h):
//   Pandar40 (manual Section 3.2.2, Table 3.6): FF EE | date 6 @2 | time 6 @8 | us time u32 @14 |
//     GPRMC 77 @18 | 411 x 0xDF @95 | location valid @506 | PPS lock @507 | reserved 4 @508
//   Pandar64 (manual Section 3.2.2 "GPS UDP data"): FF EE | date 6 @2 | time 6 @8 | reserved 4 @14 |
//     NMEA 84 @18 | 404 x 0xDF @102 | positioning status @506 | PPS lock @507 | reserved 4 @508
// Date/time digits are "lower byte first": the units digit comes first on the wire.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "hesai/gps.h"
#include "packet_builder.h"

namespace {

using hesai::ByteView;
using hesai::Error;
using hesai::GpsLayout;
using hesai::GpsPacket;
using Packet = hesai_test::GpsBytes;
using namespace hesai_test;

// The manuals' example sentences (Pandar64 manual, Sections 3.2.2.1 and 3.2.2.2), as printed;
// kGpsRmc67 and the packet builders are in packet_builder.h.
const char* const kRmc74Hash = "$GPRMC,065829.00,A,3121.86377,N,12114.68322,E,0.027,,#160617#,,,A*74";
const char* const kGga47 = "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47";
const char* const kGga60Printed = "$GPGGA,134658.00,5106.9792,N,11402.3003,W,2,09,1.0,1048.47,M,-6.27,M,08,AAAA*60";

[[nodiscard]] Error parse(const Packet& p, GpsPacket& out) { return hesai::parse_gps_packet(ByteView{p.data(), p.size()}, out); }

void expect_time(const hesai::DateTime& t, int y, int mo, int d, int h, int mi, int s) {
  EXPECT_EQ(t.year, y);
  EXPECT_EQ(t.month, mo);
  EXPECT_EQ(t.day, d);
  EXPECT_EQ(t.hour, h);
  EXPECT_EQ(t.minute, mi);
  EXPECT_EQ(t.second, s);
}

// ---------------------------------------------------------------------------------------------
// The manuals' examples

// Pandar64 manual, Section 3.2.4, Figure 18: 0x30 0x32 = 20, 0x34 0x30 = 04, 0x37 0x30 = 07,
// 0x38 0x35 = 58, 0x37 0x30 = 07, 0x34 0x30 = 04 -> 2020-04-07 04:07:58.
TEST(GpsPandar64, ManualFigure18) {
  Packet p = gps_base64();
  const std::uint8_t wire[12] = {0x30, 0x32, 0x34, 0x30, 0x37, 0x30, 0x38, 0x35, 0x37, 0x30, 0x34, 0x30};
  std::memcpy(p.data() + 2, wire, sizeof wire);
  GpsPacket g;
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar64);
  expect_time(g.time, 2020, 4, 7, 4, 7, 58);
  EXPECT_EQ(g.us_time, 0u);
  EXPECT_EQ(g.nmea_length, 0u);
  EXPECT_STREQ(g.nmea, "");
  EXPECT_FALSE(g.nmea_checksum_ok);
  EXPECT_EQ(g.location_status, 0);
  EXPECT_FALSE(g.pps_locked);
}

// Pandar40 manual, Section 3.2.2, "Example of GPS Data Packet UDP Data Analysis": year 0x37 0x31
// = 17, month 0x32 0x31 = 12, day 0x30 0x32 = 20, second 0x32 0x35 = 52, minute 0x35 0x34 = 45,
// hour 0x32 0x31 = 12 -> 2017-12-20 12:45:52. us time (same example, "us Time"):
// (45 * 60 + 52) * 1e6 = 2 752 000 000 = 0xA408_3000.
TEST(GpsPandar40, ManualExample) {
  Packet p = gps_base40();
  const std::uint8_t wire[12] = {0x37, 0x31, 0x32, 0x31, 0x30, 0x32, 0x32, 0x35, 0x35, 0x34, 0x32, 0x31};
  std::memcpy(p.data() + 2, wire, sizeof wire);
  p[14] = 0x00;
  p[15] = 0x30;
  p[16] = 0x08;
  p[17] = 0xA4;
  gps_put_sentence(p, kGpsRmc67);
  p[506] = 'V';
  p[507] = 0;
  GpsPacket g;
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar40);
  expect_time(g.time, 2017, 12, 20, 12, 45, 52);
  EXPECT_EQ(g.us_time, 2752000000u);
  EXPECT_STREQ(g.nmea, kGpsRmc67);
  EXPECT_EQ(g.nmea_length, 70u);
  EXPECT_TRUE(g.nmea_checksum_ok);
  EXPECT_EQ(g.location_status, 'V');
  EXPECT_FALSE(g.pps_locked);
}

// The Pandar64 manual's GPRMC example in a Pandar64 packet dated as the sentence says.
// Checksum by hand: XOR of "GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W" is 0x67,
// so the manual's "*67" is right.
TEST(GpsPandar64, ManualGprmcExample) {
  GpsPacket g;
  ASSERT_EQ(parse(gps_rmc64(), g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar64);
  expect_time(g.time, 2017, 6, 16, 7, 22, 42);
  EXPECT_EQ(g.us_time, 0u);
  EXPECT_STREQ(g.nmea, "$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W*67");
  EXPECT_EQ(g.nmea_length, 70u);
  EXPECT_TRUE(g.nmea_checksum_ok);
  EXPECT_EQ(g.location_status, 'A');
  EXPECT_TRUE(g.pps_locked);
}

TEST(GpsPandar40, SameSentenceAndTime) {
  GpsPacket g;
  ASSERT_EQ(parse(gps_rmc40(), g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar40);
  expect_time(g.time, 2017, 6, 16, 7, 22, 42);
  EXPECT_EQ(g.us_time, 1362000000u);
  EXPECT_STREQ(g.nmea, kGpsRmc67);
  EXPECT_EQ(g.nmea_length, 70u);
  EXPECT_TRUE(g.nmea_checksum_ok);
  EXPECT_EQ(g.location_status, 'A');
  EXPECT_TRUE(g.pps_locked);
}

// ---------------------------------------------------------------------------------------------
// NMEA checksum

struct SentenceCase {
  const char* sentence;
  bool checksum_ok;
  const char* why;
};

// Expected results worked out by hand (XOR of the characters between '$' and '*').
const SentenceCase kSentences[] = {
    {kGpsRmc67, true, "manual GPRMC example 1"},
    // The '#' marks look like OCR artefacts; '#' ^ '#' = 0, so the checksum holds either way.
    {kRmc74Hash, true, "manual GPRMC example 2 as printed"},
    {"$GPRMC,065829.00,A,3121.86377,N,12114.68322,E,0.027,,160617,,,A*74", true, "example 2 without '#'"},
    {kGga47, true, "manual GPGGA example 1"},
    // As printed the sentence XORs to 0x51; with "-16.27" instead of "-6.27" ('1' = 0x31, 0x51 ^ 0x31 = 0x60)
    // it matches its "*60": the manual lost a '1'.
    {kGga60Printed, false, "manual GPGGA example 2 as printed"},
    {"$GPGGA,134658.00,5106.9792,N,11402.3003,W,2,09,1.0,1048.47,M,-16.27,M,08,AAAA*60", true,
     "GPGGA example 2 with -16.27"},
    {"$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W*68", false, "last hex digit off by one"},
    {"$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W*76", false, "hex digits swapped"},
    // 'N' -> 'S': 0x4E ^ 0x53 = 0x1D, 0x67 ^ 0x1D = 0x7A.
    {"$GPRMC,072242,A,3027.3680,S,11423.6975,E,000.0,316.7,160617,004.1,W*7A", true, "hex letter"},
    {"$GPRMC,072242,A,3027.3680,S,11423.6975,E,000.0,316.7,160617,004.1,W*7a", true, "lower-case hex letter"},
    {"$GPRMC,072242,A,3027.3680,S,11423.6975,E,000.0,316.7,160617,004.1,W*7G", false, "not a hex digit"},
    {"$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,X*67", false, "payload changed"},
    {"!GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W*67", false, "no '$'"},
    {"$*00", true, "empty payload XORs to 0"},
    {"$*01", false, "empty payload, wrong sum"},
};

TEST(GpsNmea, ChecksumInBothLayouts) {
  for (const SentenceCase& c : kSentences) {
    SCOPED_TRACE(c.why);
    const std::size_t len = std::strlen(c.sentence);
    for (const bool p40 : {false, true}) {
      if (p40 && len > 77) continue;  // does not fit the Pandar40 GPRMC field
      Packet p = p40 ? gps_rmc40() : gps_rmc64();
      for (std::size_t i = 18; i < (p40 ? 95u : 102u); ++i) p[i] = 0;
      gps_put_sentence(p, c.sentence);
      GpsPacket g;
      ASSERT_EQ(parse(p, g), Error::ok);
      EXPECT_EQ(g.layout, p40 ? GpsLayout::pandar40 : GpsLayout::pandar64);
      EXPECT_STREQ(g.nmea, c.sentence);
      EXPECT_EQ(g.nmea_length, len);
      EXPECT_EQ(g.nmea_checksum_ok, c.checksum_ok);
    }
  }
}

TEST(GpsNmea, LongestSentences) {
  // 77 characters fill the Pandar40 field: seven more '0's in field 10 (7 x 0x30 = 0x30, 0x67 ^ 0x30 = 0x57).
  const char* s77 = "$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,0000000004.1,W*57";
  ASSERT_EQ(std::strlen(s77), 77u);
  Packet p = gps_rmc40();
  gps_put_sentence(p, s77);
  GpsPacket g;
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar40);
  EXPECT_EQ(g.nmea_length, 77u);
  EXPECT_STREQ(g.nmea, s77);
  EXPECT_TRUE(g.nmea_checksum_ok);

  // 84 characters fill the Pandar64 field: fourteen more '0's cancel out (still 0x67).
  const char* s84 = "$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,00000000000000004.1,W*67";
  ASSERT_EQ(std::strlen(s84), 84u);
  p = gps_rmc64();
  gps_put_sentence(p, s84);
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar64);
  EXPECT_EQ(g.nmea_length, 84u);
  EXPECT_STREQ(g.nmea, s84);
  EXPECT_EQ(g.nmea[84], '\0');
  EXPECT_TRUE(g.nmea_checksum_ok);
}

TEST(GpsNmea, SentenceStopsTwoBytesAfterStar) {
  Packet p = gps_rmc64();
  // CR LF and junk after the checksum stay out of the sentence.
  const char tail[] = "\r\nXYZ*12";
  std::memcpy(p.data() + 18 + 70, tail, sizeof tail - 1);
  GpsPacket g;
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_STREQ(g.nmea, kGpsRmc67);
  EXPECT_EQ(g.nmea_length, 70u);
  EXPECT_TRUE(g.nmea_checksum_ok);
}

TEST(GpsNmea, NoSentence) {
  struct Case {
    const char* field;
    const char* why;
  };
  const Case cases[] = {
      {"", "all zero"},
      {"$GPRMC,072242,A", "no '*'"},
      {"$GPRMC,072242,A*", "nothing after '*'"},
      {"$GPRMC,072242,A*6", "one byte after '*'"},
      {"$GPRMC,07\x01" "2242,A*67", "control byte inside"},
      {"$GPRMC,07\x80" "2242,A*67", "high byte inside"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.why);
    for (const bool p40 : {false, true}) {
      Packet p = p40 ? gps_rmc40() : gps_rmc64();
      for (std::size_t i = 18; i < (p40 ? 95u : 102u); ++i) p[i] = 0;
      gps_put_sentence(p, c.field);
      GpsPacket g;
      ASSERT_EQ(parse(p, g), Error::ok);  // the date and time still count
      EXPECT_EQ(g.nmea_length, 0u);
      EXPECT_STREQ(g.nmea, "");
      EXPECT_FALSE(g.nmea_checksum_ok);
      expect_time(g.time, 2017, 6, 16, 7, 22, 42);
    }
  }
}

TEST(GpsNmea, StarAtTheEndOfTheField) {
  // Pandar40: printable bytes fill the 77-byte field, '*' at field index 75 or 76: the two bytes after
  // it would be in the 0xDF filler, so there is no sentence.
  for (const std::size_t star : {75u, 76u}) {
    Packet p = gps_rmc40();
    p[18] = '$';
    for (std::size_t i = 19; i < 95; ++i) p[i] = 'A';
    p[18 + star] = '*';
    GpsPacket g;
    ASSERT_EQ(parse(p, g), Error::ok);
    EXPECT_EQ(g.layout, GpsLayout::pandar40);
    EXPECT_EQ(g.nmea_length, 0u);
  }
  // Pandar64 likewise at field index 82 or 83.
  for (const std::size_t star : {82u, 83u}) {
    Packet p = gps_rmc64();
    p[18] = '$';
    for (std::size_t i = 19; i < 102; ++i) p[i] = 'A';
    p[18 + star] = '*';
    GpsPacket g;
    ASSERT_EQ(parse(p, g), Error::ok);
    EXPECT_EQ(g.layout, GpsLayout::pandar64);
    EXPECT_EQ(g.nmea_length, 0u);
  }
  // '*' at index 81 leaves exactly two bytes: an 84-byte sentence.
  Packet p = gps_rmc64();
  p[18] = '$';
  for (std::size_t i = 19; i < 102; ++i) p[i] = 'A';
  p[18 + 81] = '*';
  GpsPacket g;
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.nmea_length, 84u);
  EXPECT_FALSE(g.nmea_checksum_ok);  // "AA" is not the XOR of 80 'A's (which is 0)
}

// ---------------------------------------------------------------------------------------------
// Recognition: length, magic, filler

TEST(GpsRecognition, IsGpsPacket) {
  const Packet p40 = gps_rmc40();
  const Packet p64 = gps_rmc64();
  EXPECT_TRUE(hesai::is_gps_packet(ByteView{p40.data(), 512}));
  EXPECT_TRUE(hesai::is_gps_packet(ByteView{p64.data(), 512}));
  Packet bad = p64;
  bad[0] = 0xEE;
  bad[1] = 0xFF;  // the Pandar64 point-cloud order, not the GPS header
  EXPECT_FALSE(hesai::is_gps_packet(ByteView{bad.data(), 512}));
  EXPECT_FALSE(hesai::is_gps_packet(ByteView{}));
}

TEST(GpsRecognition, EveryWrongLength) {
  std::array<std::uint8_t, 1024> buf{};
  const Packet p = gps_rmc64();
  std::memcpy(buf.data(), p.data(), p.size());
  for (std::size_t i = 512; i < buf.size(); ++i) buf[i] = 0xDF;
  GpsPacket g;
  g.us_time = 12345;
  for (std::size_t n = 0; n <= buf.size(); ++n) {
    if (n == 512) continue;
    SCOPED_TRACE(n);
    EXPECT_FALSE(hesai::is_gps_packet(ByteView{buf.data(), n}));
    EXPECT_EQ(hesai::parse_gps_packet(ByteView{buf.data(), n}, g), Error::bad_length);
  }
  EXPECT_EQ(g.us_time, 12345u);  // untouched on error
  EXPECT_EQ(hesai::parse_gps_packet(ByteView{buf.data(), 512}, g), Error::ok);
}

TEST(GpsRecognition, EveryMagicCorruption) {
  for (const bool p40 : {false, true}) {
    for (std::size_t at = 0; at < 2; ++at) {
      for (unsigned v = 0; v < 256; ++v) {
        Packet p = p40 ? gps_rmc40() : gps_rmc64();
        const std::uint8_t good = p[at];
        if (v == good) continue;
        p[at] = static_cast<std::uint8_t>(v);
        GpsPacket g;
        EXPECT_FALSE(hesai::is_gps_packet(ByteView{p.data(), p.size()})) << at << " " << v;
        EXPECT_EQ(parse(p, g), Error::bad_magic) << at << " " << v;
      }
    }
  }
}

// Bytes 102..505 are 0xDF in both layouts: any other byte there rejects the packet.
TEST(GpsRecognition, SharedFillerMustBeDF) {
  for (const bool p40 : {false, true}) {
    for (std::size_t i = 102; i < 506; ++i) {
      for (const std::uint8_t v : {std::uint8_t{0x00}, std::uint8_t{0xDE}, std::uint8_t{0x5F}}) {
        Packet p = p40 ? gps_rmc40() : gps_rmc64();
        p[i] = v;
        GpsPacket g;
        EXPECT_EQ(parse(p, g), Error::bad_magic) << (p40 ? "Pandar40 " : "Pandar64 ") << i;
      }
    }
  }
}

// Bytes 95..101 tell the layouts apart: 0xDF filler in a Pandar40 packet, the end of the 84-byte
// NMEA field in a Pandar64 packet. Bytes 14..17 are then the us time or reserved.
TEST(GpsRecognition, FillerStartTellsTheLayouts) {
  GpsPacket g;
  ASSERT_EQ(parse(gps_rmc40(), g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar40);
  EXPECT_EQ(g.us_time, 1362000000u);
  for (std::size_t i = 95; i < 102; ++i) {
    SCOPED_TRACE(i);
    Packet p = gps_rmc40();  // bytes 14..17 hold 1 362 000 000
    p[i] = 0x00;
    ASSERT_EQ(parse(p, g), Error::ok);
    EXPECT_EQ(g.layout, GpsLayout::pandar64);
    EXPECT_EQ(g.us_time, 0u);  // reserved in a Pandar64 packet
    EXPECT_STREQ(g.nmea, kGpsRmc67);
  }
  // A Pandar64 packet whose NMEA field ends in zero bytes (a short sentence) is Pandar64.
  ASSERT_EQ(parse(gps_rmc64(), g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar64);
  // A sentence longer than 77 bytes can only be Pandar64.
  Packet p = gps_rmc64();
  gps_put_sentence(p, "$GPGGA,134658.00,5106.9792,N,11402.3003,W,2,09,1.0,1048.47,M,-16.27,M,08,AAAA*60");
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.layout, GpsLayout::pandar64);
  EXPECT_EQ(g.nmea_length, 80u);
  EXPECT_TRUE(g.nmea_checksum_ok);
}

// ---------------------------------------------------------------------------------------------
// Date and time digits

bool is_ascii_digit(unsigned v) { return v >= 0x30 && v <= 0x39; }

TEST(GpsDigits, EveryNonDigitIsRejected) {
  for (const bool p40 : {false, true}) {
    for (std::size_t at = 2; at < 14; ++at) {
      for (unsigned v = 0; v < 256; ++v) {
        if (is_ascii_digit(v)) continue;
        Packet p = p40 ? gps_rmc40() : gps_rmc64();
        p[at] = static_cast<std::uint8_t>(v);
        GpsPacket g;
        g.us_time = 777;
        EXPECT_EQ(parse(p, g), Error::bad_gps_field) << at << " " << v;
        EXPECT_EQ(g.us_time, 777u);
      }
    }
  }
}

// Every digit substituted into every position of 2017-06-16 07:22:42 ("716061242270" on the wire):
// the field's value is tens * 10 + units with the units digit first; valid or bad_gps_field.
TEST(GpsDigits, EveryDigitSubstitution) {
  struct Field {
    std::size_t offset;
    int units, tens;  // digits of the base value
    int min, max;     // valid range for 2017-06 (June has 30 days)
  };
  const Field fields[] = {
      {2, 7, 1, 0, 99},   // year 17
      {4, 6, 0, 1, 12},   // month 06
      {6, 6, 1, 1, 30},   // day 16 (valid for month 06)
      {8, 2, 4, 0, 59},   // second 42
      {10, 2, 2, 0, 59},  // minute 22
      {12, 7, 0, 0, 23},  // hour 07
  };
  for (std::size_t f = 0; f < 6; ++f) {
    for (int which = 0; which < 2; ++which) {
      for (int d = 0; d < 10; ++d) {
        const Field& fl = fields[f];
        const int value = which == 0 ? fl.tens * 10 + d : d * 10 + fl.units;
        Packet p = gps_rmc64();
        p[fl.offset + static_cast<std::size_t>(which)] = static_cast<std::uint8_t>('0' + d);
        GpsPacket g;
        const Error e = parse(p, g);
        SCOPED_TRACE(testing::Message() << "field " << f << " byte " << which << " digit " << d);
        if (value < fl.min || value > fl.max) {
          EXPECT_EQ(e, Error::bad_gps_field);
          continue;
        }
        ASSERT_EQ(e, Error::ok);
        const int got[6] = {g.time.year - 2000, g.time.month, g.time.day, g.time.second, g.time.minute, g.time.hour};
        const int base[6] = {17, 6, 16, 42, 22, 7};
        for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(got[k], k == f ? value : base[k]);
      }
    }
  }
}

TEST(GpsDigits, CalendarEdges) {
  struct Case {
    char wire[13];  // year, month, day, second, minute, hour: units digit first
    bool ok;
    const char* why;
  };
  const Case cases[] = {
      {"001010000000", true, "2000-01-01 00:00:00"},
      {"992113959532", true, "2099-12-31 23:59:59"},
      {"022092000000", true, "2020-02-29 (leap year)"},
      {"712092000000", false, "2017-02-29"},
      {"710010000000", false, "2017-00-01"},
      {"713110000000", false, "2017-13-01"},
      {"716000000000", false, "2017-06-00"},
      {"716013000000", false, "2017-06-31"},
      {"716023000000", false, "2017-06-32"},
      {"716011000042", false, "2017-06-11 24:00:00"},
      {"716011006002", true, "2017-06-11 20:06:00"},
      {"716011006000", true, "2017-06-11 00:06:00"},
      {"716011000600", false, "2017-06-11 00:60:00"},
      {"716011060000", false, "2017-06-11 00:00:60"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.why);
    for (const bool p40 : {false, true}) {
      Packet p = p40 ? gps_rmc40() : gps_rmc64();
      p[14] = p[15] = p[16] = p[17] = 0;
      gps_put_time(p, c.wire);
      GpsPacket g;
      EXPECT_EQ(parse(p, g), c.ok ? Error::ok : Error::bad_gps_field);
    }
  }
  Packet p = gps_rmc64();
  gps_put_time(p, cases[1].wire);
  GpsPacket g;
  ASSERT_EQ(parse(p, g), Error::ok);
  expect_time(g.time, 2099, 12, 31, 23, 59, 59);
}

// ---------------------------------------------------------------------------------------------
// Other fields

TEST(GpsFields, LocationStatus) {
  struct Case {
    std::uint8_t byte;
    bool ok40, ok64;
  };
  const Case cases[] = {
      {'A', true, true}, {'V', true, true}, {0, true, true},
      {'0', false, true}, {'9', false, true},  // GPGGA fix quality (Pandar64 only)
      {'a', false, false}, {'v', false, false}, {'X', false, false}, {0xDF, false, false}, {' ', false, false},
  };
  for (const Case& c : cases) {
    for (const bool p40 : {false, true}) {
      Packet p = p40 ? gps_rmc40() : gps_rmc64();
      p[506] = c.byte;
      GpsPacket g;
      const bool ok = p40 ? c.ok40 : c.ok64;
      ASSERT_EQ(parse(p, g), ok ? Error::ok : Error::bad_gps_field) << int{c.byte} << " " << p40;
      if (ok) {
        EXPECT_EQ(g.location_status, static_cast<char>(c.byte));
      }
    }
  }
}

TEST(GpsFields, PpsLock) {
  for (const bool p40 : {false, true}) {
    Packet p = p40 ? gps_rmc40() : gps_rmc64();
    GpsPacket g;
    p[507] = 1;
    ASSERT_EQ(parse(p, g), Error::ok);
    EXPECT_TRUE(g.pps_locked);
    p[507] = 0;
    ASSERT_EQ(parse(p, g), Error::ok);
    EXPECT_FALSE(g.pps_locked);
    for (const std::uint8_t v : {std::uint8_t{2}, std::uint8_t{'0'}, std::uint8_t{'1'}, std::uint8_t{0xFF}}) {
      p[507] = v;
      EXPECT_EQ(parse(p, g), Error::bad_gps_field) << int{v};
    }
  }
}

TEST(GpsFields, Pandar40UsTimeBelowOneHour) {
  Packet p = gps_rmc40();
  GpsPacket g;
  // 3 599 999 999 = 0xD693_A3FF: the last microsecond of the hour.
  p[14] = 0xFF;
  p[15] = 0xA3;
  p[16] = 0x93;
  p[17] = 0xD6;
  ASSERT_EQ(parse(p, g), Error::ok);
  EXPECT_EQ(g.us_time, 3599999999u);
  // 3 600 000 000 = 0xD693_A400.
  p[14] = 0x00;
  p[15] = 0xA4;
  EXPECT_EQ(parse(p, g), Error::bad_gps_field);
  p[14] = p[15] = p[16] = p[17] = 0xFF;
  EXPECT_EQ(parse(p, g), Error::bad_gps_field);
  // The same bytes are reserved in a Pandar64 packet: ignored.
  Packet q = gps_rmc64();
  q[14] = q[15] = q[16] = q[17] = 0xFF;
  ASSERT_EQ(parse(q, g), Error::ok);
  EXPECT_EQ(g.us_time, 0u);
}

TEST(GpsFields, ReservedTailIgnored) {
  for (const bool p40 : {false, true}) {
    Packet p = p40 ? gps_rmc40() : gps_rmc64();
    p[508] = 0x12;
    p[509] = 0xDF;
    p[510] = 0xFF;
    p[511] = 0x00;
    GpsPacket g;
    ASSERT_EQ(parse(p, g), Error::ok);
    EXPECT_EQ(g.layout, p40 ? GpsLayout::pandar40 : GpsLayout::pandar64);
  }
}

TEST(GpsFields, OutputUntouchedOnError) {
  GpsPacket g;
  ASSERT_EQ(parse(gps_rmc64(), g), Error::ok);
  Packet p = gps_rmc40();
  p[507] = 7;
  ASSERT_EQ(parse(p, g), Error::bad_gps_field);
  EXPECT_EQ(g.layout, GpsLayout::pandar64);
  EXPECT_EQ(std::string(g.nmea), kGpsRmc67);
}

}  // namespace
