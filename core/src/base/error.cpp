#include "hesai/error.h"

namespace hesai {

const char* error_name(Error e) noexcept {
  switch (e) {
    case Error::ok: return "ok";
    case Error::truncated: return "truncated";
    case Error::bad_length: return "bad_length";
    case Error::bad_magic: return "bad_magic";
    case Error::unsupported_version: return "unsupported_version";
    case Error::unsupported_model: return "unsupported_model";
    case Error::unsupported_section: return "unsupported_section";
    case Error::flags_length_mismatch: return "flags_length_mismatch";
    case Error::bad_header: return "bad_header";
    case Error::bad_azimuth: return "bad_azimuth";
    case Error::bad_return_mode: return "bad_return_mode";
    case Error::bad_date_time: return "bad_date_time";
    case Error::bad_timestamp: return "bad_timestamp";
    case Error::bad_motor_speed: return "bad_motor_speed";
    case Error::dual_block_mismatch: return "dual_block_mismatch";
    case Error::crc_body: return "crc_body";
    case Error::crc_functional_safety: return "crc_functional_safety";
    case Error::crc_tail: return "crc_tail";
    case Error::signature_missing: return "signature_missing";
    case Error::signature_invalid: return "signature_invalid";
    case Error::model_mismatch: return "model_mismatch";
    case Error::invalid_argument: return "invalid_argument";
    case Error::bad_gps_field: return "bad_gps_field";
    case Error::calib_bad_header: return "calib_bad_header";
    case Error::calib_bad_row: return "calib_bad_row";
    case Error::calib_bad_number: return "calib_bad_number";
    case Error::calib_bad_channel: return "calib_bad_channel";
    case Error::calib_channel_count: return "calib_channel_count";
  }
  return "unknown";
}

}  // namespace hesai
