#include "hesai/health.h"

#include <cstddef>

#include "hesai/model.h"

namespace hesai {

namespace {
constexpr std::int64_t kHourNs = 3600LL * 1000000000;
constexpr std::int64_t kTurn = 36000;  // 0.01 degree

void bump(std::uint64_t& counter) { saturating_increment(counter); }
void take_back(std::uint64_t& counter) { saturating_subtract(counter, 1); }

// round(a / b) for a >= 0, b > 0.
constexpr std::int64_t div_round(std::int64_t a, std::int64_t b) { return (a + b / 2) / b; }

bool is_virtual(const PacketInfo& info) {
  return info.time_reference == TimeReference::utc && info.time_ns >= kVirtualClockStartNs &&
         info.time_ns < kVirtualClockEndNs;
}

// The firings per packet, blocks / returns; 0 when they do not divide or the model has no facts.
std::uint8_t firings_per_packet(const PacketInfo& info) {
  if (info.returns == 0 || info.blocks == 0 || info.blocks % info.returns != 0) return 0;
  if (model_facts::of(info.model).firings == 0) return 0;
  return static_cast<std::uint8_t>(info.blocks / info.returns);
}

// The arithmetic of one comparison: the model's N, the packet's F and the two motor speeds.
struct Pace {
  std::int64_t n;         // firings per rotation at 600 rpm
  std::int64_t f;         // firings per packet
  std::int64_t rpm_sum;   // the two packets' rpm added (0: no usable rate)

