// hesai decode and hesai stats: a capture through the engine, to an output or to the counters.
#include <unistd.h>

#include <cstdio>
#include <string>

#include "hesai_port/pipeline/pipeline.h"
#include "hesai_port/pipeline/report.h"
#include "hesai_port/pipeline/run.h"
#include "hesai_port/pipeline/sinks.h"
#include "commands.h"

namespace hesai::cli {

namespace {
// The "NN.N% N packets" line on a terminal's stderr while a capture is read (none with --quiet or
// when stderr is not a terminal); it is cleared once the run returns.
struct ProgressLine {
  bool shown = false;
  ~ProgressLine() {
    if (shown) std::fprintf(stderr, "\r%60s\r", "");
  }
};
}  // namespace

std::function<void(const port::CaptureFeed&)> progress_line(bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  auto line = std::make_shared<ProgressLine>();
  return [line](const port::CaptureFeed& feed) {
    line->shown = true;
    std::fprintf(stderr, "\r%5.1f%% %llu packets", 100.0 * feed.fraction(), static_cast<unsigned long long>(feed.datagrams()));
  };
}

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
  const KeyWipe key_wipe(o);  // every return below
  if (const int st = finish_key_options(o, error); st != kExitOk) return fail("decode", st, error);

  // The input first: an unreadable capture leaves any existing output untouched.
  port::CaptureFile file;
  if (!open_capture(capture, file)) return kExitInput;
  OutputSink sink(out);
  Pipeline pipeline(o, &sink);
  wipe_key(o);
  if (const port::Status s = pipeline.load_files(); !s.ok()) return report("decode", s);
  if (const port::Status s = sink.open(); !s.ok()) return fail("decode", exit_status(s), s.message());
  const int rc = report("", port::run_capture(file, pipeline, progress_line(quiet)));
  if (const port::Status s = sink.close(); !s.ok()) return report("decode", s);
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
                  "                          unsigned_accepted, unsigned_rejected, signature_unverified,\n"
                  "                          replayed, malformed, unsupported, lost, duplicates,\n"
                  "                          reordered, sequence_resyncs, lost_by, time_stalls,\n"
                  "                          time_virtual, time_jumps, blockage_units,\n"
                  "                          blockage_by_channel, duplicate_returns, beyond_rated_range,\n"
                  "                          fov_gap_deg, ip_fragments, gps_packets, first_time_ns,\n"
                  "                          last_time_ns, high_temperature, gps_unlocked,\n"
                  "                          gps_position_invalid, fs_packets, fs_states (per lidar state),\n"
                  "                          fs_current_fault, fs_past_fault, fs_reserved_fault_type,\n"
                  "                          fs_last_fault_code, fs_last_fault_id, fs_last_fault_total,\n"
                  "                          fs_counter_stalls, sensors (one object a sensor, when there\n"
                  "                          are several)\n"
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
  const KeyWipe key_wipe(o);  // every return below
  if (const int st = finish_key_options(o, error); st != kExitOk) return fail("stats", st, error);
  // An unreadable capture gets its error alone; one damaged part-way, the counts up to the damage.
  port::CaptureFile file;
  if (!open_capture(capture, file)) return kExitInput;
  Pipeline pipeline(o, nullptr);
  wipe_key(o);
  if (const port::Status s = pipeline.load_files(); !s.ok()) return report("stats", s);
  const int rc = report("", port::run_capture(file, pipeline, progress_line(quiet)));
  if (rc == kExitUsage) return rc;
  pipeline.set_ip_fragments(file.stats().fragments);
  if (json) std::printf("%s\n", stats_json(pipeline.stats(), pipeline.sensors()).c_str());
  else std::printf("%s\n%s", capture.c_str(), stats_text(pipeline).c_str());
  return rc;
}

}  // namespace hesai::cli
