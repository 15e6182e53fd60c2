// PTC 1.0 framing and payload parsers (hesai/ptc.h has the sources of every layout).
#include "hesai/ptc.h"

#include "model_facts.h"

namespace hesai::ptc {
namespace {

// Copies a fixed-size text field, cut at its first NUL, into a NUL-ended array of n + 1.
void copy_text(const std::uint8_t* field, std::size_t n, char* out) noexcept {
  std::size_t i = 0;
  for (; i < n && field[i] != 0; ++i) out[i] = static_cast<char>(field[i]);
  for (std::size_t j = i; j <= n; ++j) out[j] = '\0';
}

std::int16_t load_be_i16(const std::uint8_t* p) { return static_cast<std::int16_t>(load_be16(p)); }
std::int32_t load_be_i32(const std::uint8_t* p) { return static_cast<std::int32_t>(load_be32(p)); }

}  // namespace

const char* command_name(std::uint8_t command) noexcept {
  switch (static_cast<Command>(command)) {
    case Command::calibration: return "calibration";
    case Command::inventory: return "inventory";
    case Command::config: return "config";
    case Command::status: return "status";
    case Command::ptp_diagnostics: return "ptp_diagnostics";
    case Command::reboot: return "reboot";
    case Command::set_spin_rate: return "set_spin_rate";
    case Command::set_sync_angle: return "set_sync_angle";
    case Command::set_standby: return "set_standby";
    case Command::set_return_mode: return "set_return_mode";
    case Command::set_destination: return "set_destination";
    case Command::set_fov: return "set_fov";
    case Command::get_fov: return "get_fov";
    case Command::ptp_lock_offset: return "ptp_lock_offset";
    case Command::signature_state: return "signature_state";
    case Command::signature_start: return "signature_start";
    case Command::signature_stop: return "signature_stop";
    case Command::channel_config: return "channel_config";
    case Command::firetimes: return "firetimes";
  }
  return "unknown";
}

const char* return_code_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {
      "no error",     "invalid input parameter", "server connection failed", "invalid data",
      "out of memory", "unsupported command",    "FPGA communication failed", "other error"};
  return code < sizeof kNames / sizeof kNames[0] ? kNames[code] : "unknown return code";
}

std::uint32_t max_response_bytes(Command command) noexcept {
  switch (command) {
    case Command::calibration:
    case Command::firetimes:
    case Command::channel_config: return kMaxFileBytes;
    default: return kMaxSmallResponseBytes;
  }
}

void encode_header(std::uint8_t command, std::uint8_t return_code, std::uint32_t length,
                   std::uint8_t out[kHeaderBytes]) noexcept {
  out[0] = kMagic0;
  out[1] = kMagic1;
  out[2] = command;
  out[3] = return_code;
  out[4] = static_cast<std::uint8_t>(length >> 24);
  out[5] = static_cast<std::uint8_t>(length >> 16);
  out[6] = static_cast<std::uint8_t>(length >> 8);
  out[7] = static_cast<std::uint8_t>(length);
}

Error encode_request(Command command, ByteView payload, std::uint8_t* out, std::size_t out_size,
                     std::size_t& written) noexcept {
  if (out_size < kHeaderBytes || payload.size > out_size - kHeaderBytes || payload.size > UINT32_MAX)
    return Error::buffer_too_small;
  encode_header(static_cast<std::uint8_t>(command), 0, static_cast<std::uint32_t>(payload.size), out);
  for (std::size_t i = 0; i < payload.size; ++i) out[kHeaderBytes + i] = payload.data[i];
  written = kHeaderBytes + payload.size;
  return Error::ok;
}

Error parse_header(ByteView bytes, Header& out) noexcept {
  if (bytes.size < kHeaderBytes) return Error::truncated;
  if (bytes[0] != kMagic0 || bytes[1] != kMagic1) return Error::ptc_bad_magic;
  out.command = bytes[2];
  out.return_code = bytes[3];
  out.length = load_be32(bytes.data + 4);
  return Error::ok;
}

Error check_response(ByteView header, Command expected, std::uint32_t max_length, Header& out) noexcept {
  if (const Error e = parse_header(header, out); e != Error::ok) return e;
  if (out.command != static_cast<std::uint8_t>(expected)) return Error::ptc_command_mismatch;
  if (out.length > max_length) return Error::ptc_length_exceeds_bound;
  if (out.return_code != 0) return Error::ptc_sensor_error;
  return Error::ok;
}

// ---- Inventory ----

Model model_from_product_number(std::uint8_t number) noexcept {
  for (std::size_t i = 1; i < kModelCount && number != 255; ++i)
    if (product_number(static_cast<Model>(i)) == number) return static_cast<Model>(i);
  return Model::unknown;
}

std::uint8_t product_number(Model model) noexcept { return model_facts::of(model).ptc_product; }

