// Integrity counters of a decoding run: a plain aggregate the caller fills and prints.
#pragma once

#include <array>
#include <cstdint>

#include "hesai/decoder.h"
#include "hesai/error.h"
#include "hesai/gps.h"
#include "hesai/health.h"
#include "hesai/model.h"
#include "hesai/safety.h"

namespace hesai {

/// Which method counted the losses of a run: a bit per method, so that a run of several sensors
/// shows both when their packets differ.
enum class LostBy : std::uint8_t {
  none = 0,          ///< no point-cloud packet yet
  udp_sequence = 1,  ///< the packets' UDP sequence numbers (SequenceTracker)
  azimuth_time = 2,  ///< the block azimuth and the packet time (HealthMonitor): packets without a sequence
  mixed = 3,         ///< some sensors one way, some the other
};
/// `lost_by` with `method` added.
constexpr LostBy operator|(LostBy a, LostBy b) {
  return static_cast<LostBy>(static_cast<std::uint8_t>(a) | static_cast<std::uint8_t>(b));
}
/// "none", "udp_sequence", "azimuth_time", "mixed".
const char* lost_by_name(LostBy by) noexcept;

/// Counters of a run. Each rejected packet counts under the first check it failed (count_error).
/// Every counter saturates at its largest value (hesai/saturating.h); none wraps.
struct Stats {
  std::uint64_t packets = 0;               ///< UDP payloads examined
  std::uint64_t points = 0;                ///< points decoded
  std::uint64_t frames = 0;                ///< frames (rotations) closed
  std::uint64_t crc_errors = 0;            ///< QT128 CRC1, CRC2 or CRC3 mismatch
  std::uint64_t signature_valid = 0;       ///< HMAC-SHA256 verified
  std::uint64_t signature_invalid = 0;     ///< HMAC-SHA256 mismatch
  std::uint64_t signature_missing = 0;     ///< a key is configured, the packet is unsigned:
                                           ///< unsigned_accepted + unsigned_rejected
  std::uint64_t unsigned_accepted = 0;     ///< of those, accepted (allowed unsigned: --allow-unsigned,
                                           ///< or received before a live session's key was agreed)
  std::uint64_t unsigned_rejected = 0;     ///< of those, rejected (Error::signature_missing)
  std::uint64_t signature_unverified = 0;  ///< signed, but no key configured
  std::uint64_t replayed = 0;              ///< validly signed, but not new in its session (ReplayGuard):
                                           ///< refused, not counted in signature_valid, none of its points kept
  std::uint64_t malformed = 0;             ///< every other rejection (length, magic, fields...)
  std::uint64_t unsupported = 0;           ///< a version, model or section we do not implement, or
                                           ///< customised QT128 channels without a matching configuration
  std::uint64_t lost = 0;                  ///< packets never seen: UDP sequence numbers (SequenceTracker) where
                                           ///< the packets carry one, else by block azimuth and time (HealthMonitor)
  std::uint64_t duplicates = 0;            ///< packets seen again (by the same method as `lost`)
  std::uint64_t reordered = 0;             ///< packets that arrived after a later one (by the same method as `lost`)
  std::uint64_t sequence_resyncs = 0;      ///< sequence series restarts: a sensor restart, or a loss
                                           ///< longer than kSequenceWindow (not counted in `lost`)
  LostBy lost_by = LostBy::none;           ///< which method counted `lost` (and duplicates, reordered)
  std::uint64_t time_stalls = 0;           ///< HealthCounts::time_stalls, every sensor summed
  std::uint64_t time_virtual = 0;          ///< HealthCounts::time_virtual: packets dated in 2000, the free-run clock
  std::uint64_t time_jumps = 0;            ///< HealthCounts::time_jumps: clock steps
  std::uint64_t blockage_units = 0;        ///< UnitScan::blockage_units summed: QT128C2X distance-1 markers
  std::array<std::uint32_t, kMaxChannels> blockage_by_channel{};  ///< the same per channel - 1 (saturating)
  std::uint64_t duplicate_returns = 0;     ///< UnitScan::duplicate_returns summed: one echo sent as both returns
  std::uint64_t beyond_rated_range = 0;    ///< UnitScan::beyond_rated_range summed: points beyond rated_range_m()
  bool fov_gap = false;                    ///< HealthCounts::fov_gap of the first sensor that showed one
  std::uint16_t fov_gap_from = 0;          ///< its edges, 0.01 degree, in the direction of rotation
  std::uint16_t fov_gap_to = 0;
  std::uint64_t ip_fragments = 0;          ///< IP fragments a capture reader skipped (set by the port: not reassembled)
  std::uint64_t gps_packets = 0;           ///< GPS packets (512 bytes)
  std::int64_t first_time_ns = 0;          ///< packet time of the first packet, ns (0: none yet)
  std::int64_t last_time_ns = 0;           ///< packet time of the last packet, ns (0: none yet)
  std::array<std::uint64_t, kModelCount> models{};  ///< point-cloud packets per hesai::Model
  std::uint16_t spin_rpm_last = 0;         ///< motor speed of the last packet, rpm
  std::uint8_t return_mode_last = 0;       ///< return-mode byte of the last packet
  // What the sensors report about themselves (count_status, count_gps, count_safety).
  std::uint64_t high_temperature = 0;      ///< Pandar40/40P/64 packets with the high-temperature shutdown flag set
  std::uint64_t gps_unlocked = 0;          ///< GPS packets with PPS unlocked or NMEA unlocked (gps_unlocked())
  std::uint64_t gps_position_invalid = 0;  ///< GPS packets whose positioning status says no valid position
  SafetyCounts safety;                     ///< QT128 functional safety, every sensor's sections summed
};

/// Adds one to the counter of a rejection: crc_body, crc_functional_safety, crc_tail ->
/// crc_errors; signature_invalid -> signature_invalid; signature_missing -> signature_missing and
/// unsigned_rejected;
/// unsupported_version, unsupported_model, unsupported_section, channel_config_required,
/// channel_config_mismatch -> unsupported; any other code
/// -> malformed. Error::ok counts nothing. Touches no other counter (not `packets`).
void count_error(Stats& stats, Error error) noexcept;

/// The status fields of a decoded point-cloud packet: high_temperature + 1 when its
/// high-temperature shutdown flag is set (any non-zero byte; the manuals define 0x01).
void count_status(Stats& stats, const PacketInfo& info) noexcept;

/// True when a GPS packet says its time source is not locked: the PPS lock flag is 0, or the
/// positioning status byte is NUL, which the Pandar64 manual (Section 3.2.2.1, GPRMC field <02>)
/// defines as "GPS unlocked". 'V' (void position) and a GPGGA fix quality of '0' describe the
/// position, not the lock: NMEA is locked once a valid sentence arrives (Pandar64 manual Section 4.1).
bool gps_unlocked(const GpsPacket& gps) noexcept;

/// True when the positioning status byte says the position is not valid: 'V' (GPRMC "Void",
/// Pandar40 manual Table 3.6 "V=invalid", Pandar64 manual 3.2.2.1) or '0' (GPGGA fix quality
/// "Invalid", Pandar64 manual 3.2.2.2).
bool gps_position_invalid(const GpsPacket& gps) noexcept;

/// A parsed GPS packet: gps_packets + 1; gps_unlocked + 1 when gps_unlocked(gps);
/// gps_position_invalid + 1 when gps_position_invalid(gps).
void count_gps(Stats& stats, const GpsPacket& gps) noexcept;

/// Adds one to models[model]; a value outside hesai::Model counts as Model::unknown.
void count_model(Stats& stats, Model model) noexcept;

}  // namespace hesai
