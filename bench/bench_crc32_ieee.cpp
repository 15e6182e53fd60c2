// CRC-32 (IEEE, as zlib, PNG and MCAP; hesai_port/base/crc32_ieee.h) on each path of this CPU,
// against the byte-at-a-time path (`bytewise`, the implementation before the fast paths) in the
// same run: BM_CRC32IEEE_<path>/<bytes>; bench/report.py divides each by BM_CRC32IEEE_bytewise.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <vector>

#include "hesai_port/base/crc32_ieee.h"

namespace {

using hesai::port::Crc32IeeePath;

void BM_Crc32Ieee(benchmark::State& state, Crc32IeeePath path) {
  std::vector<std::uint8_t> data(static_cast<std::size_t>(state.range(0)));
  std::uint32_t x = 0x12345678u;
  for (auto& v : data) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    v = static_cast<std::uint8_t>(x);
  }
  for (auto _ : state) {
    std::uint32_t crc = hesai::port::crc32_ieee(path, data.data(), data.size());
    benchmark::DoNotOptimize(crc);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

// Registered before main() runs: every path this CPU has, at a PointCloud2 field's size, 64 KiB
// and an MCAP chunk's 1 MiB.
const int kRegistered = [] {
  for (const Crc32IeeePath p :
       {Crc32IeeePath::bytewise, Crc32IeeePath::slicing, Crc32IeeePath::pclmul, Crc32IeeePath::armv8}) {
    if (!hesai::port::crc32_ieee_available(p)) continue;
    benchmark::RegisterBenchmark((std::string("BM_CRC32IEEE_") + hesai::port::crc32_ieee_path_name(p)).c_str(),
                                 BM_Crc32Ieee, p)
        ->Arg(256)
        ->Arg(64 * 1024)
        ->Arg(1024 * 1024);
  }
  return 0;
}();

}  // namespace
