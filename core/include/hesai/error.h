// Error codes of the core: one code per distinct cause. (The port has its own: capture files are
// read by port/, see hesai_port/capture.h CaptureError.)
#pragma once

#include <cstdint>

namespace hesai {

/// Outcome of every fallible core operation. `ok` is zero; every other value names one cause.
/// Bad input is a normal outcome: callers count it, nothing asserts or throws.
enum class Error : std::uint8_t {
  ok = 0,

  // Byte reading.
  truncated,              ///< a read would pass the end of the input

  // Packet recognition.
  bad_length,             ///< the length fits no supported layout
  bad_magic,              ///< start bytes or block preamble are not the manual's
  unsupported_version,    ///< a Hesai header with a protocol version we do not implement
  unsupported_model,      ///< a Hesai header whose laser/block counts match no supported sensor
  unsupported_section,    ///< a section whose layout the manual does not give (QT128 IMU)
  flags_length_mismatch,  ///< header flags announce sections that do not add up to the length
  bad_header,             ///< a header field out of its documented range (distance unit 0, return count)

  // Field validation.
  bad_azimuth,            ///< block azimuth >= 360.00 degrees
  bad_return_mode,        ///< return-mode byte not listed in the manual
  bad_date_time,          ///< tail date-time outside the calendar
  bad_timestamp,          ///< microsecond field beyond its manual's range (999 999; QT128 1 000 000)
  bad_motor_speed,        ///< motor speed above 1500 rpm (the sensors spin at 600 or 1200)
  dual_block_mismatch,    ///< the two blocks of one dual-return firing disagree in azimuth

  // Integrity.
  crc_body,               ///< QT128 CRC1 (body) does not match
  crc_functional_safety,  ///< QT128 CRC2 (functional safety) does not match
  crc_tail,               ///< QT128 CRC3 (tail) does not match
  signature_missing,      ///< a key is configured but the packet carries no signature
  signature_invalid,      ///< the HMAC-SHA256 signature does not match

  // Decoder use.
  model_mismatch,         ///< the packet is of another model than the decoder's calibration
  invalid_argument,       ///< a parameter outside its documented range

  // GPS packets.
  bad_gps_field,          ///< a GPS date/time digit or status byte outside its range

  // Calibration files.
  calib_bad_header,       ///< the header row is not one the manuals give
  calib_bad_row,          ///< a row has the wrong number of fields
  calib_bad_number,       ///< a field is not a decimal number
  calib_bad_channel,      ///< a channel number outside 1..N, or repeated
  calib_channel_count,    ///< the file has another number of channels than the model
};

/// The last code, for loops over every code (keep it last when adding codes).
inline constexpr Error kLastError = Error::calib_channel_count;

/// Stable lower-case name of an error code, for logs and JSON ("crc_body").
const char* error_name(Error e) noexcept;

}  // namespace hesai
