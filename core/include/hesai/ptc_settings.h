// PTC settings: the payloads of the set commands, the settings as the configuration (0x08) reports
// them, the values each model allows, and the names of the configuration's coded fields.
//
// Sources:
// - Set payloads, big-endian (HesaiLidar_SDK_2.0 libhesai/PtcClient ptc_client.cc SetSpinSpeed,
//   SetSyncAngle, SetReturnMode, SetStandbyMode, SetDesIpandPort, SetAllChannelFov with
//   fov_model 0; tier4/nebula hesai_hw_interface.cpp set_spin_rate, set_sync_angle,
//   set_return_mode, set_standby_mode, set_destination_ip, set_lidar_range(start, end)):
//   0x17 rpm u16; 0x18 enable u8, angle u16 in whole degrees; 0x1E return-mode code u8; 0x1C
//   standby u8 (SDK: 0 in operation, 1 standby); 0x20 IPv4[4], point-cloud port u16, GPS port
//   u16; 0x22 method u8 (0: one range for all channels), start u16, end u16 in 0.1 degree (the
//   0x23 answer has the same three fields first, nebula HesaiLidarRangeAll).
// - Read back from the configuration (hesai/ptc.h Config): spin rate in rpm; sync u8 and sync
//   angle in 0.01 degree (nebula check_and_set_config divides it by 100 before it compares);
//   start and stop angle in 0.1 degree; return mode, standby mode as above.
// - Return-mode codes per model (nebula hesai_common.hpp return_mode_from_int_hesai): XT16, XT32,
//   XT32M2X, QT128C2X 0 last, 1 strongest, 2 last+strongest, 3 first, 4 last+first, 5
//   first+strongest; PandarQT64 0 last, 2 last+first, 3 first; Pandar64 and Pandar40P 0 last, 1
//   strongest, 2 last+strongest (the Pandar40 as the 40P: its manual lists the same three).
// - Spin rates: 600 and 1200 rpm (Pandar64 manual, chapter 4 Web Control "Spin Rate"; QT128C2X
//   manual, chapter 4; Pandar40 manual). No manual here for the PandarQT64 and XT models: the
//   rates nebula's HTTP spin-speed call knows (300, 600, 1200; set_spin_speed_async_http).
// - Spin rate over HTTP: nebula sets it over HTTP, not PTC, for the Pandar40P, Pandar64 and
//   PandarQT64 (and any model it does not list: use_http_set_spin_rate); over PTC for the QT128C2X
//   and the XT models.
// - FOV: nebula sets and reads the range of every model but the Pandar64 (and the AT128, not a
//   model here); no source says whether the Pandar40 has it, so it is refused there too.
// - Sync angle 0 to 359 degrees (Pandar64 manual, chapter 4 "Sync Angle").
// - Coded fields: clock source 0 GPS, 1 PTP (nebula g_hesai_lidar_gps_clock_source,
//   g_hesai_lidar_ptp_clock_source); standby 0 in operation, 1 standby (SDK SetStandbyMode);
//   trigger method, reflectivity mapping, motor status, UDP sequence and VLAN: no source gives
//   their codes, so the order of the manuals' Web Control lists is taken, default first (Pandar64
//   manual chapter 4: Time-Based (default), Angle-Based; Linear Mapping (default), Nonlinear
//   Mapping; QT128C2X manual 1.2: clockwise by default, counter-clockwise selectable), and 0 off,
//   1 on for the two flags.
//
// Contract: as hesai/ptc.h: reentrant, writes only its outputs, bounded reads, no allocation.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/error.h"
#include "hesai/model.h"
#include "hesai/ptc.h"

