// PTC 1.0 (Pandar TCP Commands, default TCP port 9347): the framing of requests and responses,
// and the response payloads whose layouts are published, parsed into fixed structs.
//
// Sources (the manuals here only name the commands; the layouts are the vendor's and nebula's):
// - Framing, requests and responses alike: 47 74, command, return code (0 in requests), payload
//   length u32 big-endian, then the payload; no CRC. Multi-byte payload fields are big-endian.
//   (HesaiLidar_SDK_2.0 libhesai/PtcParser PTCHeader_1_0; tier4/nebula hesai_hw_interface.cpp.)
// - Return codes 0..7 (nebula hesai_hw_interface.hpp g_ptc_error_code_*).
// - Inventory 0x07, configuration 0x08, status 0x09 (nebula hesai_cmd_response.hpp).
// - Signature session 0x2D/0x2E/0x2F: a 32-byte client random in, a 32-byte lidar random out;
//   the state is one byte (HesaiTechnology/Cyber_Security Point_Cloud_Signature
//   tcp_command_client.c). QT128C2X manual, 4.9.3 "Point Cloud Signature": the session key is
//   HKDF(shared secret, randoms, info), see hesai_session_key() in hkdf.h.
// - Calibration 0x05, firing times 0xA9, QT128 channel configuration 0xA8: the files as the unit
//   stores them, the same CSV text that calibration.h parses (SDK Lidar::LoadCorrectionForUdpParser
//   hands the 0x05 payload to the CSV parser).
//
// Contract: every function is reentrant, writes only its output, never reads past the view it is
// given and never allocates. A payload longer than a layout is accepted (later firmware appends
// fields); a shorter one is Error::ptc_payload_length.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/error.h"
#include "hesai/model.h"

