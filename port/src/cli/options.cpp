#include "options.h"

#include <cmath>
#include <cstdlib>

#include "hesai/hkdf.h"

namespace hesai::cli {

namespace {
// Key material gathered before the session key can be derived.
struct PendingSecret {
  std::string secret, lidar_random, client_random;
};
PendingSecret g_pending;
}  // namespace

const char* const kDecodeOptionsHelp =
    "  --calibration FILE      angle-correction CSV of the unit (default: the manual's design angles)\n"
    "  --firetimes FILE        firing-time CSV (default: the manual's firing times)\n"
    "  --channel-config FILE   QT128 channel-configuration CSV (checked; see README)\n"
    "  --no-firetime-azimuth   do not add firing time x spin rate to each point's azimuth\n"
    "  --packets FIRST:END     keep point-cloud packets FIRST <= index < END (0-based)\n"
    "  --cut-angle DEG         azimuth where a frame ends (default 0)\n"
    "  --fov START:END         keep points with START <= azimuth < END (degrees, may wrap)\n"
    "  --min-range M           keep points at M metres or more\n"
    "  --max-range M           keep points at M metres or less\n";
const char* const kKeyOptionsHelp =
    "  --session-key HEX64     QT128 signature key (32 bytes in hex)\n"
    "  --secret TEXT --lidar-random HEX64 --client-random HEX64\n"
    "                          derive the session key by HKDF-SHA256 as the sensor does\n"
    "  --allow-unsigned        with a key, accept packets that carry no signature\n";
const char* const kOutputOptionsHelp =
    "  --format csv|pcd|ply|png  output format (default csv)\n"
    "  --out PATH              output file ('-' = stdout for csv); a directory with --per-frame\n"
    "  --per-frame             one file per frame in --out: frame_000001.pcd, ...\n"
    "  --png-range M           PNG: metres from the sensor to the image edge (default 60)\n"
    "  --png-color intensity|height  PNG: what colours the points (default intensity)\n";

Args::Args(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i) args_.emplace_back(argv[i]);
}

bool Args::value(const std::string& option, std::string& out) {
  if (empty()) return false;
  out = take();
  (void)option;
  return true;
}

bool parse_u64(const std::string& s, std::uint64_t& out) {
  if (s.empty() || s[0] == '-') return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
  if (*end != '\0' || errno != 0) return false;
  out = v;
  return true;
}

bool parse_float(const std::string& s, float& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  const float v = std::strtof(s.c_str(), &end);
  if (*end != '\0' || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool parse_hex(const std::string& s, std::uint8_t* out, std::size_t n) {
  if (s.size() != 2 * n) return false;
  auto nibble = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const int hi = nibble(s[2 * i]), lo = nibble(s[2 * i + 1]);
    if (hi < 0 || lo < 0) return false;
    out[i] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  return true;
}

namespace {
bool split_pair(const std::string& s, std::string& a, std::string& b) {
  const std::size_t colon = s.find(':');
  if (colon == std::string::npos) return false;
  a = s.substr(0, colon);
  b = s.substr(colon + 1);
  return true;
}
}  // namespace

bool parse_decode_option(Args& args, DecodeOptions& o, std::string& error) {
  const std::string opt = args.peek();
  auto need = [&](std::string& v) {
    args.take();
    if (!args.value(opt, v)) {
      error = opt + " needs a value";
      return false;
    }
    return true;
  };
  std::string v;
  if (opt == "--calibration") return need(o.calibration_path) || true;
  if (opt == "--firetimes") return need(o.firetimes_path) || true;
  if (opt == "--channel-config") return need(o.channel_config_path) || true;
  if (opt == "--no-firetime-azimuth") {
    args.take();
    o.firetime_azimuth = false;
    return true;
  }
  if (opt == "--allow-unsigned") {
    args.take();
    o.allow_unsigned = true;
    return true;
  }
  if (opt == "--packets") {
    std::string a, b;
    if (need(v) && (!split_pair(v, a, b) || !parse_u64(a, o.first_packet) || !parse_u64(b, o.end_packet) ||
                    o.end_packet < o.first_packet))
      error = "--packets takes FIRST:END with FIRST <= END, got '" + v + "'";
    return true;
  }
  if (opt == "--cut-angle") {
    float deg = 0;
    if (need(v) && (!parse_float(v, deg) || o.frames.set_cut_deg(deg) != Error::ok))
      error = "--cut-angle takes degrees in [0, 360), got '" + v + "'";
    return true;
  }
  if (opt == "--fov") {
    std::string a, b;
    float start = 0, end = 0;
    if (need(v) && (!split_pair(v, a, b) || !parse_float(a, start) || !parse_float(b, end) ||
                    o.frames.set_fov_deg(start, end) != Error::ok))
      error = "--fov takes START:END in degrees (0..360, START != END), got '" + v + "'";
    return true;
  }
  if (opt == "--min-range" || opt == "--max-range") {
    float m = 0;
    if (need(v) && (!parse_float(v, m) || m < 0)) error = opt + " takes metres >= 0, got '" + v + "'";
    (opt == "--min-range" ? o.min_range : o.max_range) = m;
    return true;
  }
  if (opt == "--session-key") {
    if (need(v) && !parse_hex(v, o.session_key.data(), 32)) error = "--session-key takes 64 hex digits";
    o.has_key = true;
    return true;
  }
  if (opt == "--secret") return need(g_pending.secret) || true;
  if (opt == "--lidar-random") return need(g_pending.lidar_random) || true;
  if (opt == "--client-random") return need(g_pending.client_random) || true;
  return false;
}

bool finish_key_options(DecodeOptions& o, std::string& error) {
  const PendingSecret& p = g_pending;
  if (p.secret.empty() && p.lidar_random.empty() && p.client_random.empty()) return true;
  if (o.has_key) {
    error = "give either --session-key or --secret with --lidar-random and --client-random";
    return false;
  }
  std::uint8_t lidar[32], client[32];
  if (p.secret.empty() || !parse_hex(p.lidar_random, lidar, 32) || !parse_hex(p.client_random, client, 32)) {
    error = "--secret needs --lidar-random HEX64 and --client-random HEX64 (32 bytes each in hex)";
    return false;
  }
  const Error e = hesai_session_key(ByteView{reinterpret_cast<const std::uint8_t*>(p.secret.data()), p.secret.size()},
                                    lidar, client, o.session_key.data());
  if (e != Error::ok) {
    error = "--secret must be 8 to 32 characters";
    return false;
  }
  o.has_key = true;
  return true;
}

bool parse_output_option(Args& args, OutputOptions& o, std::string& error) {
  const std::string opt = args.peek();
  if (opt == "--per-frame") {
    args.take();
    o.per_frame = true;
    return true;
  }
  if (opt != "--format" && opt != "--out" && opt != "--png-range" && opt != "--png-color") return false;
  args.take();
  std::string v;
  if (!args.value(opt, v)) {
    error = opt + " needs a value";
    return true;
  }
  if (opt == "--out") {
    o.out = v;
  } else if (opt == "--png-range") {
    if (!parse_float(v, o.png_range_m) || o.png_range_m <= 0) error = "--png-range takes metres > 0, got '" + v + "'";
  } else if (opt == "--png-color") {
    if (v != "intensity" && v != "height") error = "--png-color takes intensity or height, got '" + v + "'";
    o.png_height = v == "height";
  } else if (v == "csv" || v == "pcd" || v == "ply" || v == "png") {
    o.format = v;
  } else {
    error = "--format takes csv, pcd, ply or png, got '" + v + "'";
  }
  return true;
}

}  // namespace hesai::cli
