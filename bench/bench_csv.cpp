// CSV rows (hesai_port/formats/writers.h): format_csv_row over points spread as a sensor's,
// against a memcpy of rows of the same bytes already formatted (the floor of any formatter) in the
// same run: BM_CsvFormatRow and BM_CsvCopyRow, per row (time per row; their ratio is the cost of
// formatting over copying the bytes).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hesai_port/formats/writers.h"

namespace {

// Points spread as a sensor's: azimuth 0..360, elevation -25..15, distance 0.3..200 m, x/y/z from
// them, time_ns of today's dates (a fixed generator, not a capture: the digits per field vary as
// a capture's do).
std::vector<hesai::Point> points() {
  std::vector<hesai::Point> out(4096);
  std::uint32_t x = 2463534242u;
  auto next = [&x] {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return x;
  };
  for (hesai::Point& p : out) {
    p.azimuth_deg = static_cast<float>(next() % 360000) / 1000.0f;
    p.elevation_deg = static_cast<float>(next() % 40000) / 1000.0f - 25.0f;
    p.distance_m = 0.3f + static_cast<float>(next() % 2000000) / 10000.0f;
    p.x = p.distance_m * (static_cast<float>(next() % 2001) / 1000.0f - 1.0f);
    p.y = p.distance_m * (static_cast<float>(next() % 2001) / 1000.0f - 1.0f);
    p.z = p.distance_m * (static_cast<float>(next() % 601) / 1000.0f - 0.3f);
    p.intensity = static_cast<std::uint8_t>(next());
    p.channel = static_cast<std::uint8_t>(1 + next() % 64);
    p.block = static_cast<std::uint8_t>(next() % 6);
    p.return_index = static_cast<std::uint8_t>(next() % 2);
    p.time_ns = 1700000000000000000 + static_cast<std::int64_t>(next());
  }
  return out;
}

void BM_CsvFormatRow(benchmark::State& state) {
  const std::vector<hesai::Point> pts = points();
  std::vector<char> out(hesai::port::kCsvMaxRow);
  std::size_t i = 0, bytes = 0;
  for (auto _ : state) {
    bytes += hesai::port::format_csv_row(out.data(), pts[i], 42, 123456);
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) % pts.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
BENCHMARK(BM_CsvFormatRow);

void BM_CsvCopyRow(benchmark::State& state) {
  const std::vector<hesai::Point> pts = points();
  std::vector<std::string> rows;
  for (const hesai::Point& p : pts) {
    char row[hesai::port::kCsvMaxRow];
    rows.emplace_back(row, hesai::port::format_csv_row(row, p, 42, 123456));
  }
  std::vector<char> out(hesai::port::kCsvMaxRow);
  std::size_t i = 0, bytes = 0;
  for (auto _ : state) {
    std::memcpy(out.data(), rows[i].data(), rows[i].size());
    bytes += rows[i].size();
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) % rows.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
BENCHMARK(BM_CsvCopyRow);

}  // namespace
