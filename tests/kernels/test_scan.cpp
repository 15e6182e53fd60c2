// The hosted unit scans (UnitScan: blockage markers, repeated dual returns, distances beyond the
// rated range) against the reference scalar scan that the firmware builds run
// (sensors/block_points.h scan_units, forced by hesai::detail::use_reference_scan): the branch-free
// scalar scan (DecodePath::portable) and the AVX2 scan (DecodePath::avx2 and best on x86-64), on
// every packet of every bundled capture and on packets whose units are randomised. The AVX2 scan
// must have run where it is claimed (its kernel counter), not the scalar scan in its place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/detail/pandar40_packet.h"
#include "hesai/detail/pandar64_packet.h"
#include "kernel_calls.h"
#include "packet_builder.h"
#include "test_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {

using Packet = std::vector<std::uint8_t>;

struct Capture {
  const char* file;
  Model model;
};
const Capture kCaptures[] = {{"pandar40p_dual.pcap", Model::pandar40p},
                             {"pandar64_dual.pcap", Model::pandar64},
                             {"qt128c2x_dual.pcap", Model::qt128c2x},
                             {"pandar_qt64.pcap", Model::pandar_qt64},
                             {"pandar_xt16.pcap", Model::pandar_xt16},
                             {"pandar_xt32.pcap", Model::pandar_xt32},
                             {"pandar_xt32m2x.pcap", Model::pandar_xt32m2x}};

// Whether DecodePath `path` scans by the AVX2 scan here (a packet without a channel map).
bool vector_scan(DecodePath path) {
  if (path == DecodePath::portable || !decode_simd_available()) return false;
  const char* isa = decode_simd_name();
  return std::strcmp(isa, "avx2") == 0 || std::strcmp(isa, "avx512") == 0;
}

::testing::AssertionResult same_scan(const UnitScan& want, const UnitScan& got) {
  if (want.blockage_units != got.blockage_units)
    return ::testing::AssertionFailure() << "blockage_units " << got.blockage_units << ", reference " << want.blockage_units;
  if (want.duplicate_returns != got.duplicate_returns)
    return ::testing::AssertionFailure() << "duplicate_returns " << got.duplicate_returns << ", reference "
                                         << want.duplicate_returns;
  if (want.beyond_rated_range != got.beyond_rated_range)
    return ::testing::AssertionFailure() << "beyond_rated_range " << got.beyond_rated_range << ", reference "
                                         << want.beyond_rated_range;
  for (std::size_t c = 0; c < kMaxChannels; ++c)
    if (want.blockage_by_channel[c] != got.blockage_by_channel[c])
      return ::testing::AssertionFailure() << "blockage_by_channel[" << c << "] " << int{got.blockage_by_channel[c]}
                                           << ", reference " << int{want.blockage_by_channel[c]};
  for (std::size_t f = 0; f < kMaxDualFirings; ++f)
    for (std::size_t i = 0; i < kMaxChannels / 8; ++i)
      if (want.repeated[f][i] != got.repeated[f][i])
        return ::testing::AssertionFailure() << "repeated[" << f << "][" << i << "] " << int{got.repeated[f][i]}
                                             << ", reference " << int{want.repeated[f][i]};
  return ::testing::AssertionSuccess();
}

// Scans one packet by the reference and by every hosted path, and compares; `vector_scans` counts
// the decodes the AVX2 scan should have taken. The scan's summary, for the tests' own checks.
struct Summary {
  std::uint64_t blockage = 0, duplicates = 0, beyond = 0, packets = 0;
};
void compare_paths(Decoder& d, const Packet& p, bool mapped, std::uint32_t& vector_scans, Summary& sum,
                   const std::string& what) {
  static PacketPoints pts;
  PacketInfo info;
  UnitScan want;
  detail::use_reference_scan(true);
  const Error e = d.decode(view(p), info, pts, want, Returns::all, DecodePath::portable);
  detail::use_reference_scan(false);
  ASSERT_EQ(e, Error::ok) << what;
  for (const DecodePath path : {DecodePath::portable, DecodePath::avx2, DecodePath::best}) {
    UnitScan got;
    ASSERT_EQ(d.decode(view(p), info, pts, got, Returns::all, path), Error::ok) << what;
    EXPECT_TRUE(same_scan(want, got)) << what << ", DecodePath " << static_cast<int>(path);
    if (!mapped && vector_scan(path)) ++vector_scans;
  }
  sum.blockage += want.blockage_units, sum.duplicates += want.duplicate_returns, sum.beyond += want.beyond_rated_range;
  ++sum.packets;
}

