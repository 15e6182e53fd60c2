// The hesai program. Placeholder until the command-line interface lands.
#include <cstdio>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <command> [options] FILE.pcap\n", argc > 0 ? argv[0] : "hesai");
    return 1;
  }
  std::fprintf(stderr, "%s: no commands yet\n", argv[0]);
  return 1;
}
