// hesai: decode Hesai lidar captures and live streams.
//   hesai decode CAPTURE ...   points to CSV, PCD, PLY or PNG
//   hesai stats CAPTURE ...    integrity, loss and content counters
//   hesai listen ...           live UDP statistics (and frames with --out)
//   hesai replay CAPTURE ...   send a capture's payloads to HOST:PORT (--serve-ptc: a stand-in sensor)
//   hesai sensor COMMAND HOST  PTC: the unit's inventory, status, calibration, signature session
#include <unistd.h>

#include <atomic>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "hesai/ct.h"
#include "hesai/ptc.h"
#include "hesai_port/capture.h"
#include "hesai_port/udp.h"
#include "commands.h"
#include "options.h"
#include "pipeline.h"
#include "report.h"
#include "sensor.h"
#include "sinks.h"

namespace hesai::cli {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

int usage_error(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "hesai %s: %s\nRun 'hesai %s --help' for usage.\n", command.c_str(), message.c_str(), command.c_str());
  return kExitUsage;
}

bool open_capture(const std::string& path, port::CaptureFile& file) {
  if (file.open(path) == port::CaptureError::ok) return true;
  std::fprintf(stderr, "hesai: %s\n", file.message().c_str());
  return false;
}

namespace {

constexpr const char* kUsage =
    "usage: hesai <command> [options]\n"
    "\n"
    "commands:\n"
    "  decode CAPTURE   decode a pcap/pcapng capture or a PandarScan MCAP bag into points\n"
    "  stats CAPTURE    count packets, points, frames, integrity failures and losses\n"
    "  listen           receive packets live over UDP and report statistics\n"
    "  replay CAPTURE   send a capture's UDP payloads to HOST:PORT (and stand in for the sensor's PTC)\n"
    "  sensor COMMAND HOST  talk to a sensor over PTC: info, config, status, calibration,\n"
    "                   firetimes, channel-config, signature start|status|stop\n"
    "\n"
    "Run 'hesai <command> --help' for the options of a command.\n";

// Reports a failure with exit status `status`: a usage error with the hint to --help, any other
// with the message alone.
int fail(const std::string& command, int status, const std::string& message) {
  if (status == kExitUsage) return usage_error(command, message);
  std::fprintf(stderr, "hesai %s: %s\n", command.c_str(), message.c_str());
  return status;
}

// Feeds every datagram of an open capture to the pipeline. Returns an exit status.
// The sender of a captured datagram, for the per-sensor report: "192.168.1.201:10000",
// "[fe80::1]:10000", or "mcap channel N" (MCAP packets carry no address).
std::string source_text(const port::UdpDatagram& d) {
  char buf[64];
  if (d.ip_version == 4) {
    std::snprintf(buf, sizeof buf, "%u.%u.%u.%u:%u", d.src_addr[0], d.src_addr[1], d.src_addr[2], d.src_addr[3], d.src_port);
  } else if (d.ip_version == 6) {
    std::string a = "[";
    for (std::size_t i = 0; i < 16; i += 2) {
      std::snprintf(buf, sizeof buf, "%s%x", i ? ":" : "", (d.src_addr[i] << 8) | d.src_addr[i + 1]);
      a += buf;
    }
    return a + "]:" + std::to_string(d.src_port);
  } else {
    std::snprintf(buf, sizeof buf, "mcap channel %u", d.interface_id);
  }
  return buf;
}

int run_capture(port::CaptureFile& file, Pipeline& pipeline, bool quiet) {
  const bool progress = !quiet && isatty(STDERR_FILENO);
  const std::size_t total = file.bytes().size;
  port::UdpDatagram d;
  std::uint64_t n = 0;
  for (;;) {
    const port::CaptureStatus st = file.next(d);
    if (st == port::CaptureStatus::end) break;
    if (st == port::CaptureStatus::error) {
      std::fprintf(stderr, "hesai: %s\n", file.message().c_str());
      pipeline.finish();
      return kExitInput;
    }
    const std::uint64_t key = source_key(d);
    if (!pipeline.has_label(key)) pipeline.label_source(key, source_text(d));
    if (!pipeline.feed(d.payload, key)) {
      std::fprintf(stderr, "hesai: %s\n", pipeline.error().c_str());
      return kExitUsage;
    }
    if (progress && (++n & 0x3FFF) == 0)
      std::fprintf(stderr, "\r%5.1f%% %llu packets", 100.0 * static_cast<double>(d.file_offset) / static_cast<double>(total),
                   static_cast<unsigned long long>(n));
  }
  if (progress && n >= 0x4000) std::fprintf(stderr, "\r%60s\r", "");
  pipeline.finish();
  return kExitOk;
}

// ---- decode ----

int cmd_decode(Args& args) {
  DecodeOptions o;
  OutputOptions out;
  std::string capture, error;
  bool quiet = false;
  while (!args.empty()) {
    const std::string a = args.peek();
    if (a == "--help" || a == "-h") {
      std::printf("usage: hesai decode CAPTURE [options]\n\nDecodes every point of a capture (pcap, pcapng, or an MCAP bag of\n"
                  "pandar_msgs/msg/PandarScan, told apart by their first bytes).\n\n%s%s%s"
                  "  --quiet                 no progress line\n\n"
                  "CSV columns: frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns\n",
                  kDecodeOptionsHelp, kOutputOptionsHelp, kKeyOptionsHelp);
      return kExitOk;
    }
    if (parse_decode_option(args, o, error) || parse_output_option(args, out, error)) {
      if (!error.empty()) return usage_error("decode", error);
      continue;
    }
    args.take();
    if (a == "--quiet") quiet = true;
    else if (a.rfind("--", 0) == 0) return usage_error("decode", "unknown option " + a);
    else if (capture.empty()) capture = a;
    else return usage_error("decode", "one capture at a time ('" + a + "')");
  }
  if (capture.empty()) return usage_error("decode", "missing CAPTURE");
  if (const int st = finish_key_options(o, error); st != kExitOk) return fail("decode", st, error);

  // The input first: an unreadable capture leaves any existing output untouched.
  port::CaptureFile file;
  if (!open_capture(capture, file)) return kExitInput;
  OutputSink sink(out);
  Pipeline pipeline(o, &sink);
  wipe_key(o);
  if (const int rc = pipeline.load_files(error); rc != kExitOk) {
    std::fprintf(stderr, "hesai decode: %s\n", error.c_str());
    return rc;
  }
  if (const int st = sink.open(error); st != kExitOk) return fail("decode", st, error);
  const int rc = run_capture(file, pipeline, quiet);
  if (!sink.close(error)) {
    std::fprintf(stderr, "hesai decode: %s\n", error.c_str());
    return kExitInput;
  }
  if (!quiet && !(out.format == "csv" && (out.out.empty() || out.out == "-"))) {
    const Stats& s = pipeline.stats();
    std::fprintf(stderr, "%llu packets, %llu frames, %llu points written",
                 static_cast<unsigned long long>(s.packets), static_cast<unsigned long long>(s.frames),
                 static_cast<unsigned long long>(sink.points_written()));
    if (sink.files().size() == 1) std::fprintf(stderr, " to %s\n", sink.files()[0].c_str());
    else std::fprintf(stderr, " to %zu files in %s\n", sink.files().size(), out.out.c_str());
  }
  return rc;
}

// ---- stats ----

int cmd_stats(Args& args) {
  DecodeOptions o;
  std::string capture, error;
  bool json = false, quiet = false;
  while (!args.empty()) {
    const std::string a = args.peek();
    if (a == "--help" || a == "-h") {
      std::printf("usage: hesai stats CAPTURE [--json] [options]\n\n"
                  "Counts packets per model, points, frames, integrity failures, sequence losses and what the\n"
                  "sensors report about themselves (temperature, GPS lock, QT128 functional safety).\n\n"
                  "  --json                  one JSON object: packets, models, points, frames, crc_errors,\n"
                  "                          signature_valid, signature_invalid, signature_missing,\n"
                  "                          signature_unverified, malformed, unsupported, lost, duplicates,\n"
                  "                          reordered, sequence_resyncs, lost_by, time_stalls,\n"
                  "                          time_virtual, time_jumps, blockage_units,\n"
                  "                          blockage_by_channel, duplicate_returns, beyond_rated_range,\n"
                  "                          fov_gap_deg, ip_fragments, gps_packets, first_time_ns,\n"
                  "                          last_time_ns, high_temperature, gps_unlocked,\n"
                  "                          gps_position_invalid, fs_packets, fs_states (per lidar state),\n"
                  "                          fs_current_fault, fs_past_fault, fs_reserved_fault_type,\n"
                  "                          fs_last_fault_code, fs_last_fault_id, fs_last_fault_total,\n"
                  "                          fs_counter_stalls\n"
                  "  --quiet                 no progress line\n%s%s",
                  kDecodeOptionsHelp, kKeyOptionsHelp);
      return kExitOk;
    }
    if (parse_decode_option(args, o, error)) {
      if (!error.empty()) return usage_error("stats", error);
      continue;
    }
    args.take();
    if (a == "--json") json = true;
    else if (a == "--quiet") quiet = true;
    else if (a.rfind("--", 0) == 0) return usage_error("stats", "unknown option " + a);
    else if (capture.empty()) capture = a;
    else return usage_error("stats", "one capture at a time ('" + a + "')");
  }
  if (capture.empty()) return usage_error("stats", "missing CAPTURE");
  if (const int st = finish_key_options(o, error); st != kExitOk) return fail("stats", st, error);
  // An unreadable capture gets its error alone; one damaged part-way, the counts up to the damage.
  port::CaptureFile file;
  if (!open_capture(capture, file)) return kExitInput;
  Pipeline pipeline(o, nullptr);
  wipe_key(o);
  if (const int rc = pipeline.load_files(error); rc != kExitOk) {
    std::fprintf(stderr, "hesai stats: %s\n", error.c_str());
    return rc;
  }
  const int rc = run_capture(file, pipeline, quiet);
  if (rc == kExitUsage) return rc;
  pipeline.set_ip_fragments(file.stats().fragments);
  if (json) std::printf("%s\n", stats_json(pipeline.stats(), pipeline.sensors()).c_str());
  else std::printf("%s\n%s", capture.c_str(), stats_text(pipeline).c_str());
  return rc;
}

// ---- listen ----

// The kernel's drop count for the socket, or "unavailable" on the portable receive path.
std::string kernel_drops(const port::UdpReceiver& rx) {
  return port::UdpReceiver::kernel_drops_known() ? std::to_string(rx.kernel_drops()) : "unavailable";
}

// The receive buffer the kernel granted (unless quiet), and always a warning when it is smaller
// than requested: net.core.rmem_max caps SO_RCVBUF, and a small buffer is the usual cause of drops.
void report_receive_buffer(const port::UdpReceiver& rx, std::size_t requested, bool quiet) {
  const std::size_t granted = rx.rcvbuf_granted();
  if (!quiet) {
    std::fprintf(stderr, "receive buffer %zu bytes (requested %zu", granted, requested);
    if (port::UdpReceiver::kRcvbufReportFactor != 1)
      std::fprintf(stderr, "; the kernel reports %zu, %zu times the usable size given here",
                   granted * port::UdpReceiver::kRcvbufReportFactor, port::UdpReceiver::kRcvbufReportFactor);
    std::fprintf(stderr, ")\n");
  }
  if (granted < requested)
    std::fprintf(stderr, "hesai listen: warning: the kernel capped the receive buffer at %zu bytes (requested %zu) "
                         "by net.core.rmem_max; to allow it, run: sysctl -w net.core.rmem_max=%zu\n",
                 granted, requested, requested);
}

int cmd_listen(Args& args) {
  DecodeOptions o;
  OutputOptions out;
  out.format = "pcd";
  std::string bind_addr = "0.0.0.0", error;
  port::UdpReceiveOptions receive;
  std::uint64_t port = 2368, gps_port = 10110, count = 0, ptc_port = ptc::kDefaultPort;
  std::string sensor_host;
  float seconds = 0, idle = 0, ptc_timeout = 3;
  bool json = false, quiet = false;
  while (!args.empty()) {
    const std::string a = args.peek();
    if (a == "--help" || a == "-h") {
      std::printf("usage: hesai listen [options]\n\nReceives sensor packets over UDP (with %s), prints statistics once a\n"
                  "second (on stderr) and a summary at the end (Ctrl-C, --count, --seconds or --idle).\n\n"
                  "  --bind ADDR             local IPv4 address (default 0.0.0.0); with --multicast, the\n"
                  "                          interface that joins the group\n"
                  "  --multicast GROUP       join the IPv4 multicast group GROUP (224.0.0.0/4) and receive\n"
                  "                          what is sent to it on the ports\n"
                  "  --rcvbuf BYTES          receive buffer to ask the kernel for (default 16777216); the\n"
                  "                          size granted is printed, and a cap by net.core.rmem_max named\n"
                  "  --port N                point-cloud port (default 2368)\n"
                  "  --gps-port N            GPS port (default 10110; 0: none)\n"
                  "  --count N               stop after N packets\n"
                  "  --seconds S             stop after S seconds\n"
                  "  --idle S                stop when no packet came for S seconds (after the first)\n"
                  "  --sensor HOST           the sensor's address: its calibration, firing times and QT128\n"
                  "                          channel configuration are fetched over PTC (a --calibration,\n"
                  "                          --firetimes or --channel-config file wins), a signature session\n"
                  "                          is started with --secret-file FILE or HESAI_SECRET (every packet\n"
                  "                          then verified, the session stopped at the end), and datagrams\n"
                  "                          from any other address are dropped and counted (foreign_packets)\n"
                  "  --ptc-port N            the sensor's PTC port (default 9347)\n"
                  "  --timeout S             PTC connect and per-request timeout (default 3)\n"
                  "  --json                  the summary as one JSON object (keys as in 'hesai stats --json',\n"
                  "                          and foreign_packets)\n"
                  "  --quiet                 no statistics once a second\n%s%s%s",
                  port::UdpReceiver::method(), kDecodeOptionsHelp, kOutputOptionsHelp, kKeyOptionsHelp);
      return kExitOk;
    }
    if (parse_decode_option(args, o, error) || parse_output_option(args, out, error)) {
      if (!error.empty()) return usage_error("listen", error);
      continue;
    }
    args.take();
    std::string v;
    if (a == "--json") json = true;
    else if (a == "--quiet") quiet = true;
    else if (a == "--sensor") { if (!args.value(a, sensor_host)) return usage_error("listen", "--sensor needs a host"); }
    else if (a == "--ptc-port") {
      if (!args.value(a, v) || !parse_u64(v, ptc_port) || ptc_port == 0 || ptc_port > 65535)
        return usage_error("listen", "--ptc-port takes 1 to 65535");
    } else if (a == "--timeout") {
      if (!args.value(a, v) || !parse_float(v, ptc_timeout) || !(ptc_timeout > 0) || ptc_timeout > 3600)
        return usage_error("listen", "--timeout takes seconds above 0 (at most 3600)");
    }
    else if (a == "--bind") { if (!args.value(a, bind_addr)) return usage_error("listen", "--bind needs an address"); }
    else if (a == "--multicast") {
      if (!args.value(a, receive.multicast_group) || !port::is_ipv4_multicast(receive.multicast_group))
        return usage_error("listen", "--multicast takes an IPv4 multicast group (224.0.0.0 to 239.255.255.255), got '" +
                                         receive.multicast_group + "'");
    } else if (a == "--rcvbuf") {
      std::uint64_t n = 0;
      if (!args.value(a, v) || !parse_u64(v, n) || n == 0 || n > INT_MAX)
        return usage_error("listen", "--rcvbuf takes bytes from 1 to " + std::to_string(INT_MAX) + ", got '" + v + "'");
      receive.rcvbuf_request = static_cast<std::size_t>(n);
    }
    else if (a == "--port" || a == "--gps-port" || a == "--count") {
      std::uint64_t n = 0;
      if (!args.value(a, v) || !parse_u64(v, n) || (a != "--count" && n > 65535))
        return usage_error("listen", a + " needs a number");
      (a == "--port" ? port : a == "--gps-port" ? gps_port : count) = n;
    } else if (a == "--seconds" || a == "--idle") {
      float& target = a == "--seconds" ? seconds : idle;
      if (!args.value(a, v) || !parse_float(v, target) || target <= 0) return usage_error("listen", a + " needs a positive number");
    } else return usage_error("listen", "unknown option " + a);
  }
  o.session_secret_allowed = !sensor_host.empty();  // the session's randoms come from the sensor
  if (const int st = finish_key_options(o, error); st != kExitOk) return fail("listen", st, error);
  std::uint32_t sensor_address = 0;
  if (!sensor_host.empty() && !port::resolve_ipv4(sensor_host, sensor_address, error)) return fail("listen", kExitInput, error);
  std::string session_secret;
  session_secret.swap(o.session_secret);  // the pipeline gets no copy

  std::unique_ptr<OutputSink> sink;
  if (!out.out.empty()) {
    sink = std::make_unique<OutputSink>(out);
    if (const int st = sink->open(error); st != kExitOk) return fail("listen", st, error);
  }
  Pipeline pipeline(o, sink.get());
  wipe_key(o);
  if (const int rc = pipeline.load_files(error); rc != kExitOk) {
    std::fprintf(stderr, "hesai listen: %s\n", error.c_str());
    return rc;
  }
  port::UdpReceiver points_rx, gps_rx;
  if (!points_rx.open(bind_addr, static_cast<std::uint16_t>(port), receive, error) ||
      (gps_port != 0 && gps_port != port && !gps_rx.open(bind_addr, static_cast<std::uint16_t>(gps_port), receive, error))) {
    std::fprintf(stderr, "hesai listen: %s\n", error.c_str());
    return kExitInput;
  }
  report_receive_buffer(points_rx, receive.rcvbuf_request, quiet);
  // The sockets are bound: what the sensor sends from now on waits for us while PTC runs.
  std::unique_ptr<SensorLink> link;
  if (!sensor_host.empty()) {
    link = std::make_unique<SensorLink>(sensor_host, static_cast<std::uint16_t>(ptc_port), static_cast<int>(ptc_timeout * 1000));
    int rc = link->fetch(o, pipeline, error);
    if (rc == kExitOk && !session_secret.empty()) rc = link->start_session(session_secret, pipeline, error);
    secure_wipe(session_secret.data(), session_secret.size());
    if (rc != kExitOk) {
      std::fprintf(stderr, "hesai listen: %s\n", error.c_str());
      return rc;
    }
  }
  std::uint64_t foreign = 0;
  if (!quiet && receive.multicast_group.empty())
    std::fprintf(stderr, "listening on %s:%u (GPS %u)\n", bind_addr.c_str(), points_rx.port(), static_cast<unsigned>(gps_port));
  else if (!quiet)
    std::fprintf(stderr, "listening on group %s:%u (GPS %u), joined on %s\n", receive.multicast_group.c_str(),
                 points_rx.port(), static_cast<unsigned>(gps_port), bind_addr.c_str());
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const std::int64_t start = port::monotonic_ns();
  const std::int64_t deadline = seconds > 0 ? start + static_cast<std::int64_t>(seconds * 1e9) : INT64_MAX;
  std::int64_t next_report = start + 1000000000;
  std::vector<port::Datagram> batch;
  const std::int64_t idle_ns = static_cast<std::int64_t>(idle * 1e9);
  std::int64_t now = start;
  std::int64_t last_packet = 0;  // monotonic time of the last datagram; 0 before the first
  std::uint64_t received = 0;
  bool fatal = false;
  while (!g_stop && !fatal && (count == 0 || received < count) && now < deadline &&
         !(idle_ns > 0 && last_packet != 0 && now - last_packet > idle_ns)) {
    bool arrived = false;
    for (port::UdpReceiver* rx : {&points_rx, &gps_rx}) {
      if (rx->fd() < 0) continue;
      if (rx->receive(batch, rx == &points_rx ? 50 : 0) < 0) fatal = true;
      arrived = arrived || !batch.empty();
      for (const port::Datagram& d : batch) {
        if (count != 0 && received >= count) break;
        if (link && d.source_ipv4 != sensor_address) {
          ++foreign;  // not the sensor's address: no point of it is decoded
          continue;
        }
        ++received;
        if (!pipeline.feed(ByteView{d.data, d.size}, rx == &gps_rx ? 1 : 0)) {
          std::fprintf(stderr, "hesai listen: %s\n", pipeline.error().c_str());
          return kExitUsage;
        }
      }
    }
    now = port::monotonic_ns();
    if (arrived) last_packet = now;
    if (!quiet && now >= next_report) {
      const Stats& s = pipeline.stats();
      std::fprintf(stderr, "%6.1f s  packets %llu  points %llu  frames %llu  lost %llu  crc %llu  kernel drops %s\n",
                   static_cast<double>(now - start) / 1e9, static_cast<unsigned long long>(s.packets),
                   static_cast<unsigned long long>(s.points), static_cast<unsigned long long>(s.frames),
                   static_cast<unsigned long long>(s.lost), static_cast<unsigned long long>(s.crc_errors),
                   kernel_drops(points_rx).c_str());
      next_report += 1000000000;
    }
  }
  pipeline.finish();
  if (link) link->stop_session();
  if (sink && !sink->close(error)) std::fprintf(stderr, "hesai listen: %s\n", error.c_str());
  if (json) {
    std::string j = stats_json(pipeline.stats(), pipeline.sensors());
    j.insert(j.size() - 1, ",\"foreign_packets\":" + std::to_string(foreign));
    std::printf("%s\n", j.c_str());
  } else {
    std::printf("%s  kernel_drops          %s\n  foreign_packets       %llu\n", stats_text(pipeline).c_str(),
                kernel_drops(points_rx).c_str(), static_cast<unsigned long long>(foreign));
  }
  return fatal ? kExitInput : kExitOk;
}

}  // namespace
}  // namespace hesai::cli

int main(int argc, char** argv) {
  using namespace hesai::cli;
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? kExitUsage : kExitOk;
  }
  const std::string command = argv[1];
  Args args(argc, argv, 2);
  if (command == "decode") return cmd_decode(args);
  if (command == "stats") return cmd_stats(args);
  if (command == "listen") return cmd_listen(args);
  if (command == "replay") return cmd_replay(args);
  if (command == "sensor") return cmd_sensor(args);
  std::fprintf(stderr, "hesai: unknown command '%s'\n\n%s", command.c_str(), kUsage);
  return kExitUsage;
}