void expect_vector_scans(std::uint32_t want, const std::string& what) {
  const std::uint32_t got = detail::kernel_calls(detail::Kernel::avx2_scan);
  if (want > 0) {
    EXPECT_GT(got, 0u) << what << ": the AVX2 scan never ran (the scalar scan in its place)";
  }
  EXPECT_EQ(got, want) << what << ": calls of the AVX2 scan";
}

TEST(Scan, EveryPacketOfEveryCaptureEqualsTheReference) {
  for (const Capture& cap : kCaptures) {
    const auto packets = pcap_payloads(cap.file);
    ASSERT_FALSE(packets.empty()) << cap.file;
    detail::reset_kernel_calls();
    Decoder d(cap.model);
    std::uint32_t vector_scans = 0;
    Summary sum;
    for (std::size_t i = 0; i < packets.size(); ++i)
      compare_paths(d, packets[i], false, vector_scans, sum, std::string(cap.file) + " packet " + std::to_string(i));
    EXPECT_EQ(sum.packets, packets.size());
    expect_vector_scans(vector_scans, cap.file);
  }
}

// Where a packet's units are: block b's first unit at `at[b]`, `units` of `bytes` bytes each.
struct Units {
  std::vector<std::size_t> at;
  std::size_t units, bytes;
  bool resting_zero = false;  // QT128C2X
};
Units units_of(Model model, const Packet& p) {
  Units u;
  if (model == Model::qt128c2x) {
    const QtOffsets o = qt128_offsets(p);
    for (std::size_t b = 0; b < 2; ++b) u.at.push_back(12 + b * o.block + 2);
    u.units = p[6], u.bytes = o.unit, u.resting_zero = true;
    return u;
  }
  const BlockLayout l = block_layout(model);
  for (std::size_t b = 0; b < l.blocks; ++b) u.at.push_back(l.first + b * l.stride + 2);
  u.bytes = model == Model::pandar40p || model == Model::pandar40 || model == Model::pandar64 ? 3 : 4;
  u.units = (l.stride - 2) / u.bytes;
  return u;
}

// Replaces every unit of `p` by a random one, biased to the values the scans decide on: distance
// 0, 1 (the QT128C2X's blockage marker), 2, the largest within the rated range (`limit`) and the
// ones around it, 0xFFFF, or any; reflectivity 0, 255 or any. A second return copies its first's
// distance half the time, and then its reflectivity half of that. `returns`: the packet's.
void randomise(Packet& p, const Units& u, std::uint32_t limit, std::size_t returns, std::mt19937& rng) {
  auto pick = [&](std::uint32_t n) { return static_cast<std::uint32_t>(rng() % n); };
  for (std::size_t b = 0; b < u.at.size(); ++b) {
    const bool second = returns == 2 && b % 2 == 1;
    for (std::size_t j = 0; j < u.units; ++j) {
      std::uint8_t* unit = &p[u.at[b] + j * u.bytes];
      // A QT128 channel resting in the block's firing sequence must stay all zero (validate()):
      // the units all zero in the real packet are left so.
      if (u.resting_zero && std::all_of(unit, unit + u.bytes, [](std::uint8_t c) { return c == 0; })) continue;
      std::uint32_t d = 0;
      switch (pick(9)) {
        case 0: d = 0; break;
        case 1: d = 1; break;
        case 2: d = 2; break;
        case 3: d = limit; break;
        case 4: d = limit + 1; break;
        case 5: d = limit - 1; break;
        case 6: d = 0xFFFF; break;
        default: d = pick(0x10000); break;
      }
      const std::uint32_t r = pick(4);
      std::uint8_t refl = r == 0 ? 0 : r == 1 ? 255 : static_cast<std::uint8_t>(pick(256));
      if (second && pick(2) == 0) {
        const std::uint8_t* first = &p[u.at[b - 1] + j * u.bytes];
        d = load_le16(first);
        if (pick(2) == 0) refl = first[2];
      }
      store_le16(unit, static_cast<std::uint16_t>(d > 0xFFFF ? 0xFFFF : d));
      unit[2] = refl;
      if (u.bytes == 4) unit[3] = static_cast<std::uint8_t>(pick(256));
    }
  }
}