  // Packets in a time move dt >= 0: round(dt N / (F 10^8)).
  std::int64_t by_time(std::int64_t dt) const { return div_round(dt * n, f * 100000000); }
  // N x the azimuth step of a packet, 0.01 degree: F x 60 x (rpm_sum / 2).
  std::int64_t step_n() const { return f * 30 * rpm_sum; }
  // Packets in an azimuth move of `move` (0.01 degree, either sign), rounded half away from 0.
  std::int64_t by_azimuth(std::int64_t move) const {
    const std::int64_t k = div_round((move < 0 ? -move : move) * n, step_n());
    return move < 0 ? -k : k;
  }
  // Whether k packets agree with a move of `move` (0.01 degree, [0, a turn)), modulo a turn.
  bool agrees(std::int64_t k, std::int64_t move) const {
    const std::int64_t turn_n = kTurn * n;
    const std::int64_t predicted_n = k * step_n();
    const std::int64_t tolerance_n = step_n() / 2 + predicted_n / 32;
    if (tolerance_n >= turn_n / 2) return true;
    std::int64_t off = (move * n - predicted_n) % turn_n;  // (-turn, turn)
    if (off < 0) off += turn_n;
    if (off > turn_n / 2) off -= turn_n;
    return (off < 0 ? -off : off) <= tolerance_n;
  }
};

// Whether two motor speeds give a usable rate: both non-zero, within 1/16 of the larger.
bool rate_usable(std::uint16_t a, std::uint16_t b) {
  if (a == 0 || b == 0) return false;
  const std::uint32_t hi = a > b ? a : b, lo = a > b ? b : a;
  return (hi - lo) * 16 <= hi;
}

std::uint32_t clamp_k(std::int64_t k) {
  if (k < 1) return 1;
  return k > INT32_MAX ? static_cast<std::uint32_t>(INT32_MAX) : static_cast<std::uint32_t>(k);
}
}  // namespace

std::uint32_t HealthMonitor::advance(std::uint32_t k) noexcept {
  seen_.clear_after(newest_, k);
  newest_ += k;
  seen_.set(newest_);
  span_ = span_ + k < kHealthWindow ? span_ + k : kHealthWindow;
  saturating_add(counts_.lost, k - 1);
  return k - 1;
}

void HealthMonitor::late(std::uint32_t k_back) noexcept {
  bump(counts_.reordered);
  if (k_back >= kHealthWindow) return;  // too far behind to know: reordered only
  const std::uint32_t slot = newest_ - k_back;
  if (seen_.test(slot)) {
    take_back(counts_.reordered);
    bump(counts_.duplicates);
    return;
  }
  seen_.set(slot);
  if (k_back < span_) take_back(counts_.lost);  // counted lost when it was skipped
}

void HealthMonitor::observe_units(const UnitScan& scan) noexcept {
  saturating_add(counts_.duplicate_returns, scan.duplicate_returns);
  saturating_add(counts_.beyond_rated_range, scan.beyond_rated_range);
  if (scan.blockage_units == 0) return;
  saturating_add(counts_.blockage_units, scan.blockage_units);
  for (std::size_t ch = 0; ch < kMaxChannels; ++ch) saturating_add(counts_.blockage_by_channel[ch], scan.blockage_by_channel[ch]);
}

void HealthMonitor::take_back_lost(std::uint64_t n) noexcept { saturating_subtract(counts_.lost, n); }

std::uint32_t HealthMonitor::fov_rule(std::uint32_t lost, std::uint16_t from, std::uint16_t to,
                                      std::uint32_t tolerance) noexcept {
  const auto near = [tolerance](std::uint16_t a, std::uint16_t b) {
    std::int32_t d = static_cast<std::int32_t>(a) - b;
    if (d < 0) d = -d;
    if (d > kTurn / 2) d = static_cast<std::int32_t>(kTurn) - d;
    return static_cast<std::uint32_t>(d) <= tolerance;
  };
  bool fov = counts_.fov_gap && near(from, counts_.fov_gap_from) && near(to, counts_.fov_gap_to);
  for (Gap& g : gaps_) {
    if (fov || g.lost == 0 || !near(from, g.from) || !near(to, g.to)) continue;
    take_back_lost(g.lost);  // its first occurrence, counted then
    g.lost = 0;
    fov = true;
  }
  if (fov) {
    take_back_lost(lost);
    counts_.fov_gap = true;
    counts_.fov_gap_from = from;
    counts_.fov_gap_to = to;
    return 0;
  }
  gaps_[next_gap_] = Gap{from, to, lost};
  next_gap_ = static_cast<std::uint8_t>((next_gap_ + 1) % kHealthGaps);
  return lost;
}

void HealthMonitor::restart(const PacketInfo& info) noexcept {
  model_ = info.model;
  firings_ = firings_per_packet(info);
  reference_ = info.time_reference;
}

std::uint32_t HealthMonitor::observe(const PacketInfo& info) noexcept {
  bump(counts_.packets);
  if (is_virtual(info)) bump(counts_.time_virtual);
  const std::uint16_t azimuth = static_cast<std::uint16_t>(info.block_azimuth[0] % kTurn);
  std::uint32_t k = 1;
  bool trusted = true;  // this packet's time becomes the base of the next comparisons
  if (!started_) {
    started_ = true;
    restart(info);
    newest_ = 0;
    span_ = 1;
    seen_.clear();
    seen_.set(0);
    trusted_slot_ = 0;
    trusted_ns_ = info.time_ns;
    time_ns_ = info.time_ns;
    azimuth_ = azimuth;
    rpm_ = info.motor_rpm;
    return 0;
  }
  if (info.model != model_ || firings_per_packet(info) != firings_ || info.time_reference != reference_) {
    restart(info);  // nothing to compare with: 1 ahead
  } else {
    std::int64_t dt = info.time_ns - time_ns_;
    std::int64_t dt_trusted = info.time_ns - trusted_ns_;
    if (reference_ == TimeReference::hour_relative) {  // modulo the hour, into [-half, half)
      auto fold = [](std::int64_t d) {
        d %= kHourNs;
        if (d >= kHourNs / 2) d -= kHourNs;
        if (d < -kHourNs / 2) d += kHourNs;
        return d;
      };
      dt = fold(dt);
      dt_trusted = fold(dt_trusted);
    }
    std::int64_t da = static_cast<std::int64_t>(azimuth) - azimuth_;
    if (rotation_ == Rotation::counterclockwise) da = -da;
    if (da < 0) da += kTurn;                                 // [0, a turn)
    const std::int64_t move = da < kTurn / 2 ? da : da - kTurn;  // [-half, half)
    const bool usable = firings_ != 0 && rate_usable(info.motor_rpm, rpm_);
    const Pace pace{static_cast<std::int64_t>(model_facts::of(model_).firings), firings_,
                    usable ? static_cast<std::int64_t>(info.motor_rpm) + rpm_ : 0};

    if (dt == 0 && move == 0) {  // a copy of the newest packet
      bump(counts_.duplicates);
      return 0;
    }
    if (dt <= 0) {
      const std::int64_t back_a = usable ? -pace.by_azimuth(move) : 0;
      if (back_a >= 1) {  // behind in azimuth: a late packet
        const std::int64_t back_t = dt < 0 ? pace.by_time(-dt) : 0;
        const std::int64_t back = back_t >= 1 && pace.agrees(back_t, -move) ? back_t : back_a;
        late(back > INT32_MAX ? static_cast<std::uint32_t>(INT32_MAX) : static_cast<std::uint32_t>(back));
        return 0;
      }
      bump(counts_.time_stalls);
      trusted = false;
      k = usable ? clamp_k(pace.by_azimuth(move)) : 1;
    } else if (dt > kHealthMaxGapNs) {
      bump(counts_.time_jumps);
      k = usable ? clamp_k(pace.by_azimuth(move)) : 1;
    } else if (firings_ == 0) {
      k = 1;
    } else {
      const std::int64_t k_t = pace.by_time(dt);
      const std::int64_t since = static_cast<std::int64_t>(newest_ - trusted_slot_);  // slots since the trusted packet
      const std::int64_t k_trusted =
          dt_trusted > 0 && dt_trusted <= kHealthMaxGapNs ? pace.by_time(dt_trusted) - since : 0;
      if (!usable) {
        k = clamp_k(since > 0 ? k_trusted : k_t);  // the time alone, from the last packet whose time held
      } else if (k_t >= 1 && pace.agrees(k_t, da)) {
        k = clamp_k(k_t);
      } else if (since > 0 && k_trusted >= 1 && pace.agrees(k_trusted, da)) {
        k = clamp_k(k_trusted);
      } else {
        bump(counts_.time_jumps);
        k = clamp_k(pace.by_azimuth(move));
      }
    }
  }
  std::uint32_t lost = advance(k);
  if (lost != 0) {
    // The FOV rule's tolerance: 3 azimuth steps at the packet's rate, else 3 degrees.
    const std::uint8_t f = firings_per_packet(info);
    const std::uint32_t n = model_facts::of(info.model).firings;
    const std::uint32_t tolerance =
        f != 0 && n != 0 && rate_usable(info.motor_rpm, rpm_) ? 3u * f * 60u * info.motor_rpm / n : 300u;
    lost = fov_rule(lost, azimuth_, azimuth, tolerance);
  }
  time_ns_ = info.time_ns;
  azimuth_ = azimuth;
  rpm_ = info.motor_rpm;
  if (trusted) {
    trusted_ns_ = info.time_ns;
    trusted_slot_ = newest_;
  }
  return lost;
}

}  // namespace hesai
