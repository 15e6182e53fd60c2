// Stats and count_error: the mapping from error codes to counters, typed in from the brief.
#include <gtest/gtest.h>

#include <cstdint>
#include <type_traits>

#include "hesai/stats.h"

namespace {

using hesai::Error;
using hesai::Model;
using hesai::Stats;

static_assert(std::is_aggregate_v<Stats>, "Stats is a plain aggregate");

// The error counters, in a fixed order, to see which one moved.
struct Counters {
  std::uint64_t crc, sig_invalid, sig_missing, unsupported, malformed, others;
};
Counters snapshot(const Stats& s) {
  return {s.crc_errors,       s.signature_invalid, s.signature_missing, s.unsupported, s.malformed,
          s.packets + s.points + s.frames + s.signature_valid + s.signature_unverified + s.lost + s.duplicates +
              s.reordered + s.gps_packets};
}

TEST(Stats, StartsAtZero) {
  const Stats s{};
  EXPECT_EQ(s.packets, 0u);
  EXPECT_EQ(s.malformed, 0u);
  EXPECT_EQ(s.first_time_ns, 0);
  for (std::uint64_t m : s.models) EXPECT_EQ(m, 0u);
  EXPECT_EQ(s.models.size(), hesai::kModelCount);
  EXPECT_EQ(s.spin_rpm_last, 0);
  EXPECT_EQ(s.return_mode_last, 0);
}

TEST(Stats, NamedErrors) {
  Stats s{};
  hesai::count_error(s, Error::crc_body);
  hesai::count_error(s, Error::crc_functional_safety);
  hesai::count_error(s, Error::crc_tail);
  EXPECT_EQ(s.crc_errors, 3u);
  hesai::count_error(s, Error::signature_invalid);
  EXPECT_EQ(s.signature_invalid, 1u);
  hesai::count_error(s, Error::signature_missing);
  hesai::count_error(s, Error::signature_missing);
  EXPECT_EQ(s.signature_missing, 2u);
  EXPECT_EQ(s.unsigned_rejected, 2u);  // a rejection: none of them accepted
  EXPECT_EQ(s.unsigned_accepted, 0u);
  hesai::count_error(s, Error::unsupported_version);
  hesai::count_error(s, Error::unsupported_model);
  hesai::count_error(s, Error::unsupported_section);
  EXPECT_EQ(s.unsupported, 3u);
  // A customised QT128 packet this decoder cannot map (no configuration, or another LaserNum).
  hesai::count_error(s, Error::channel_config_required);
  hesai::count_error(s, Error::channel_config_mismatch);
  EXPECT_EQ(s.unsupported, 5u);
  hesai::count_error(s, Error::bad_magic);
  hesai::count_error(s, Error::bad_length);
  hesai::count_error(s, Error::dual_block_mismatch);
  EXPECT_EQ(s.malformed, 3u);
  EXPECT_EQ(s.packets, 0u);  // count_error does not count packets
  EXPECT_EQ(s.signature_valid, 0u);
  EXPECT_EQ(s.signature_unverified, 0u);
}

TEST(Stats, OkCountsNothing) {
  Stats s{};
  hesai::count_error(s, Error::ok);
  const Counters c = snapshot(s);
  EXPECT_EQ(c.crc + c.sig_invalid + c.sig_missing + c.unsupported + c.malformed + c.others, 0u);
}

TEST(Stats, EveryCodeMovesExactlyOneCounter) {
  // Every code from truncated (1) to the last: the 10 named above go to their
  // counters, every other one to malformed.
  const auto last = static_cast<unsigned>(hesai::kLastError);
  unsigned crc = 0, sig_inv = 0, sig_miss = 0, unsup = 0, malformed = 0;
  for (unsigned v = 1; v <= last; ++v) {
    Stats s{};
    hesai::count_error(s, static_cast<Error>(v));
    const Counters c = snapshot(s);
    EXPECT_EQ(c.crc + c.sig_invalid + c.sig_missing + c.unsupported + c.malformed, 1u) << "code " << v;
    EXPECT_EQ(c.others, 0u) << "code " << v;
    crc += static_cast<unsigned>(c.crc);
    sig_inv += static_cast<unsigned>(c.sig_invalid);
    sig_miss += static_cast<unsigned>(c.sig_missing);
    unsup += static_cast<unsigned>(c.unsupported);
    malformed += static_cast<unsigned>(c.malformed);
  }
  EXPECT_EQ(crc, 3u);
  EXPECT_EQ(sig_inv, 1u);
  EXPECT_EQ(sig_miss, 1u);
  EXPECT_EQ(unsup, 5u);
  EXPECT_EQ(malformed, last - 10u);
}

TEST(Stats, CountModel) {
  Stats s{};
  hesai::count_model(s, Model::pandar64);
  hesai::count_model(s, Model::pandar64);
  hesai::count_model(s, Model::qt128c2x);
  hesai::count_model(s, static_cast<Model>(200));  // not a model: counted as unknown
  EXPECT_EQ(s.models[static_cast<std::size_t>(Model::pandar64)], 2u);
  EXPECT_EQ(s.models[static_cast<std::size_t>(Model::qt128c2x)], 1u);
  EXPECT_EQ(s.models[static_cast<std::size_t>(Model::unknown)], 1u);
  EXPECT_EQ(s.models[static_cast<std::size_t>(Model::pandar40)], 0u);
}

}  // namespace

// Issue #32: every counter saturates; none wraps. Counters set one below and at their largest
// value: one more reaches it, then stays there.
TEST(Stats, CountersSaturate) {
  hesai::Stats s{};
  s.crc_errors = UINT64_MAX - 1;
  s.malformed = UINT64_MAX;
  s.high_temperature = UINT64_MAX;
  s.models[static_cast<std::size_t>(hesai::Model::pandar64)] = UINT64_MAX;
  s.safety.packets = UINT64_MAX;
  s.safety.states[1] = UINT64_MAX;
  hesai::count_error(s, hesai::Error::crc_body);
  EXPECT_EQ(s.crc_errors, UINT64_MAX);
  hesai::count_error(s, hesai::Error::crc_body);
  EXPECT_EQ(s.crc_errors, UINT64_MAX);
  hesai::count_error(s, hesai::Error::bad_magic);
  EXPECT_EQ(s.malformed, UINT64_MAX);
  hesai::PacketInfo info;
  info.high_temperature = 1;
  hesai::count_status(s, info);
  EXPECT_EQ(s.high_temperature, UINT64_MAX);
  hesai::count_model(s, hesai::Model::pandar64);
  EXPECT_EQ(s.models[static_cast<std::size_t>(hesai::Model::pandar64)], UINT64_MAX);
  hesai::FunctionalSafety fs;
  fs.present = true;
  fs.lidar_state = 1;
  hesai::count_safety(s.safety, fs, false);
  EXPECT_EQ(s.safety.packets, UINT64_MAX);
  EXPECT_EQ(s.safety.states[1], UINT64_MAX);
  // A saturated total no longer falls: it is no longer exact.
  std::uint64_t total = UINT64_MAX;
  hesai::saturating_follow(total, 5, 2);
  EXPECT_EQ(total, UINT64_MAX);
  total = 10;
  hesai::saturating_follow(total, 5, 2);
  EXPECT_EQ(total, 7u);
}