// Packets of a model to randomise: the capture's first few in every return mode that is one byte
// away (the Pandar40P's and Pandar64's single and dual modes), and for the QT128C2X the same
// rebuilt with 3-byte units and with customised channels (a channel map).
struct Variant {
  Packet packet;
  bool mapped;  // customised QT128 channels
};
std::vector<Variant> variants(const Capture& cap, const ChannelConfig& config) {
  const auto packets = pcap_payloads(cap.file);
  std::vector<Variant> out;
  for (std::size_t i = 0; i < 8 && i < packets.size(); ++i) {
    const Packet& p = packets[i];
    out.push_back({p, false});
    if (cap.model == Model::pandar64 || cap.model == Model::pandar40p) {
      const std::size_t at = cap.model == Model::pandar64 ? pandar64::kReturnMode : pandar40::kReturnMode;
      for (const std::uint8_t mode : {std::uint8_t{0x37}, std::uint8_t{0x38}, std::uint8_t{0x39}}) {
        Packet q = p;
        q[at] = mode;
        out.push_back({q, false});
      }
    }
    if (cap.model == Model::qt128c2x) {
      std::vector<std::size_t> keep;
      for (std::size_t j = 0; j < config.laser_num; ++j) keep.push_back(config.channel[(p[1066] & 1) ? 0 : 1][j] - 1u);
      out.push_back({qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)}), false});
      out.push_back({qt128_rebuild(p, static_cast<std::uint8_t>(config.laser_num), 0x4D, {keep, keep}), true});
    }
  }
  return out;
}

TEST(Scan, RandomisedUnitsEqualTheReference) {
  const auto config_text = read_file(data_path("calibration/qt128c2x_channel_config.csv"));
  static ChannelConfig config;
  ASSERT_EQ(parse_channel_config_csv(view(config_text), config).error, Error::ok);
  std::mt19937 rng(20261129);
  for (const Capture& cap : kCaptures) {
    detail::reset_kernel_calls();
    Decoder d(cap.model);
    ASSERT_EQ(d.set_channel_config(config), cap.model == Model::qt128c2x ? Error::ok : Error::invalid_argument);
    std::uint32_t vector_scans = 0;
    Summary sum;
    bool dual = false, mapped = false;
    for (const Variant& v : variants(cap, config)) {
      PacketInfo info;
      static PacketPoints pts;
      ASSERT_EQ(d.decode(view(v.packet), info, pts), Error::ok) << cap.file;
      const std::uint32_t rated_mm = 1000u * rated_range_m(cap.model);
      const std::uint32_t limit = rated_mm != 0 ? rated_mm / info.dis_unit_mm : 0xFFFF;
      const Units u = units_of(cap.model, v.packet);
      dual = dual || info.returns == 2;
      mapped = mapped || v.mapped;
      for (int iteration = 0; iteration < 40; ++iteration) {
        Packet q = v.packet;
        randomise(q, u, limit, info.returns, rng);
        if (cap.model == Model::qt128c2x) qt128_seal(q);
        const std::string what = std::string(cap.file) + " returns " + std::to_string(info.returns) + " unit bytes " +
                                 std::to_string(u.bytes) + (v.mapped ? " customised" : "") + " iteration " +
                                 std::to_string(iteration);
        compare_paths(d, q, v.mapped, vector_scans, sum, what);
      }
    }
    // The randomised units reach every count (blockage only where distance 1 is a marker).
    if (rated_range_m(cap.model) != 0) {
      EXPECT_GT(sum.beyond, 0u) << cap.file;
    }
    if (dual) {
      EXPECT_GT(sum.duplicates, 0u) << cap.file;
    }
    if (cap.model == Model::qt128c2x) {
      EXPECT_GT(sum.blockage, 0u);
      EXPECT_TRUE(mapped);
    }
    expect_vector_scans(vector_scans, cap.file);
  }
}

}  // namespace