namespace hesai::ptc {

inline constexpr std::uint16_t kDefaultPort = 9347;
inline constexpr std::size_t kHeaderBytes = 8;
inline constexpr std::uint8_t kMagic0 = 0x47;  ///< 'G'
inline constexpr std::uint8_t kMagic1 = 0x74;  ///< 't'

/// The commands this library sends (and its stand-in sensor answers).
enum class Command : std::uint8_t {
  calibration = 0x05,      ///< the angle-correction file
  ptp_diagnostics = 0x06,  ///< PTP diagnostics (a query-type byte in)
  inventory = 0x07,        ///< serial number, MAC, versions, model
  config = 0x08,           ///< network, spin rate, return mode...
  status = 0x09,           ///< uptime, motor speed, temperatures, GPS/PTP state
  reboot = 0x10,           ///< restart the unit (no payload)
  set_spin_rate = 0x17,    ///< u16 rpm (hesai/ptc_settings.h has the set payloads)
  set_sync_angle = 0x18,   ///< enable u8, angle u16 whole degrees
  set_standby = 0x1C,      ///< u8: 0 in operation, 1 standby
  set_return_mode = 0x1E,  ///< u8 return-mode code
  set_destination = 0x20,  ///< IPv4[4], point-cloud port u16, GPS port u16
  set_fov = 0x22,          ///< method u8 (0: all channels), start u16, end u16 (0.1 degree)
  get_fov = 0x23,          ///< the same three fields
  ptp_lock_offset = 0x3A,  ///< PTP lock offset
  signature_state = 0x2D,  ///< PTC_COMMAND_GET_DP_SIG_STATE: 1 byte, 0 off
  signature_start = 0x2E,  ///< PTC_COMMAND_DP_SIG_SESSION_START: client random in, lidar random out
  signature_stop = 0x2F,   ///< PTC_COMMAND_DP_SIG_SESSION_STOP
  channel_config = 0xA8,   ///< QT128 channel configuration file
  firetimes = 0xA9,        ///< the firing-time file
};

/// Lower-case name of a command ("inventory", "signature_start"); "unknown" for another byte.
const char* command_name(std::uint8_t command) noexcept;

/// A response's return code (0 in every request).
enum class ReturnCode : std::uint8_t {
  no_error = 0,
  invalid_parameter = 1,
  connection_failed = 2,
  invalid_data = 3,
  out_of_memory = 4,
  unsupported_command = 5,
  fpga_failed = 6,
  other = 7,
};

/// What a return code means: "no error", "invalid input parameter", "server connection failed",
/// "invalid data", "out of memory", "unsupported command", "FPGA communication failed", "other
/// error"; "unknown return code" above 7.
const char* return_code_name(std::uint8_t code) noexcept;

/// The most payload bytes a response to `command` may announce before a client reads it: 1 MiB
/// for the files (calibration, firing times, channel configuration), 4 KiB for the rest (their
/// layouts are under 200 bytes). A larger announcement is refused before anything is allocated.
std::uint32_t max_response_bytes(Command command) noexcept;
inline constexpr std::uint32_t kMaxFileBytes = 1u << 20;
inline constexpr std::uint32_t kMaxSmallResponseBytes = 4096;

/// The eight header bytes of a request or response.
struct Header {
  std::uint8_t command = 0;
  std::uint8_t return_code = 0;
  std::uint32_t length = 0;  ///< payload bytes that follow
};

/// Writes a header: 47 74, command, return code, length big-endian.
void encode_header(std::uint8_t command, std::uint8_t return_code, std::uint32_t length,
                   std::uint8_t out[kHeaderBytes]) noexcept;

/// Writes a request (header with return code 0, then `payload`) into `out`; `written` is its size.
/// Error::buffer_too_small (nothing written) when `out_size` < 8 + payload.size.
Error encode_request(Command command, ByteView payload, std::uint8_t* out, std::size_t out_size,
                     std::size_t& written) noexcept;

/// Reads a header's fields. Error::truncated for fewer than 8 bytes, Error::ptc_bad_magic when it
/// does not start with 47 74 (`out` untouched in both cases).
Error parse_header(ByteView bytes, Header& out) noexcept;

/// Checks a response header to a request of `expected`, in this order: magic
/// (Error::ptc_bad_magic), the echoed command (Error::ptc_command_mismatch), the announced length
/// against `max_length` (Error::ptc_length_exceeds_bound), the return code
/// (Error::ptc_sensor_error). `out` holds the header's fields whenever the magic matched, so that
/// a caller can name the echo, the length or the return code it refused. After ok and after
/// ptc_sensor_error the stream is in step (the payload of `out.length` bytes follows and may be
/// read); after the others it is not, and the connection should be closed.
Error check_response(ByteView header, Command expected, std::uint32_t max_length, Header& out) noexcept;

// ---- Inventory (0x07) ----

/// A PTC product-model number: 0 Pandar40P, 2 Pandar64, 15 PandarQT, 25 PandarXT32, 26 PandarXT16,
/// 32 QT128C2X, 38 PandarXT32M (nebula hesai_hw_interface.cpp nebula_model_to_hesai_model_no).
Model model_from_product_number(std::uint8_t number) noexcept;
/// The number of a model (the inverse of the above); 255 for a model without one (Pandar40).
std::uint8_t product_number(Model model) noexcept;

/// Inventory layout: the fields every model shares, then model-specific bytes. Offsets in bytes.
inline constexpr std::size_t kInvSerial = 0, kInvSerialBytes = 18;
inline constexpr std::size_t kInvDate = 18, kInvDateBytes = 16;
inline constexpr std::size_t kInvMac = 34, kInvMacBytes = 6;
inline constexpr std::size_t kInvSoftware = 40, kInvHardware = 56, kInvControlFirmware = 72, kInvSensorFirmware = 88;
inline constexpr std::size_t kInvVersionBytes = 16;
inline constexpr std::size_t kInvCommonBytes = 104;
/// XT16/XT32/Pandar40P and the default (nebula HesaiInventory_XT16_32_40P): zero-angle offset i16,
/// product model, motor type, lines, 11 reserved.
inline constexpr std::size_t kInvModel = 106, kInvMotor = 107, kInvLines = 108, kInvBytes = 120;
/// QT128C2X (nebula HesaiInventory_QT128): zero-angle offset i16, counter-clockwise offset i16,
/// product model, motor type, lines, part number[32], 1 reserved.
inline constexpr std::size_t kInvQt128Model = 108, kInvQt128Motor = 109, kInvQt128Lines = 110, kInvQt128Bytes = 144;
static_assert(kInvSensorFirmware + kInvVersionBytes == kInvCommonBytes);

struct Inventory {
  char serial[kInvSerialBytes + 1]{};  ///< each text field as sent, cut at its first NUL, NUL-ended
  char manufacture_date[kInvDateBytes + 1]{};
  std::uint8_t mac[kInvMacBytes]{};
  char software_version[kInvVersionBytes + 1]{};
  char hardware_version[kInvVersionBytes + 1]{};
  char control_firmware[kInvVersionBytes + 1]{};
  char sensor_firmware[kInvVersionBytes + 1]{};
  bool has_model = false;             ///< the model-specific bytes were present
  std::uint8_t product_model = 0;     ///< PTC product-model number
  Model model = Model::unknown;       ///< the model it names (unknown for a number not listed)
  std::uint8_t motor_type = 0;        ///< 0 unidirectional, 1 bidirectional
  std::uint8_t lines = 0;             ///< laser lines
  std::int16_t zero_angle_offset = 0;
};

/// Parses an inventory. The common 104 bytes are required (else Error::ptc_payload_length). The
/// model-specific bytes follow nebula's layouts: the QT128 one when the payload holds its 144
/// bytes with product model 32 and 128 lines where that layout puts them, otherwise the common
/// one when the payload holds its 120 bytes (has_model false when neither fits).
Error parse_inventory(ByteView payload, Inventory& out) noexcept;

// ---- Configuration (0x08) ----

/// nebula HesaiConfigBase + HesaiConfig_XT_40P_64_QT128 (Pandar40P, Pandar64, QT128, XT16, XT32).
inline constexpr std::size_t kConfigBaseBytes = 38, kConfigBytes = 47;

struct Config {
  std::uint8_t ip[4]{}, mask[4]{}, gateway[4]{}, destination_ip[4]{};
  std::uint16_t destination_port = 0, gps_port = 0;
  std::uint16_t spin_rate_rpm = 0;
  std::uint8_t sync = 0;
  std::uint16_t sync_angle = 0;   ///< as the unit reports it (nebula gives no unit)
  std::uint16_t start_angle = 0;  ///< FOV start, 0.1 degree
  std::uint16_t stop_angle = 0;   ///< FOV stop, 0.1 degree
  std::uint8_t clock_source = 0, udp_sequence = 0, trigger_method = 0, return_mode = 0;
  std::uint8_t standby_mode = 0, motor_status = 0, vlan_flag = 0;
  std::uint16_t vlan_id = 0;
  bool has_extra = false;  ///< the three bytes below were present
  std::uint8_t clock_data_format = 0, noise_filtering = 0, reflectivity_mapping = 0;
};

/// Parses a configuration: 38 bytes required (Error::ptc_payload_length), the three model bytes
/// after them read when present.
Error parse_config(ByteView payload, Config& out) noexcept;

// ---- Status (0x09) ----

inline constexpr std::size_t kMaxTemperatures = 9;
/// Temperatures in a model's status: 9 for the QT128C2X (nebula HesaiLidarStatusQT128), 8 for the
/// others and for an unknown model (nebula HesaiLidarStatus_XT_40p, SDK PtcClient::GetLidarStatus).
std::size_t status_temperature_count(Model model) noexcept;
/// Bytes a status of `temperatures` takes before its 5 reserved bytes: 17 + 4 x temperatures.
constexpr std::size_t status_bytes(std::size_t temperatures) { return 17 + 4 * temperatures; }

struct Status {
  std::uint32_t uptime_s = 0;
  std::uint16_t motor_speed_rpm = 0;
  std::uint8_t temperature_count = 0;
  std::int32_t temperature_centi_c[kMaxTemperatures]{};  ///< 0.01 degree C
  std::uint8_t gps_pps_lock = 0;      ///< 1 locked
  std::uint8_t gprmc_status = 0;      ///< 1 valid
  std::uint32_t startups = 0;
  std::uint32_t operating_time_min = 0;
  std::uint8_t ptp_status = 0;        ///< 0 free run, 1 tracking, 2 locked, 3 frozen
};

/// Parses a status with the temperature count of `model`: uptime u32 s, motor speed u16 rpm,
/// temperatures i32, PPS lock, GPRMC status, start-ups u32, operating time u32 min, PTP status.
/// Error::ptc_payload_length when shorter than status_bytes(count).
Error parse_status(ByteView payload, Model model, Status& out) noexcept;

/// "free run", "tracking", "locked", "frozen"; "unknown" above 3.
const char* ptp_status_name(std::uint8_t status) noexcept;

// ---- Signature session (0x2D, 0x2E, 0x2F) ----

inline constexpr std::size_t kRandomBytes = 32;

/// The lidar random of a session-start response: exactly 32 bytes (else Error::ptc_payload_length).
Error parse_session_start(ByteView payload, std::uint8_t lidar_random[kRandomBytes]) noexcept;
/// The state of a session-state response: exactly one byte, non-zero while signing is on.
Error parse_signature_state(ByteView payload, bool& on) noexcept;

}  // namespace hesai::ptc
