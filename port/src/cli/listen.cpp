// hesai listen: live UDP through the engine, with the sensor's files and signature session over PTC.
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "hesai/ct.h"
#include "hesai/ptc.h"
#include "hesai_port/base/clock.h"
#include "hesai_port/net/udp.h"
#include "hesai_port/pipeline/pipeline.h"
#include "hesai_port/pipeline/report.h"
#include "hesai_port/pipeline/sinks.h"
#include "commands.h"
#include "live_session.h"
#include "sensor.h"

namespace hesai::cli {

namespace {

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

std::int64_t to_ns(float seconds) { return static_cast<std::int64_t>(static_cast<double>(seconds) * 1e9); }

// listen --sensor with a secret: a live signature session where the unit signs. A secret asks for
// verified packets, so a unit that signs none (or whose model we do not know) is refused, unless
// --allow-unsigned says to run unverified. Exit status, with a message.
int start_live_session(SensorLink& link, const std::string& secret, bool allow_unsigned, SessionWatchOptions watch,
                       Pipeline& pipeline, std::unique_ptr<LiveSession>& session, std::string& error) {
  if (link.model() != Model::qt128c2x) {
    const std::string what = link.model() == Model::unknown
                                 ? "the unit's inventory names no model we know"
                                 : std::string("the ") + model_name(link.model()) + " signs no packets";
    if (!allow_unsigned) {
      error = "a secret was given, but " + what + ": no packet could be verified (--allow-unsigned runs unverified)";
      return kExitInput;
    }
    std::fprintf(stderr, "signature: %s; no session started (--allow-unsigned)\n", what.c_str());
    return kExitOk;
  }
  session = std::make_unique<LiveSession>(link.client(), secret, pipeline, watch);
  return session->start(error);
}

}  // namespace

int cmd_listen(Args& args) {
  DecodeOptions o;
  OutputOptions out;
  out.format = "pcd";
  std::string bind_addr = "0.0.0.0", error;
  port::UdpReceiveOptions receive;
  std::uint64_t port = 2368, gps_port = 10110, count = 0, ptc_port = ptc::kDefaultPort;
  std::string sensor_host;
  float seconds = 0, idle = 0, ptc_timeout = 3, session_poll = 1, signature_grace = 1;
  bool json = false, quiet = false, require_sync = false;
  TlsOptions tls;
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
                  "                          is started with --secret-file FILE or HESAI_SECRET (a packet\n"
                  "                          received after it started is accepted only with a valid\n"
                  "                          signature; a lost session is started again; the session is\n"
                  "                          stopped at the end), datagrams from any other address are\n"
                  "                          dropped and counted (foreign_packets), and packets of another\n"
                  "                          model from its address too (foreign_model_packets); first, its\n"
                  "                          status and clock source say where its times come from (JSON:\n"
                  "                          ptp_status, time_source ptp, gps or free_run)\n"
                  "  --require-sync          with --sensor: exit 2 before recording when the unit runs free\n"
                  "  --session-poll S        ask the unit whether it still signs every S seconds (default 1),\n"
                  "                          off the receive path: a poll unanswered within --timeout is\n"
                  "                          counted (session_poll_timeouts) and reception goes on\n"
                  "  --signature-grace S     packets with no valid signature for S seconds mean the session\n"
                  "                          was lost: it is started again (default 1)\n"
                  "  --ptc-port N            the sensor's PTC port (default 9347)\n"
                  "  --timeout S             the deadline of each PTC request, connecting included (default 3)\n"
                  "  --tls ...               PTCS: the PTC of --sensor over TLS (the options below)\n"
                  "  --json                  the summary as one JSON object (keys as in 'hesai stats --json',\n"
                  "                          and kernel_drops (null where unknown), foreign_packets,\n"
                  "                          foreign_model_packets, session_restarts, session_poll_timeouts)\n"
                  "  --quiet                 no statistics once a second\n%s%s%s%s",
                  port::UdpReceiver::method(), kDecodeOptionsHelp, kOutputOptionsHelp, kKeyOptionsHelp, kTlsOptionsHelp);
      return kExitOk;
    }
    if (parse_decode_option(args, o, error) || parse_output_option(args, out, error) || parse_tls_option(args, tls, error)) {
      if (!error.empty()) return usage_error("listen", error);
      continue;
    }
    args.take();
    std::string v;
    if (a == "--json") json = true;
    else if (a == "--quiet") quiet = true;
    else if (a == "--require-sync") require_sync = true;
    else if (a == "--sensor") { if (!args.value(a, sensor_host)) return usage_error("listen", "--sensor needs a host"); }
    else if (a == "--ptc-port") {
      if (!args.value(a, v) || !parse_u64(v, ptc_port) || ptc_port == 0 || ptc_port > 65535)
        return usage_error("listen", "--ptc-port takes 1 to 65535");
    } else if (a == "--timeout" || a == "--session-poll" || a == "--signature-grace") {
      float& target = a == "--timeout" ? ptc_timeout : a == "--session-poll" ? session_poll : signature_grace;
      if (!args.value(a, v) || !parse_float(v, target) || !(target > 0) || target > 3600)
        return usage_error("listen", a + " takes seconds above 0 (at most 3600)");
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
  if (tls.tls && sensor_host.empty()) return usage_error("listen", "--tls goes with --sensor HOST");
  if (require_sync && sensor_host.empty()) return usage_error("listen", "--require-sync goes with --sensor HOST");
  std::shared_ptr<port::TlsContext> tls_context;
  if (const int st = finish_tls_options(tls, tls_context, error); st != kExitOk) return fail("listen", st, error);
  o.session_secret_allowed = !sensor_host.empty();  // the session's randoms come from the sensor
  std::string session_secret;
  const KeyWipe key_wipe(o, &session_secret);  // every return below
  if (const int st = finish_key_options(o, error); st != kExitOk) return fail("listen", st, error);
  // Resolved once: PTC talks to the address the datagrams are filtered by.
  std::uint32_t sensor_address = 0;
  if (!sensor_host.empty() && !port::resolve_ipv4(sensor_host, sensor_address, error)) return fail("listen", kExitInput, error);
  session_secret.swap(o.session_secret);  // the pipeline gets no copy

  std::unique_ptr<OutputSink> sink;
  if (!out.out.empty()) {
    sink = std::make_unique<OutputSink>(out);
    if (const port::Status s = sink->open(); !s.ok()) return fail("listen", exit_status(s), s.message());
  }
  Pipeline pipeline(o, sink.get());
  wipe_key(o);
  if (const port::Status s = pipeline.load_files(); !s.ok()) return report("listen", s);
  port::UdpReceiver points_rx, gps_rx;
  if (!points_rx.open(bind_addr, static_cast<std::uint16_t>(port), receive, error) ||
      (gps_port != 0 && gps_port != port && !gps_rx.open(bind_addr, static_cast<std::uint16_t>(gps_port), receive, error))) {
    std::fprintf(stderr, "hesai listen: %s\n", error.c_str());
    return kExitInput;
  }
  report_receive_buffer(points_rx, receive.rcvbuf_request, quiet);
  // The sockets are bound: what the sensor sends from now on waits for us while PTC runs. Ctrl-C
  // from here on ends the run in order: the session, if one started, is stopped and its key wiped.
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::unique_ptr<SensorLink> link;
  std::unique_ptr<LiveSession> session;
  if (!sensor_host.empty()) {
    link = std::make_unique<SensorLink>(sensor_host, sensor_address, static_cast<std::uint16_t>(ptc_port),
                                        static_cast<int>(ptc_timeout * 1000), tls_context);
    int rc = link->fetch(o, pipeline, error, require_sync);
    if (rc == kExitOk && link->model() != Model::unknown) pipeline.fix_model(link->model());
    if (rc == kExitOk && !session_secret.empty() && !g_stop)
      rc = start_live_session(*link, session_secret, o.allow_unsigned, {to_ns(session_poll), to_ns(signature_grace)},
                              pipeline, session, error);
    secure_wipe(session_secret.data(), session_secret.size());
    if (rc == kExitOk && g_stop) {
      session.reset();  // stopped on the unit, key wiped
      return kExitOk;
    }
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
  const std::int64_t start = port::monotonic_ns();
  const std::int64_t deadline = seconds > 0 ? start + static_cast<std::int64_t>(seconds * 1e9) : INT64_MAX;
  std::int64_t next_report = start + 1000000000;
  std::vector<port::Datagram> batch;
  const std::int64_t idle_ns = static_cast<std::int64_t>(idle * 1e9);
  std::int64_t now = start;
  std::int64_t last_packet = 0;  // monotonic time of the last datagram; 0 before the first
  std::uint64_t received = 0;
  bool fatal = false;
  int status = kExitOk;  // kExitInput when the session could not be kept
  // One datagram: dropped when it is not from the sensor, else decoded (false: a fatal error).
  const auto take = [&](const port::Datagram& d, bool gps, bool pre_session) {
    if (link && d.source_ipv4 != sensor_address) {
      ++foreign;  // not the sensor's address: no point of it is decoded
      return true;
    }
    ++received;
    // Each sender is a sensor of its own, named by its address and port (GPS packets make none).
    const std::uint64_t key = (std::uint64_t{d.source_ipv4} << 16) | d.source_port;
    if (!gps && !pipeline.has_label(key)) {
      const auto* a = reinterpret_cast<const std::uint8_t*>(&d.source_ipv4);  // network byte order
      pipeline.label_source(key, std::to_string(a[0]) + "." + std::to_string(a[1]) + "." + std::to_string(a[2]) +
                                     "." + std::to_string(a[3]) + ":" + std::to_string(d.source_port));
    }
    pipeline.set_receive_time(static_cast<std::uint64_t>(d.time_ns));
    return pipeline.feed(ByteView{d.data, d.size}, key, pre_session);
  };
  if (session) {
    // What waits in the sockets arrived before the session's answer was read, or while it was
    // read. Where the kernel stamps each datagram (SO_TIMESTAMPNS), only those it received
    // before the answer may be unsigned, and the drain ends at the first one after it; on the
    // portable path, what is queued at this moment (until a receive finds less than a batch).
    const bool stamped = port::UdpReceiver::kernel_timestamps();
    std::uint64_t before = 0;
    for (port::UdpReceiver* rx : {&points_rx, &gps_rx}) {
      bool queued = rx->fd() >= 0;
      while (queued && !fatal) {
        const int n = rx->receive(batch, 0);
        fatal = n < 0;
        queued = n == static_cast<int>(port::UdpReceiver::kBatch);
        for (const port::Datagram& d : batch) {
          if (count != 0 && received >= count) break;
          const bool pre_session = !stamped || d.time_ns <= session->agreed_realtime_ns();
          before += pre_session;
          queued = queued && pre_session;
          if (!take(d, rx == &gps_rx, pre_session)) {
            std::fprintf(stderr, "hesai listen: %s\n", pipeline.error().c_str());
            return kExitUsage;
          }
        }
      }
    }
    std::fprintf(stderr, "signature session started (%llu datagrams received before it may be unsigned): from now on "
                         "a packet is accepted only with a valid signature\n",
                 static_cast<unsigned long long>(before));
  }
  while (!g_stop && !fatal && status == kExitOk && (count == 0 || received < count) && now < deadline &&
         !(idle_ns > 0 && last_packet != 0 && now - last_packet > idle_ns)) {
    bool arrived = false;
    for (port::UdpReceiver* rx : {&points_rx, &gps_rx}) {
      if (rx->fd() < 0) continue;
      if (rx->receive(batch, rx == &points_rx ? 50 : 0) < 0) fatal = true;
      arrived = arrived || !batch.empty();
      for (const port::Datagram& d : batch) {
        if (count != 0 && received >= count) break;
        if (!take(d, rx == &gps_rx, false)) {
          std::fprintf(stderr, "hesai listen: %s\n", pipeline.error().c_str());
          return kExitUsage;
        }
      }
    }
    now = port::monotonic_ns();
    if (session && (status = session->watch(now, error)) != kExitOk) std::fprintf(stderr, "hesai listen: %s\n", error.c_str());
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
  if (session) session->stop();
  if (sink)
    if (const port::Status s = sink->close(); !s.ok()) std::fprintf(stderr, "hesai listen: %s\n", s.message().c_str());
  const std::uint64_t restarts = session ? session->restarts() : 0;
  const std::uint64_t poll_timeouts = session ? session->poll_timeouts() : 0;
  if (json) {
    std::string j = stats_json(pipeline.stats(), pipeline.sensors());
    // kernel_drops: null where the receive path cannot know it (the portable path), never 0.
    const std::string drops = port::UdpReceiver::kernel_drops_known() ? std::to_string(points_rx.kernel_drops()) : "null";
    j.insert(j.size() - 1, ",\"kernel_drops\":" + drops + ",\"foreign_packets\":" + std::to_string(foreign) + ",\"foreign_model_packets\":" +
                               std::to_string(pipeline.foreign_model_packets()) +
                               ",\"session_restarts\":" + std::to_string(restarts) +
                               ",\"session_poll_timeouts\":" + std::to_string(poll_timeouts) +
                               (link ? ",\"ptp_status\":" + json_string(link->ptp_status().c_str()) +
                                           ",\"time_source\":" + json_string(link->time_source().c_str())
                                     : std::string()));
    std::printf("%s\n", j.c_str());
  } else {
    std::printf("%s  kernel_drops          %s\n  foreign_packets       %llu\n  foreign_model_packets %llu\n"
                "  session_restarts      %llu\n  session_poll_timeouts %llu\n",
                stats_text(pipeline).c_str(), kernel_drops(points_rx).c_str(), static_cast<unsigned long long>(foreign),
                static_cast<unsigned long long>(pipeline.foreign_model_packets()),
                static_cast<unsigned long long>(restarts), static_cast<unsigned long long>(poll_timeouts));
  }
  return fatal ? kExitInput : status;
}

}  // namespace hesai::cli
