#include "options.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "hesai/ct.h"
#include "hesai_port/formats/pointcloud2.h"

namespace hesai::cli {

const char* const kDecodeOptionsHelp =
    "  --calibration FILE      angle-correction CSV of the unit (default: the manual's design angles)\n"
    "  --firetimes FILE        firing-time CSV (default: the manual's firing times)\n"
    "  --channel-config FILE   QT128 channel-configuration CSV: maps the units of packets with\n"
    "                          customised channels (header flags bit 6)\n"
    "  --reflectivity raw|nonlinear  intensity: the byte as sent (default), or the Pandar64's\n"
    "                          nonlinear mapping (manual Appendix D) as a percentage\n"
    "  --returns all|distinct  dual return: both returns as sent (default), or a second return\n"
    "                          that repeats its first (same distance and reflectivity) once\n"
    "  --no-firetime-azimuth   do not add firing time x spin rate to each point's azimuth\n"
    "  --rotation auto|cw|ccw  direction the sensor spins (default auto: detected per sensor from\n"
    "                          its block azimuths; clockwise until known, see docs/CLI.md)\n"
    "  --packets FIRST:END     keep point-cloud packets FIRST <= index < END (0-based)\n"
    "  --cut-angle DEG         azimuth where a frame ends (default 0)\n"
    "  --fov START:END         keep points with START <= azimuth < END (degrees, may wrap)\n"
    "  --min-range M           keep points at M metres or more\n"
    "  --max-range M           keep points at M metres or less\n";
const char* const kOutputOptionsHelp =
    "  --format csv|pcd|ply|png|mcap  output format (default csv); mcap: a ROS 2 bag of one\n"
    "                          sensor_msgs/PointCloud2 per frame (see docs/CLI.md)\n"
    "  --out PATH              output file ('-' = stdout for csv); a directory with --per-frame\n"
    "  --per-frame             one file per sensor and frame in --out:\n"
    "                          frame_<sensor>_000001.pcd, ...\n"
    "  --png-range M           PNG: metres from the sensor to the image edge (default 60)\n"
    "  --png-color intensity|height  PNG: what colours the points (default intensity)\n"
    "  --topic NAME            MCAP: topic of the point clouds, a ROS 2 name; {sensor} is each\n"
    "                          sensor's name token (default /hesai/{sensor}/points)\n"
    "  --frame-id ID           MCAP: header.frame_id of the point clouds (default hesai_{sensor})\n"
    "  --ros-distro NAME       MCAP: the ROS 2 distribution the bag names (default humble)\n";

Args::Args(int argc, char** argv, int first) : argv_(argv), first_(first) {
  for (int i = first; i < argc; ++i) args_.emplace_back(argv[i]);
}

bool Args::value(const std::string& option, std::string& out) {
  if (empty()) return false;
  out = take();
  (void)option;
  return true;
}

bool Args::secret_value(std::string& out) {
  if (empty()) return false;
  out.assign(args_[pos_]);
  wipe_secret(args_[pos_]);
  char* arg = argv_[static_cast<std::size_t>(first_) + pos_];
  secure_wipe(arg, std::strlen(arg));
  ++pos_;
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
  if (opt == "--reflectivity") {
    if (need(v)) {
      if (v == "raw") o.reflectivity = Reflectivity::raw;
      else if (v == "nonlinear") o.reflectivity = Reflectivity::nonlinear;
      else error = "--reflectivity takes raw or nonlinear, got '" + v + "'";
    }
    return true;
  }
  if (opt == "--returns") {
    if (need(v)) {
      if (v == "all") o.returns = Returns::all;
      else if (v == "distinct") o.returns = Returns::distinct;
      else error = "--returns takes all or distinct, got '" + v + "'";
    }
    return true;
  }
  if (opt == "--no-firetime-azimuth") {
    args.take();
    o.firetime_azimuth = false;
    return true;
  }
  if (opt == "--rotation") {
    if (need(v)) {
      if (v == "auto" || v == "cw" || v == "ccw") {
        o.detect_rotation = v == "auto";
        o.rotation = v == "ccw" ? Rotation::counterclockwise : Rotation::clockwise;
      } else {
        error = "--rotation takes auto, cw or ccw, got '" + v + "'";
      }
    }
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
  return parse_key_option(args, error);
}

const char* const kTlsOptionsHelp =
    "  --tls                   PTCS, PTC over TLS 1.3 (a unit set to TLS or mTLS); the unit's\n"
    "                          certificate must chain to --ca and name its serial (CN or\n"
    "                          serialNumber); its host name or address is not checked\n"
    "  --ca FILE               PEM: the CA certificate(s) the unit's certificate must chain to\n"
    "  --cert FILE --key FILE  PEM, mTLS: this client's certificate and key (the key file must be a\n"
    "                          regular file that group and others cannot access: mode 0600)\n"
    "  --expect-serial SN      the unit's certificate must name SN, checked before any command\n"
    "  --insecure              do not verify the unit's certificate (a warning; no --ca)\n";

bool parse_tls_option(Args& args, TlsOptions& o, std::string& error) {
  const std::string opt = args.peek();
  if (opt == "--tls" || opt == "--insecure") {
    args.take();
    if (opt == "--insecure") o.client.insecure = true;
    else o.tls = true;
    if (opt == "--tls" && !port::tls_available())
      error = "built without TLS: --tls needs a build with OpenSSL (libssl-dev, cmake -DHESAI_WITH_TLS=ON)";
    return true;
  }
  std::string* target = opt == "--ca"              ? &o.client.ca_file
                        : opt == "--cert"          ? &o.client.cert_file
                        : opt == "--key"           ? &o.client.key_file
                        : opt == "--expect-serial" ? &o.client.expect_serial
                                                   : nullptr;
  if (target == nullptr) return false;
  args.take();
  if (!args.value(opt, *target) || target->empty()) error = opt + " needs a value";
  return true;
}

int finish_tls_options(const TlsOptions& o, std::shared_ptr<port::TlsContext>& context, std::string& error) {
  context.reset();
  const port::TlsClientOptions& c = o.client;
  if (!o.tls) {
    if (c.insecure || !c.ca_file.empty() || !c.cert_file.empty() || !c.key_file.empty() || !c.expect_serial.empty()) {
      error = "--ca, --cert, --key, --expect-serial and --insecure go with --tls";
      return kExitUsage;
    }
    return kExitOk;
  }
  if (c.cert_file.empty() != c.key_file.empty()) {
    error = "--cert and --key go together (mTLS: the client's certificate and its key)";
    return kExitUsage;
  }
  if (c.insecure && !c.ca_file.empty()) {
    error = "--insecure verifies nothing: give --ca FILE or --insecure, not both";
    return kExitUsage;
  }
  if (!c.insecure && c.ca_file.empty()) {
    error = "--tls needs --ca FILE, the CA the unit's certificate chains to (or --insecure, which verifies nothing)";
    return kExitUsage;
  }
  if (c.insecure)
    std::fprintf(stderr, "hesai: warning: --insecure: the unit's certificate is not verified (neither its chain nor its "
                         "serial%s): anyone on the network path can pose as the unit\n",
                 c.expect_serial.empty() ? "" : ", but for --expect-serial");
  context = port::TlsContext::client(c, error);
  return context ? kExitOk : kExitInput;
}

bool parse_output_option(Args& args, OutputOptions& o, std::string& error) {
  const std::string opt = args.peek();
  if (opt == "--per-frame") {
    args.take();
    o.per_frame = true;
    return true;
  }
  if (opt != "--format" && opt != "--out" && opt != "--png-range" && opt != "--png-color" && opt != "--topic" &&
      opt != "--frame-id" && opt != "--ros-distro")
    return false;
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
  } else if (opt == "--topic") {
    // Checked with a sensor's token in place of {sensor}: what the bag will record.
    std::string why;
    if (port::ros2_topic(with_sensor(v, "ip_192_168_1_201"), why).empty())
      error = "--topic '" + v + "' is not a ROS 2 topic name: " + why;
    o.topic = v;
  } else if (opt == "--frame-id") {
    if (with_sensor(v, "ip_192_168_1_201").empty()) error = "--frame-id needs a name";
    o.frame_id = v;
  } else if (opt == "--ros-distro") {
    if (!port::ros2_token(v)) error = "--ros-distro takes a distribution's name (humble, jazzy, ...), got '" + v + "'";
    o.ros_distro = v;
  } else if (v == "csv" || v == "pcd" || v == "ply" || v == "png" || v == "mcap") {
    o.format = v;
  } else {
    error = "--format takes csv, pcd, ply, png or mcap, got '" + v + "'";
  }
  return true;
}

}  // namespace hesai::cli
