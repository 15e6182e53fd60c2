// GPS data packets of the Pandar40 and Pandar64: 512-byte UDP payloads (destination port 10110),
// sent once a second at the PPS edge. parse_gps_packet() is reentrant and thread-safe, a fixed
// number of reads; a GpsPacket is 112 bytes.
//
// Both layouts share the header, the date-time digits, the end of the 0xDF filler and the last six
// bytes; they differ in bytes 14..17 (Pandar40 "us time", Pandar64 reserved) and in the length of
// the NMEA field (77 bytes vs 84), so the filler starts at 95 (Pandar40) or at 102 (Pandar64).
// Sources: Pandar40 manual, Section 3.2.2, Table 3.6 and its example; Pandar64 manual,
// Section 3.2.2 "GPS UDP data" and Section 3.2.4 (Figure 18).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/civil_time.h"
#include "hesai/error.h"

namespace hesai {

/// Which of the two GPS packet layouts a packet has.
enum class GpsLayout : std::uint8_t {
  pandar40,  ///< date, time, u32 us time, GPRMC 77 bytes, 411 x 0xDF, location valid, PPS, 4 reserved
  pandar64,  ///< date, time, 4 reserved, NMEA 84 bytes, 404 x 0xDF, positioning status, PPS, 4 reserved
};

/// Wire layout of a GPS packet (byte offsets into the UDP payload).
namespace gps_wire {
inline constexpr std::size_t kPacketSize = 512;
inline constexpr std::uint8_t kMagic0 = 0xFF;  ///< header 0xFFEE, "0xFF first"
inline constexpr std::uint8_t kMagic1 = 0xEE;
inline constexpr std::uint8_t kFill = 0xDF;    ///< the reserved filler byte

// Common to both layouts. Each date/time field is two ASCII digits, units digit first
// ("lower byte first"): the bytes 0x30 0x32 ('0', '2') mean 20.
inline constexpr std::size_t kHeader = 0;   ///< 2 bytes FF EE
inline constexpr std::size_t kYear = 2;     ///< 2 digits, year - 2000
inline constexpr std::size_t kMonth = 4;    ///< 2 digits, 1..12
inline constexpr std::size_t kDay = 6;      ///< 2 digits
inline constexpr std::size_t kSecond = 8;   ///< 2 digits (time order: second, minute, hour)
inline constexpr std::size_t kMinute = 10;  ///< 2 digits
inline constexpr std::size_t kHour = 12;    ///< 2 digits
inline constexpr std::size_t kWord14 = 14;  ///< 4 bytes: Pandar40 us time (u32 LE), Pandar64 reserved
inline constexpr std::size_t kNmea = 18;    ///< NMEA field start (both layouts)
inline constexpr std::size_t kStatus = 506;     ///< 1 byte ASCII: 'A', 'V' or 0
inline constexpr std::size_t kPpsLock = 507;    ///< 1 byte: 1 locked, 0 unlocked
inline constexpr std::size_t kReserved = 508;   ///< 4 bytes, ignored
inline constexpr std::size_t kReservedSize = 4;

// Pandar40 (manual Section 3.2.2, Table 3.6): 18-byte time data (2 + 6 + 6 + 4), GPRMC 77, filler 411.
inline constexpr std::size_t kNmeaSize40 = 77;
inline constexpr std::size_t kFill40 = kNmea + kNmeaSize40;  ///< 95
inline constexpr std::size_t kFillSize40 = 411;

// Pandar64 (manual Section 3.2.2): 18-byte time data (2 + 6 + 6 + 4 reserved), NMEA 84, filler 404.
inline constexpr std::size_t kNmeaSize64 = 84;
inline constexpr std::size_t kFill64 = kNmea + kNmeaSize64;  ///< 102
inline constexpr std::size_t kFillSize64 = 404;

static_assert(kYear == kHeader + 2 && kSecond == kYear + 6 && kWord14 == kSecond + 6 && kNmea == kWord14 + 4,
              "GPS time data: header 2, date 6, time 6, us time / reserved 4 = 18 bytes");
static_assert(kNmea == 18);
static_assert(2 + 6 + 6 + 4 + kNmeaSize40 + kFillSize40 + 1 + 1 + 4 == kPacketSize, "Pandar40 GPS layout");
static_assert(2 + 6 + 6 + 4 + kNmeaSize64 + kFillSize64 + 1 + 1 + 4 == kPacketSize, "Pandar64 GPS layout");
static_assert(kFill40 + kFillSize40 == kStatus && kFill64 + kFillSize64 == kStatus, "filler ends at the status byte");
static_assert(kPpsLock == kStatus + 1 && kReserved == kPpsLock + 1 && kReserved + kReservedSize == kPacketSize);
}  // namespace gps_wire

/// A decoded GPS packet.
struct GpsPacket {
  GpsLayout layout = GpsLayout::pandar40;
  DateTime time;                  ///< UTC date-time from the packet's digit fields (full year, whole seconds)
  std::uint32_t us_time = 0;      ///< Pandar40 "us time" (us within the hour, < 3 600 000 000); 0 for Pandar64
  char nmea[85] = {};             ///< NMEA sentence up to 2 bytes after its first '*', NUL-terminated; "" if none
  std::uint8_t nmea_length = 0;   ///< characters in `nmea` (0..77 Pandar40, 0..84 Pandar64)
  char location_status = 0;       ///< 'A', 'V' or 0 as sent (Pandar64 with GPGGA: '0'..'9' too)
  bool pps_locked = false;        ///< PPS lock flag byte was 1
  bool nmea_checksum_ok = false;  ///< `nmea` starts with '$' and its XOR checksum matches the 2 hex digits after '*'
};
static_assert(sizeof(GpsPacket::nmea) == gps_wire::kNmeaSize64 + 1, "room for the longest NMEA field and its NUL");

/// Parses a GPS packet (UDP payload) of either layout; the layout is identified from the 0xDF
/// filler: bytes 102..505 must all be 0xDF (both layouts); bytes 95..101 all 0xDF means Pandar40,
/// anything else there is the tail of a Pandar64 NMEA field.
/// Errors: bad_length (size != 512), bad_magic (not FF EE, or the filler is not all 0xDF),
/// bad_gps_field (a date/time byte that is not an ASCII digit, a date-time that fails is_valid(),
/// a Pandar40 us time >= 3 600 000 000, a status byte other than 'A'/'V'/0 (Pandar64 also '0'..'9'),
/// a PPS byte other than 0/1). A missing or malformed NMEA sentence is not an error: it leaves
/// `nmea` empty and `nmea_checksum_ok` false. `out` is written only on success.
[[nodiscard]] Error parse_gps_packet(ByteView payload, GpsPacket& out) noexcept;

/// Cheap recognition: 512 bytes starting FF EE. A true result does not promise parse success.
bool is_gps_packet(ByteView payload) noexcept;

}  // namespace hesai