namespace hesai::ptc {

/// The settings 'hesai sensor set' and 'apply' write, in the order they are written.
enum class Setting : std::uint8_t { rpm, return_mode, standby, sync_angle, destination, fov };
inline constexpr std::size_t kSettingCount = 6;

/// "rpm", "return_mode", "standby", "sync_angle", "destination", "fov".
const char* setting_name(Setting setting) noexcept;
/// The setting named by the `size` bytes at `name`; false for any other name.
bool setting_from_name(const char* name, std::size_t size, Setting& out) noexcept;
/// The set command of a setting (0x17, 0x1E, 0x1C, 0x18, 0x20, 0x22).
Command set_command(Setting setting) noexcept;

/// Every setting's value, in the units the set commands carry.
struct Settings {
  std::uint16_t rpm = 0;
  std::uint8_t return_mode = 0;  ///< the model's PTC code
  std::uint8_t standby = 0;      ///< 0 in operation, 1 standby
  std::uint8_t sync = 0;         ///< 0 off, 1 on
  std::uint16_t sync_angle = 0;  ///< whole degrees
  std::uint8_t destination_ip[4]{};
  std::uint16_t destination_port = 0, gps_port = 0;
  std::uint16_t fov_start = 0, fov_end = 0;  ///< 0.1 degree
};

/// The settings a configuration reports (sync angle from 0.01 degree to whole degrees, rounded).
void settings_from_config(const Config& config, Settings& out) noexcept;
/// Whether `setting` is the same in both (a sync angle that is off equals any other that is off).
bool same_setting(Setting setting, const Settings& a, const Settings& b) noexcept;

inline constexpr std::size_t kMaxSetPayloadBytes = 8;
/// The payload of the set command of `setting` with its value in `value`: `size` bytes in `out`.
void encode_setting(Setting setting, const Settings& value, std::uint8_t out[kMaxSetPayloadBytes],
                    std::size_t& size) noexcept;
/// Reads a set command's payload (the stand-in's side): the setting it sets and its value in
/// `out` (other fields untouched). Error::ptc_command_mismatch for a command that sets none of
/// them, Error::ptc_payload_length for a payload of another size.
Error parse_setting(std::uint8_t command, ByteView payload, Setting& setting, Settings& out) noexcept;

// ---- What each model allows ----

inline constexpr std::size_t kMaxSpinRates = 3;
/// The spin rates `model` allows, ascending, in `rates`; their count.
std::size_t allowed_spin_rates(Model model, std::uint16_t rates[kMaxSpinRates]) noexcept;
/// Whether nebula sets the spin rate of `model` over the unit's HTTP API rather than PTC.
bool spin_rate_over_http(Model model) noexcept;
/// Whether `model` takes a FOV (0x22).
bool fov_supported(Model model) noexcept;
inline constexpr std::uint16_t kMaxSyncAngle = 359;
inline constexpr std::uint16_t kMaxFovTenths = 3600;

inline constexpr std::size_t kReturnModeNames = 6;
/// The return-mode name of a code on `model` ("last", "strongest", "last_strongest", "first",
/// "last_first", "first_strongest"); null for a code the model does not list. Model::unknown
/// takes the six codes of the XT and QT128 family.
const char* return_mode_name(Model model, std::uint8_t code) noexcept;
/// The code of a return-mode name on `model`; false when the model has no such mode.
bool return_mode_code(Model model, const char* name, std::size_t size, std::uint8_t& code) noexcept;

// ---- Names of the configuration's coded fields ("unknown" for a code not listed) ----

const char* clock_source_name(std::uint8_t code) noexcept;          ///< "GPS", "PTP"
const char* trigger_method_name(std::uint8_t code) noexcept;        ///< "time-based", "angle-based"
const char* standby_name(std::uint8_t code) noexcept;               ///< "in operation", "standby"
const char* motor_direction_name(std::uint8_t code) noexcept;       ///< "clockwise", "counter-clockwise"
const char* on_off_name(std::uint8_t code) noexcept;                ///< "off", "on" (UDP sequence, VLAN)
const char* reflectivity_mapping_name(std::uint8_t code) noexcept;  ///< "linear", "nonlinear"

// ---- FOV (0x23) ----

struct Fov {
  std::uint8_t method = 0;  ///< 0: one range for all channels
  std::uint16_t start = 0, end = 0;  ///< 0.1 degree (method 0)
};
/// Reads the first five bytes of a 0x23 answer (Error::ptc_payload_length when shorter).
Error parse_fov(ByteView payload, Fov& out) noexcept;

// ---- PTP diagnostics (0x06) ----

/// The query type of a PTP status request (nebula g_ptc_command_ptp_status), the payload of 0x06.
inline constexpr std::uint8_t kPtpQueryStatus = 0x01;
inline constexpr std::size_t kPtpDiagStatusBytes = 16;
/// nebula HesaiPtpDiagStatus: master offset i64 (as sent), PTP state i32, elapsed ms i32.
struct PtpDiagStatus {
  std::int64_t master_offset = 0;
  std::int32_t ptp_state = 0;  ///< as the status's PTP state: 0 free run .. 3 frozen
  std::int32_t elapsed_ms = 0;
};
/// Reads the answer to a PTP status query (Error::ptc_payload_length when shorter than 16 bytes).
Error parse_ptp_diag_status(ByteView payload, PtpDiagStatus& out) noexcept;

// ---- Time source ----

enum class TimeSource : std::uint8_t { free_run, ptp, gps };
/// "free_run", "ptp", "gps".
const char* time_source_name(TimeSource source) noexcept;
/// Where the unit's packet times come from (Pandar64 manual, Appendix B.1): with clock source PTP,
/// the PTP master while tracking or locked (free run and frozen count the internal 1 Hz signal
/// from a virtual or a last synchronised time: free_run); with clock source GPS, GPS when both the
/// PPS and the GPRMC/NMEA are locked, else free_run. Another clock source: free_run.
TimeSource time_source(std::uint8_t clock_source, const Status& status) noexcept;

}  // namespace hesai::ptc
