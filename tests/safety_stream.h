// Test-only: a QT128 functional-safety stream built from the bundled capture's packets, byte for
// byte, with every lidar state, current, past and reserved fault types, a stalled rolling counter
// and a hold just short of a stall; and what it must count, derived while building it.
//
// Functional-safety layout (QT128C2X manual, Section 3.1.2 "UDP Data", table "Functional Safety:
// 17 bytes"), typed in here: byte 0 FS version; byte 1 lidar state [7:5], fault code type [4:3]
// (b-01 current, b-10 past), rolling counter [2:0]; byte 2 total fault code num [7:4], fault code
// ID [3:0]; bytes 3-4 outgoing fault code (u16 LE); 8 reserved; CRC2 over bytes 1..12.
#pragma once

#include <cstdint>
#include <vector>

#include "hesai/bytes.h"
#include "packet_builder.h"
#include "test_support.h"

namespace hesai_test {

/// Where the bundled QT128 capture's packets (flags 0x1D) hold their sections.
inline constexpr std::size_t kQtFs = 1044;    ///< functional safety
inline constexpr std::size_t kQtTail = 1061;  ///< tail
inline constexpr std::int64_t kStallLimitNs = 20000000;  ///< the issue's 20 ms of packet time

/// A QT128 packet's time from its own bytes: the tail's date-time (year - 1900, month, day,
/// hour, minute, second at tail + 15) plus its timestamp (u32 us at tail + 21), in ns.
inline std::int64_t qt128_raw_time_ns(const std::vector<std::uint8_t>& p) {
  const std::uint8_t* d = &p[kQtTail + 15];
  return timegm_utc(1900 + d[0], d[1], d[2], d[3], d[4], d[5]) * 1000000000 +
         static_cast<std::int64_t>(hesai::load_le32(&p[kQtTail + 21])) * 1000;
}

/// One packet's functional-safety fields.
struct FsFields {
  std::uint8_t state = 0, fault_type = 0, counter = 0, total = 0, id = 0;
  std::uint16_t code = 0;
};

/// Writes the fields into a bundled QT128 packet and re-seals its CRCs (CRC2 covers them).
inline void qt128_set_fs(std::vector<std::uint8_t>& p, const FsFields& f) {
  p[kQtFs + 1] = static_cast<std::uint8_t>(f.state << 5 | f.fault_type << 3 | f.counter);
  p[kQtFs + 2] = static_cast<std::uint8_t>(f.total << 4 | f.id);
  hesai::store_le16(&p[kQtFs + 3], f.code);
  qt128_seal(p);
}

/// What the built stream must count.
struct SafetyExpect {
  std::uint64_t packets = 0;
  std::uint64_t states[8] = {};
  std::uint64_t current = 0, past = 0, reserved = 0, stalls = 0;
  std::uint16_t last_code = 0;
  std::uint8_t last_id = 0, last_total = 0;
  std::int64_t longest_hold_ns = 0;  ///< the stalled hold's span
  std::int64_t short_hold_ns = 0;    ///< the hold that must not count: the longest span <= 20 ms
};

struct SafetyStream {
  std::vector<std::vector<std::uint8_t>> packets;
  SafetyExpect expect;
};

/// The bundled capture's 1800 packets (about 200 ms at 111 us each), rewritten:
/// - lidar state k / 225: 225 packets in each of the eight states, in order;
/// - the rolling counter steps by 1 every 45 packets (about 5 ms), by 3 at every tenth step (the
///   capture shows both), and at the start and after the end of two holds: from packet 300 it
///   holds while the packet times stay within 30 ms of packet 300's (a stall: more than 20 ms,
///   counted once however many packets it lasts); from packet 1000 while they stay within 20 ms
///   (the longest hold that is not a stall);
/// - a current fault every 100 packets (k % 100 == 7), a past fault at k % 100 == 57, the
///   reserved type b-11 at k % 450 == 99; queue position and length and code vary with k.
/// The stall count is derived from the built counter values: a run of one value whose packet
/// times span more than 20 ms is one stall.
inline SafetyStream build_safety_stream() {
  SafetyStream s;
  s.packets = pcap_payloads("qt128c2x_dual.pcap");
  const std::size_t n = s.packets.size();
  if (n != 1800) {  // the holds below need the whole capture
    ADD_FAILURE() << "qt128c2x_dual.pcap: " << n << " packets, expected 1800";
    s.packets.clear();
    return s;
  }
  std::vector<std::int64_t> t(n);
  for (std::size_t k = 0; k < n; ++k) t[k] = qt128_raw_time_ns(s.packets[k]);
  // The two holds: [start, last packet within `span` of the start].
  auto hold_end = [&](std::size_t start, std::int64_t span) {
    std::size_t k = start;
    while (k + 1 < n && t[k + 1] - t[start] <= span) ++k;
    return k;
  };
  const std::size_t stall_from = 300, stall_to = hold_end(stall_from, 30000000);
  const std::size_t short_from = 1000, short_to = hold_end(short_from, kStallLimitNs);
  SafetyExpect& e = s.expect;
  e.longest_hold_ns = t[stall_to] - t[stall_from];
  e.short_hold_ns = t[short_to] - t[short_from];

  std::uint8_t counter = 0;
  unsigned steps = 0;
  std::size_t run_start = 0;  // first packet of the current counter value
  for (std::size_t k = 0; k < n; ++k) {
    const bool inside_hold = (k > stall_from && k <= stall_to) || (k > short_from && k <= short_to);
    const bool change = k == stall_from || k == short_from || k == stall_to + 1 || k == short_to + 1 ||
                        (k % 45 == 0 && !inside_hold);
    if (k > 0 && change) {
      if (t[k - 1] - t[run_start] > kStallLimitNs) ++e.stalls;  // the run that ends here
      ++steps;
      counter = static_cast<std::uint8_t>((counter + (steps % 10 == 0 ? 3 : 1)) % 8);
      run_start = k;
    }
    FsFields f;
    f.state = static_cast<std::uint8_t>(k / 225 % 8);
    f.counter = counter;
    if (k % 100 == 7 || k % 100 == 57) {
      f.fault_type = k % 100 == 7 ? 1 : 2;
      f.total = static_cast<std::uint8_t>(k / 100 % 15 + 1);
      f.id = static_cast<std::uint8_t>(k / 50 % f.total + 1);
      f.code = static_cast<std::uint16_t>(0x1000 + k);
      ++(f.fault_type == 1 ? e.current : e.past);
      e.last_code = f.code;
      e.last_id = f.id;
      e.last_total = f.total;
    } else if (k % 450 == 99) {
      f.fault_type = 3;
      f.code = 0xBEEF;  // neither current nor past: not a last fault code
      ++e.reserved;
    }
    ++e.states[f.state];
    ++e.packets;
    qt128_set_fs(s.packets[k], f);
  }
  if (t[n - 1] - t[run_start] > kStallLimitNs) ++e.stalls;
  return s;
}

}  // namespace hesai_test
