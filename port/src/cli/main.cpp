// hesai: decode Hesai lidar captures and live streams. The commands are the table below: the
// usage is made from it, so it names every command there is.
#include <cstdio>
#include <cstring>
#include <string>

#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/sha256.h"
#include "hesai_port/base/crc32_ieee.h"
#include "hesai_port/net/tls.h"
#include "commands.h"

namespace hesai::cli {
namespace {

struct Command {
  const char* name;
  const char* operands;  // after the name in the usage
  const char* summary;
  int (*run)(Args&);
};

constexpr Command kCommands[] = {
    {"decode", "CAPTURE", "decode a pcap/pcapng capture or a PandarScan MCAP bag into points", cmd_decode},
    {"stats", "CAPTURE", "count packets, points, frames, integrity failures and losses", cmd_stats},
    {"listen", "", "receive packets live over UDP and report statistics", cmd_listen},
    {"replay", "CAPTURE", "send a capture's UDP payloads to HOST:PORT (and stand in for the sensor's PTC)", cmd_replay},
    {"sensor", "COMMAND HOST", "talk to a sensor over PTC: info, config, status, calibration, firetimes,\n"
                               "channel-config, signature start|status|stop, set, apply, reboot",
     cmd_sensor},
};

std::string usage() {
  std::string u = "usage: hesai <command> [options]\n       hesai --version\n\ncommands:\n";
  for (const Command& c : kCommands) {
    std::string head = std::string("  ") + c.name + (*c.operands ? " " : "") + c.operands;
    head.resize(head.size() < 22 ? 22 : head.size() + 1, ' ');
    u += head;
    for (const char* s = c.summary; *s; ++s) u += *s == '\n' ? std::string("\n") + std::string(22, ' ') : std::string(1, *s);
    u += "\n";
  }
  return u + "\nRun 'hesai <command> --help' for the options of a command.\n";
}

// The version, the C library's ABI, and the CPU paths this build chose on this machine.
int version() {
  std::printf("hesai %s\nC ABI (libhesai_c) %d\n", HESAI_VERSION, HESAI_C_ABI);
  std::printf("decode: %s (avx512, avx2, neon or armv7m where built for and present; none: the portable loops)\n",
              decode_simd_name());
  std::printf("crc32/mpeg-2 (packets): %s\n", crc32_path_name());
  std::printf("crc32/ieee (mcap, png): %s\n", port::crc32_ieee_path_name(port::crc32_ieee_best_path()));
  std::printf("sha-256 (signatures): %s\n", sha256_path_name());
  std::printf("tls (ptcs): %s\n", port::tls_available() ? "yes" : "no (built without OpenSSL)");
  return kExitOk;
}

}  // namespace
}  // namespace hesai::cli

int main(int argc, char** argv) {
  using namespace hesai::cli;
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    std::fputs(usage().c_str(), argc < 2 ? stderr : stdout);
    return argc < 2 ? kExitUsage : kExitOk;
  }
  if (std::strcmp(argv[1], "--version") == 0) return version();
  const std::string command = argv[1];
  Args args(argc, argv, 2);
  for (const Command& c : kCommands)
    if (command == c.name) return c.run(args);
  std::fprintf(stderr, "hesai: unknown command '%s'\n\n%s", command.c_str(), usage().c_str());
  return kExitUsage;
}
