// hesai_bench: packet validation and decoding per sensor, with a memcpy baseline of the same
// packets and a baseline that only writes their Points; frame assembly point by point and by
// block over whole captures; the CRC-32/MPEG-2 paths; SHA-256 and HMAC-SHA256 beside OpenSSL's.
// Packets are real ones from data/*.pcap, taken round-robin (a handful, not one).
// bench/report.py turns the JSON output into a table of ratios and target checks.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/frame.h"
#include "hesai/hmac.h"
#include "hesai/detail/pandar40_packet.h"
#include "hesai/detail/pandar64_packet.h"
#include "hesai/detail/qt128_packet.h"
#include "hesai/detail/qt64_packet.h"
#include "hesai/detail/xt_packet.h"
#include "hesai/sha256.h"
#include "hesai_port/base/crc32_ieee.h"

#ifdef HESAI_BENCH_OPENSSL
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/sha.h>
#endif

namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr std::size_t kPacketsPerSensor = 16;

/// UDP payloads of a classic pcap of Ethernet/IPv4/UDP frames (42 bytes of headers).
std::vector<Bytes> pcap_payloads(const char* name, std::size_t limit) {
  const std::string path = std::string(HESAI_DATA_DIR) + "/" + name;
  std::ifstream f(path, std::ios::binary);
  const Bytes file((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (file.size() < 24) {
    std::fprintf(stderr, "hesai_bench: cannot read %s\n", path.c_str());
    std::exit(1);
  }
  std::vector<Bytes> out;
  std::size_t off = 24;
  // Spread the picks over the first part of the capture.
  std::size_t index = 0;
  while (off + 16 <= file.size() && out.size() < limit) {
    const std::uint32_t incl = hesai::load_le32(&file[off + 8]);
    off += 16;
    if (incl < 42 || incl > file.size() - off) break;
    if (index++ % 7 == 0) out.emplace_back(file.begin() + static_cast<long>(off + 42), file.begin() + static_cast<long>(off + incl));
    off += incl;
  }
  return out;
}

std::vector<Bytes> pcap_payloads_all(const char* name) {
  const std::string path = std::string(HESAI_DATA_DIR) + "/" + name;
  std::ifstream f(path, std::ios::binary);
  const Bytes file((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::vector<Bytes> out;
  for (std::size_t off = 24; off + 16 <= file.size();) {
    const std::uint32_t incl = hesai::load_le32(&file[off + 8]);
    off += 16;
    if (incl < 42 || incl > file.size() - off) break;
    out.emplace_back(file.begin() + static_cast<long>(off + 42), file.begin() + static_cast<long>(off + incl));
    off += incl;
  }
  if (out.empty()) {
    std::fprintf(stderr, "hesai_bench: cannot read %s\n", path.c_str());
    std::exit(1);
  }
  return out;
}

std::uint8_t session_key(std::size_t i) { return static_cast<std::uint8_t>(0xA5 ^ (i * 29)); }

struct Sensor {
  hesai::Model model;
  std::vector<Bytes> packets;
};

const Sensor& sensor(hesai::Model m) {
  static const Sensor p40p{hesai::Model::pandar40p, pcap_payloads("pandar40p_dual.pcap", kPacketsPerSensor)};
  static const Sensor p64{hesai::Model::pandar64, pcap_payloads("pandar64_dual.pcap", kPacketsPerSensor)};
  static const Sensor qt{hesai::Model::qt128c2x, pcap_payloads("qt128c2x_dual.pcap", kPacketsPerSensor)};
  static const Sensor qt64{hesai::Model::pandar_qt64, pcap_payloads("pandar_qt64.pcap", kPacketsPerSensor)};
  // Pandar40 (1256 bytes): no bundled capture; the 40P packets' 1240 bytes of blocks + the
  // first 16 bytes of their tail.
  static const Sensor p40 = [] {
    Sensor s{hesai::Model::pandar40, {}};
    for (const Bytes& p : p40p.packets) s.packets.emplace_back(p.begin(), p.begin() + 1256);
    return s;
  }();
  // PandarXT16, XT32, XT32M2X (protocol 6.1).
  static const Sensor xt16{hesai::Model::pandar_xt16, pcap_payloads("pandar_xt16.pcap", kPacketsPerSensor)};
  static const Sensor xt32{hesai::Model::pandar_xt32, pcap_payloads("pandar_xt32.pcap", kPacketsPerSensor)};
  static const Sensor xt32m2x{hesai::Model::pandar_xt32m2x, pcap_payloads("pandar_xt32m2x.pcap", kPacketsPerSensor)};
  switch (m) {
    case hesai::Model::pandar_xt16: return xt16;
    case hesai::Model::pandar_xt32: return xt32;
    case hesai::Model::pandar_xt32m2x: return xt32m2x;
    case hesai::Model::pandar40: return p40;
    case hesai::Model::pandar40p: return p40p;
    case hesai::Model::pandar64: return p64;
    case hesai::Model::pandar_qt64: return qt64;
    default: return qt;
  }
}

/// QT128 packets signed with the session key: HMAC-SHA256 of the bytes before the signature.
const std::vector<Bytes>& signed_qt128() {
  static const std::vector<Bytes> packets = [] {
    std::uint8_t key[32];
    for (std::size_t i = 0; i < 32; ++i) key[i] = session_key(i);
    std::vector<Bytes> out = sensor(hesai::Model::qt128c2x).packets;
    for (Bytes& p : out) {
      const std::size_t at = hesai::qt128::Layout::from_header(p[hesai::qt128::kLaserNum], p[hesai::qt128::kFlags]).signature;
      if (at == 0 || p.size() != at + hesai::qt128::kSignatureBytes) {
        std::fprintf(stderr, "hesai_bench: QT128 capture packets carry no signature section\n");
        std::exit(1);
      }
      hesai::hmac_sha256({key, 32}, {p.data(), at}, p.data() + at);
    }
    return out;
  }();
  return packets;
}

/// The worst case for the per-spin-rate cache: the same packets with the motor speed changed on
/// every one, alternating 598 and 602 rpm (both seen in the bundled captures, whose units wander
/// between 598 and 602 and change speed 11-12 times each), so that every decode() rebuilds the
/// cache. CRCs re-sealed where the model has them (QT128C2X).
const std::vector<Bytes>& rpm_changing(hesai::Model model) {
  // The motor speed field of each layout.
  auto speed_at = [](hesai::Model m, const Bytes& p) -> std::size_t {
    switch (m) {
      case hesai::Model::pandar40:
      case hesai::Model::pandar40p: return hesai::pandar40::kMotorSpeed;
      case hesai::Model::pandar64: return hesai::pandar64::kMotorSpeed;
      case hesai::Model::qt128c2x:
        return hesai::qt128::Layout::from_header(p[hesai::qt128::kLaserNum], p[hesai::qt128::kFlags]).tail +
               hesai::qt128::kTailMotorSpeed;
      case hesai::Model::pandar_qt64: return hesai::qt64::kTail + hesai::qt64::kTailMotorSpeed;
      case hesai::Model::pandar_xt16:
      case hesai::Model::pandar_xt32:
      case hesai::Model::pandar_xt32m2x: return p.size() - hesai::xt::kTailBytes + hesai::xt::kTailMotorSpeed;
      case hesai::Model::unknown: break;
    }
    std::fprintf(stderr, "hesai_bench: no motor speed field for this model\n");
    std::exit(1);
  };
  static std::vector<Bytes> made[hesai::kModelCount];
  std::vector<Bytes>& out = made[static_cast<std::size_t>(model)];
  if (!out.empty()) return out;
  out = sensor(model).packets;
  for (std::size_t i = 0; i < out.size(); ++i) {
    Bytes& p = out[i];
    hesai::store_le16(&p[speed_at(model, p)], i % 2 == 0 ? 598 : 602);
    if (model == hesai::Model::qt128c2x && hesai::qt128::seal(p.data(), p.size()) != hesai::Error::ok) {
      std::fprintf(stderr, "hesai_bench: cannot re-seal a QT128 packet\n");
      std::exit(1);
    }
  }
  if (out.size() % 2 != 0) out.pop_back();  // round robin: the last packet's rate differs from the first's
  return out;
}

enum class Stage {
  validate,
  decode,
  decode_nofiretime,
  decode_signed,
  decode_rpm_changes,
  decode_columns,
  decode_columns_portable,
  decode_columns_avx2,
  decode_portable,  // Points by the scalar loop
  decode_avx2,      // Points by the AVX2 code where AVX-512 is present
  decode_scan,      // Points and the unit scan (UnitScan), best path
  decode_scan_portable  // the same by the scalar code
};

void finish_counters(benchmark::State& state, std::uint64_t bytes, std::uint64_t points) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
}

void BM_Decoder(benchmark::State& state, hesai::Model model, Stage stage) {
  const std::vector<Bytes>& packets = stage == Stage::decode_signed        ? signed_qt128()
                                      : stage == Stage::decode_rpm_changes ? rpm_changing(model)
                                                                           : sensor(model).packets;
  hesai::Decoder decoder(model);
  if (stage == Stage::decode_nofiretime) decoder.set_firetime_correction(false);
  if (stage == Stage::decode_signed) {
    std::uint8_t key[32];
    for (std::size_t i = 0; i < 32; ++i) key[i] = session_key(i);
    if (decoder.set_session_key(key) != hesai::Error::ok) {
      state.SkipWithError("this core has no signature support (HESAI_SIGNATURE 0)");
      return;
    }
  }
  // Every packet must pass, or the benchmark would time the error path.
  static hesai::PacketPoints out;
  static hesai::PacketColumns<hesai::kMaxPointsPerPacket> columns;
  const hesai::DecodePath path =
      stage == Stage::decode_columns_portable || stage == Stage::decode_portable ||
              stage == Stage::decode_scan_portable
          ? hesai::DecodePath::portable
      : stage == Stage::decode_columns_avx2 || stage == Stage::decode_avx2       ? hesai::DecodePath::avx2
                                                                                 : hesai::DecodePath::best;
  for (const Bytes& p : packets) {
    hesai::PacketInfo info;
    if (decoder.decode({p.data(), p.size()}, info, out) != hesai::Error::ok) {
      state.SkipWithError("a benchmark packet does not decode");
      return;
    }
  }
  std::size_t i = 0;
  std::uint64_t bytes = 0, points = 0;
  hesai::PacketInfo info;
  hesai::UnitScan scan;
  for (auto _ : state) {
    const Bytes& p = packets[i];
    i = i + 1 == packets.size() ? 0 : i + 1;
    hesai::Error e;
    if (stage == Stage::validate) {
      e = decoder.validate({p.data(), p.size()}, info);
    } else if (stage == Stage::decode_columns || stage == Stage::decode_columns_portable ||
               stage == Stage::decode_columns_avx2) {
      e = decoder.decode({p.data(), p.size()}, info, columns, path);
      points += columns.count;
    } else if (stage == Stage::decode_scan || stage == Stage::decode_scan_portable) {
      e = decoder.decode({p.data(), p.size()}, info, out, scan, hesai::Returns::all, path);
      points += out.count;
      benchmark::DoNotOptimize(scan);
    } else {
      e = decoder.decode({p.data(), p.size()}, info, out, path);
      points += out.count;
    }
    benchmark::DoNotOptimize(e);
    benchmark::DoNotOptimize(info);
    benchmark::ClobberMemory();
    bytes += p.size();
  }
  finish_counters(state, bytes, points);
}

/// The floor: copying the packet into a buffer.
void BM_Copy(benchmark::State& state, hesai::Model model) {
  const std::vector<Bytes>& packets = sensor(model).packets;
  alignas(64) static std::uint8_t buffer[2048];
  std::size_t i = 0;
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    const Bytes& p = packets[i];
    i = i + 1 == packets.size() ? 0 : i + 1;
    std::memcpy(buffer, p.data(), p.size());
    benchmark::DoNotOptimize(buffer);
    benchmark::ClobberMemory();
    bytes += p.size();
  }
  finish_counters(state, bytes, 0);
}

// The smallest output a decoder of x, y, z and time could have: four 4-byte arrays (time as an
// offset from the packet time), 16 bytes a point, for BM_Baseline_write_xyzt_<sensor>.
struct XyztArrays {
  float x[hesai::kMaxPointsPerPacket], y[hesai::kMaxPointsPerPacket], z[hesai::kMaxPointsPerPacket];
  std::int32_t t[hesai::kMaxPointsPerPacket];
};

enum class Floor { points, xyzt, columns };

/// The output floor: writing as many 40-byte Points as decode() yields for the same packets
/// (each field stored, none computed), i.e. what the output format alone costs. `xyzt`: the
/// 16-byte minimum above instead of hesai::Point; `columns`: the seven columns of
/// hesai::PointColumns (x, y, z, time, intensity, channel, return: 19 bytes a point).
void BM_WritePoints(benchmark::State& state, hesai::Model model, Floor floor) {
  const std::vector<Bytes>& packets = sensor(model).packets;
  hesai::Decoder decoder(model);
  static hesai::PacketPoints out;
  std::vector<std::size_t> counts;
  hesai::PacketInfo info;
  for (const Bytes& p : packets) {
    if (decoder.decode({p.data(), p.size()}, info, out) != hesai::Error::ok) {
      state.SkipWithError("a benchmark packet does not decode");
      return;
    }
    counts.push_back(out.count);
  }
  std::size_t i = 0;
  std::uint64_t bytes = 0, points = 0;
  for (auto _ : state) {
    const std::size_t n = counts[i];
    const float f = static_cast<float>(i);
    if (floor == Floor::columns) {
      static hesai::PacketColumns<hesai::kMaxPointsPerPacket> c;
      for (std::size_t k = 0; k < n; ++k) {
        c.x[k] = f;
        c.y[k] = f;
        c.z[k] = f;
        c.time_ns[k] = static_cast<std::int32_t>(k);
        c.intensity[k] = static_cast<std::uint8_t>(k);
        c.channel[k] = static_cast<std::uint8_t>(k);
        c.return_index[k] = 0;
      }
      c.count = n;
      benchmark::DoNotOptimize(c);
    } else if (floor == Floor::xyzt) {
      static XyztArrays soa;
      for (std::size_t k = 0; k < n; ++k) {
        soa.x[k] = f;
        soa.y[k] = f;
        soa.z[k] = f;
        soa.t[k] = static_cast<std::int32_t>(k);
      }
      benchmark::DoNotOptimize(soa);
    } else {
      for (std::size_t k = 0; k < n; ++k) {
        hesai::Point& o = out.points[k];
        o.x = f;
        o.y = f;
        o.z = f;
        o.distance_m = f;
        o.azimuth_deg = f;
        o.elevation_deg = f;
        o.time_ns = static_cast<std::int64_t>(k);
        o.intensity = static_cast<std::uint8_t>(k);
        o.channel = static_cast<std::uint8_t>(k);
        o.return_index = 0;
        o.confidence = 0;
        o.block = static_cast<std::uint8_t>(i);
      }
      out.count = n;
      benchmark::DoNotOptimize(out);
    }
    benchmark::ClobberMemory();
    bytes += packets[i].size();
    points += n;
    i = i + 1 == packets.size() ? 0 : i + 1;
  }
  finish_counters(state, bytes, points);
}

/// Every packet of a capture, in order (the frames need the stream: a rotation is 300 to 600
/// packets).
const std::vector<Bytes>& whole_capture(hesai::Model model) {
  static const std::vector<Bytes> p64 = pcap_payloads_all("pandar64_dual.pcap");
  static const std::vector<Bytes> qt = pcap_payloads_all("qt128c2x_dual.pcap");
  static const std::vector<Bytes> p40p = pcap_payloads_all("pandar40p_dual.pcap");
  return model == hesai::Model::pandar64 ? p64 : model == hesai::Model::qt128c2x ? qt : p40p;
}

enum class Frames {
  decode_only,  // the decode and the block azimuths alone: what both below share
  per_point,    // FrameAssembler::point() for each point, as hesai's Pipeline has done
  by_block      // FrameAssembler::points() for each block's points
};

/// The frame assignment of a whole capture, cycled: per packet decode() into Points, then
/// begin_packet(), block() per block (closed frames taken) and the block's points to their frames,
/// as hesai's Pipeline does (every point kept: no range or field-of-view filter). At the end of the
/// capture finish() and the stream starts again. Items: packets; points/s: points assigned.
void BM_Frames(benchmark::State& state, hesai::Model model, Frames how) {
  const std::vector<Bytes>& packets = whole_capture(model);
  hesai::Decoder decoder(model);
  hesai::FrameAssembler frames;
  static hesai::PacketPoints out;
  static std::uint64_t ids[hesai::kMaxPointsPerPacket];
  hesai::PacketInfo info;
  for (const Bytes& p : packets) {
    if (decoder.decode({p.data(), p.size()}, info, out) != hesai::Error::ok) {
      state.SkipWithError("a benchmark packet does not decode");
      return;
    }
  }
  std::size_t i = 0;
  std::uint64_t bytes = 0, points = 0, sum = 0;
  hesai::FrameInfo closed;
  for (auto _ : state) {
    const Bytes& p = packets[i];
    const hesai::Error e = decoder.decode({p.data(), p.size()}, info, out);
    benchmark::DoNotOptimize(e);
    if (frames.set_beam_spread(decoder.beam_spread()) != hesai::Error::ok) {
      state.SkipWithError("the frames refuse the decoder's beam spread");
      return;
    }
    frames.begin_packet(i, 0);
    std::size_t next = 0;
    for (std::size_t b = 0; b < info.blocks; ++b) {
      if (frames.block(info.block_azimuth[b]))
        while (frames.pop_closed(closed)) sum += closed.points;
      const std::size_t first = next;
      while (next < out.count && out.points[next].block == b) ++next;
      if (how == Frames::per_point) {
        for (std::size_t k = first; k < next; ++k) sum += frames.point(out.points[k].azimuth_deg);
      } else if (how == Frames::by_block && next > first) {
        const std::uint64_t id = frames.points(&out.points[first].azimuth_deg, next - first, sizeof(hesai::Point), ids);
        if (id != 0) {
          sum += id * (next - first);
        } else {
          for (std::size_t k = 0; k < next - first; ++k) sum += ids[k];
        }
      }
    }
    benchmark::DoNotOptimize(sum);
    bytes += p.size();
    points += out.count;
    if (++i == packets.size()) {
      i = 0;
      frames.finish();
      while (frames.pop_closed(closed)) sum += closed.points;
    }
  }
  finish_counters(state, bytes, points);
}

Bytes pseudo_random(std::size_t n) {
  Bytes b(n);
  std::uint32_t x = 0x12345678u;
  for (auto& v : b) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    v = static_cast<std::uint8_t>(x);
  }
  return b;
}

void BM_Crc(benchmark::State& state, hesai::CrcPath path) {
  const Bytes data = pseudo_random(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    std::uint32_t crc = hesai::crc32_mpeg2_update(path, hesai::kCrc32Mpeg2Init, {data.data(), data.size()});
    benchmark::DoNotOptimize(crc);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

constexpr std::size_t kSignedBytes = 1095;  // QT128 bytes before the signature (flags 0x1D)

void BM_Sha256(benchmark::State& state, hesai::Sha256Path path) {
  const Bytes data = pseudo_random(static_cast<std::size_t>(state.range(0)));
  std::uint8_t digest[32];
  for (auto _ : state) {
    hesai::Sha256 h(path);
    h.update({data.data(), data.size()});
    h.finish(digest);
    benchmark::DoNotOptimize(digest);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

/// One-shot HMAC (key set-up included), as OpenSSL's HMAC().
void BM_Hmac(benchmark::State& state, hesai::Sha256Path path) {
  const Bytes data = pseudo_random(static_cast<std::size_t>(state.range(0)));
  const Bytes key = pseudo_random(32);
  std::uint8_t mac[32];
  for (auto _ : state) {
    const hesai::HmacSha256Key k({key.data(), key.size()}, path);
    hesai::HmacSha256 h(k);
    h.update({data.data(), data.size()});
    h.finish(mac);
    benchmark::DoNotOptimize(mac);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

/// Per-packet HMAC with the key prepared once (what the decoder does).
void BM_HmacPrepared(benchmark::State& state, hesai::Sha256Path path) {
  const Bytes data = pseudo_random(static_cast<std::size_t>(state.range(0)));
  const Bytes key = pseudo_random(32);
  const hesai::HmacSha256Key k({key.data(), key.size()}, path);
  std::uint8_t mac[32];
  for (auto _ : state) {
    hesai::HmacSha256 h(k);
    h.update({data.data(), data.size()});
    h.finish(mac);
    benchmark::DoNotOptimize(mac);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

#ifdef HESAI_BENCH_OPENSSL
void BM_Sha256_openssl(benchmark::State& state) {
  const Bytes data = pseudo_random(static_cast<std::size_t>(state.range(0)));
  unsigned char digest[32];
  for (auto _ : state) {
    SHA256(data.data(), data.size(), digest);
    benchmark::DoNotOptimize(digest);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}

void BM_Hmac_openssl(benchmark::State& state) {
  const Bytes data = pseudo_random(static_cast<std::size_t>(state.range(0)));
  const Bytes key = pseudo_random(32);
  unsigned char mac[32];
  unsigned int len = 0;
  for (auto _ : state) {
    HMAC(EVP_sha256(), key.data(), static_cast<int>(key.size()), data.data(), data.size(), mac, &len);
    benchmark::DoNotOptimize(mac);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}
#endif

struct NamedModel {
  const char* name;
  hesai::Model model;
};
constexpr NamedModel kSensors[] = {{"Pandar40", hesai::Model::pandar40},
                                   {"Pandar40P", hesai::Model::pandar40p},
                                   {"Pandar64", hesai::Model::pandar64},
                                   {"QT128C2X", hesai::Model::qt128c2x},
                                   {"PandarQT64", hesai::Model::pandar_qt64},
                                   {"PandarXT16", hesai::Model::pandar_xt16},
                                   {"PandarXT32", hesai::Model::pandar_xt32},
                                   {"PandarXT32M2X", hesai::Model::pandar_xt32m2x}};

void register_all() {
  for (const NamedModel& s : kSensors) {
    const std::string n = s.name;
    benchmark::RegisterBenchmark(("BM_Baseline_copy_" + n).c_str(), BM_Copy, s.model);
    benchmark::RegisterBenchmark(("BM_Baseline_write_points_" + n).c_str(), BM_WritePoints, s.model, Floor::points);
    benchmark::RegisterBenchmark(("BM_Baseline_write_xyzt_" + n).c_str(), BM_WritePoints, s.model, Floor::xyzt);
    benchmark::RegisterBenchmark(("BM_Baseline_write_columns_" + n).c_str(), BM_WritePoints, s.model, Floor::columns);
    benchmark::RegisterBenchmark(("BM_" + n + "_validate").c_str(), BM_Decoder, s.model, Stage::validate);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode").c_str(), BM_Decoder, s.model, Stage::decode);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_nofiretime").c_str(), BM_Decoder, s.model,
                                 Stage::decode_nofiretime);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_rpm_changes").c_str(), BM_Decoder, s.model,
                                 Stage::decode_rpm_changes);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_columns").c_str(), BM_Decoder, s.model, Stage::decode_columns);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_columns_portable").c_str(), BM_Decoder, s.model,
                                 Stage::decode_columns_portable);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_columns_avx2").c_str(), BM_Decoder, s.model,
                                 Stage::decode_columns_avx2);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_portable").c_str(), BM_Decoder, s.model, Stage::decode_portable);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_avx2").c_str(), BM_Decoder, s.model, Stage::decode_avx2);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_scan").c_str(), BM_Decoder, s.model, Stage::decode_scan);
    benchmark::RegisterBenchmark(("BM_" + n + "_decode_scan_portable").c_str(), BM_Decoder, s.model,
                                 Stage::decode_scan_portable);
  }
  benchmark::RegisterBenchmark("BM_QT128C2X_decode_signed", BM_Decoder, hesai::Model::qt128c2x, Stage::decode_signed);
  // Frames (issue #43): a whole capture through decode() and the FrameAssembler, point by point
  // (the baseline) and by block; and the decode alone, which both include.
  for (const NamedModel& s : kSensors) {
    if (s.model != hesai::Model::pandar64 && s.model != hesai::Model::qt128c2x && s.model != hesai::Model::pandar40p) continue;
    const std::string n = s.name;
    benchmark::RegisterBenchmark(("BM_Baseline_frames_decode_" + n).c_str(), BM_Frames, s.model, Frames::decode_only);
    benchmark::RegisterBenchmark(("BM_Baseline_frames_per_point_" + n).c_str(), BM_Frames, s.model, Frames::per_point);
    benchmark::RegisterBenchmark(("BM_" + n + "_frames_by_block").c_str(), BM_Frames, s.model, Frames::by_block);
  }

  const struct {
    const char* name;
    hesai::CrcPath path;
  } crcs[] = {{"bitwise", hesai::CrcPath::bitwise},
              {"table", hesai::CrcPath::table},
              {"slicing", hesai::CrcPath::slicing},
              {"hardware", hesai::CrcPath::hardware},
              {"hardware_128", hesai::CrcPath::hardware_128}};
  for (const auto& c : crcs)
    benchmark::RegisterBenchmark((std::string("BM_CRC32_") + c.name).c_str(), BM_Crc, c.path)
        ->Arg(1028)
        ->Arg(64 * 1024);

  const std::int64_t n = static_cast<std::int64_t>(kSignedBytes);
  benchmark::RegisterBenchmark("BM_SHA256_portable", BM_Sha256, hesai::Sha256Path::portable)->Arg(n);
  benchmark::RegisterBenchmark("BM_SHA256_hardware", BM_Sha256, hesai::Sha256Path::hardware)->Arg(n);
  benchmark::RegisterBenchmark("BM_HMAC_SHA256_portable", BM_Hmac, hesai::Sha256Path::portable)->Arg(n);
  benchmark::RegisterBenchmark("BM_HMAC_SHA256_hardware", BM_Hmac, hesai::Sha256Path::hardware)->Arg(n);
  benchmark::RegisterBenchmark("BM_HMAC_SHA256_prepared_portable", BM_HmacPrepared, hesai::Sha256Path::portable)->Arg(n);
  benchmark::RegisterBenchmark("BM_HMAC_SHA256_prepared_hardware", BM_HmacPrepared, hesai::Sha256Path::hardware)->Arg(n);
#ifdef HESAI_BENCH_OPENSSL
  benchmark::RegisterBenchmark("BM_SHA256_openssl", BM_Sha256_openssl)->Arg(n);
  benchmark::RegisterBenchmark("BM_HMAC_SHA256_openssl", BM_Hmac_openssl)->Arg(n);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("crc32_hardware", hesai::crc32_hardware_available() ? "yes" : "no");
  benchmark::AddCustomContext("sha256_hardware", hesai::sha256_hardware_available() ? "yes" : "no");
  benchmark::AddCustomContext("decode_simd", hesai::decode_simd_name());
  benchmark::AddCustomContext("crc32_ieee", hesai::port::crc32_ieee_path_name(hesai::port::crc32_ieee_best_path()));
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