Error parse_inventory(ByteView payload, Inventory& out) noexcept {
  if (payload.size < kInvCommonBytes) return Error::ptc_payload_length;
  const std::uint8_t* p = payload.data;
  Inventory inv;
  copy_text(p + kInvSerial, kInvSerialBytes, inv.serial);
  copy_text(p + kInvDate, kInvDateBytes, inv.manufacture_date);
  for (std::size_t i = 0; i < kInvMacBytes; ++i) inv.mac[i] = p[kInvMac + i];
  copy_text(p + kInvSoftware, kInvVersionBytes, inv.software_version);
  copy_text(p + kInvHardware, kInvVersionBytes, inv.hardware_version);
  copy_text(p + kInvControlFirmware, kInvVersionBytes, inv.control_firmware);
  copy_text(p + kInvSensorFirmware, kInvVersionBytes, inv.sensor_firmware);
  const bool qt128 = payload.size >= kInvQt128Bytes && p[kInvQt128Model] == product_number(Model::qt128c2x) &&
                     p[kInvQt128Lines] == channel_count(Model::qt128c2x);
  if (qt128 || payload.size >= kInvBytes) inv.zero_angle_offset = load_be_i16(p + kInvCommonBytes);  // both layouts start with it
  if (qt128) {
    inv.has_model = true;
    inv.product_model = p[kInvQt128Model];
    inv.motor_type = p[kInvQt128Motor];
    inv.lines = p[kInvQt128Lines];
  } else if (payload.size >= kInvBytes) {
    inv.has_model = true;
    inv.product_model = p[kInvModel];
    inv.motor_type = p[kInvMotor];
    inv.lines = p[kInvLines];
  }
  inv.model = inv.has_model ? model_from_product_number(inv.product_model) : Model::unknown;
  out = inv;
  return Error::ok;
}

// ---- Configuration ----

Error parse_config(ByteView payload, Config& out) noexcept {
  if (payload.size < kConfigBaseBytes) return Error::ptc_payload_length;
  const std::uint8_t* p = payload.data;
  Config c;
  for (std::size_t i = 0; i < 4; ++i) {
    c.ip[i] = p[i];
    c.mask[i] = p[4 + i];
    c.gateway[i] = p[8 + i];
    c.destination_ip[i] = p[12 + i];
  }
  c.destination_port = load_be16(p + 16);
  c.gps_port = load_be16(p + 18);
  c.spin_rate_rpm = load_be16(p + 20);
  c.sync = p[22];
  c.sync_angle = load_be16(p + 23);
  c.start_angle = load_be16(p + 25);
  c.stop_angle = load_be16(p + 27);
  c.clock_source = p[29];
  c.udp_sequence = p[30];
  c.trigger_method = p[31];
  c.return_mode = p[32];
  c.standby_mode = p[33];
  c.motor_status = p[34];
  c.vlan_flag = p[35];
  c.vlan_id = load_be16(p + 36);
  static_assert(36 + 2 == kConfigBaseBytes);
  if (payload.size >= kConfigBaseBytes + 3) {
    c.has_extra = true;
    c.clock_data_format = p[38];
    c.noise_filtering = p[39];
    c.reflectivity_mapping = p[40];
  }
  out = c;
  return Error::ok;
}

// ---- Status ----

std::size_t status_temperature_count(Model model) noexcept { return detail::facts(model).temperatures; }

Error parse_status(ByteView payload, Model model, Status& out) noexcept {
  const std::size_t temperatures = status_temperature_count(model);
  if (payload.size < status_bytes(temperatures)) return Error::ptc_payload_length;
  const std::uint8_t* p = payload.data;
  Status s;
  s.uptime_s = load_be32(p);
  s.motor_speed_rpm = load_be16(p + 4);
  s.temperature_count = static_cast<std::uint8_t>(temperatures);
  for (std::size_t i = 0; i < temperatures; ++i) s.temperature_centi_c[i] = load_be_i32(p + 6 + 4 * i);
  const std::uint8_t* q = p + 6 + 4 * temperatures;
  s.gps_pps_lock = q[0];
  s.gprmc_status = q[1];
  s.startups = load_be32(q + 2);
  s.operating_time_min = load_be32(q + 6);
  s.ptp_status = q[10];
  static_assert(status_bytes(8) == 6 + 4 * 8 + 11);
  out = s;
  return Error::ok;
}

const char* ptp_status_name(std::uint8_t status) noexcept {
  static constexpr const char* kNames[] = {"free run", "tracking", "locked", "frozen"};
  return status < 4 ? kNames[status] : "unknown";
}

// ---- Signature session ----

Error parse_session_start(ByteView payload, std::uint8_t lidar_random[kRandomBytes]) noexcept {
  if (payload.size != kRandomBytes) return Error::ptc_payload_length;
  for (std::size_t i = 0; i < kRandomBytes; ++i) lidar_random[i] = payload.data[i];
  return Error::ok;
}

Error parse_signature_state(ByteView payload, bool& on) noexcept {
  if (payload.size != 1) return Error::ptc_payload_length;
  on = payload.data[0] != 0;
  return Error::ok;
}

}  // namespace hesai::ptc
