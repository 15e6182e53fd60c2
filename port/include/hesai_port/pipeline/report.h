// Printing the counters of a run: one JSON object with the contract's keys, or a text summary.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "hesai_port/pipeline/pipeline.h"

namespace hesai::port {

/// One JSON object with exactly the keys packets, models, points, frames, crc_errors,
/// signature_valid, signature_invalid, signature_missing, unsigned_accepted, unsigned_rejected,
/// signature_unverified, replayed, malformed,
/// unsupported, lost, duplicates, reordered, sequence_resyncs, lost_by ("udp_sequence",
/// "azimuth_time", "mixed" or "none"), time_stalls, time_virtual, time_jumps, blockage_units,
/// blockage_by_channel (an array, channel - 1, as long as the most channels of the models seen),
/// duplicate_returns, beyond_rated_range, fov_gap_deg ([start, end] degrees or null), ip_fragments,
/// gps_packets, first_time_ns,
/// last_time_ns, high_temperature, gps_unlocked, gps_position_invalid, fs_packets, fs_states (an
/// object keyed by lidar_state_name(), all eight states), fs_current_fault, fs_past_fault,
/// fs_reserved_fault_type, fs_last_fault_code, fs_last_fault_id, fs_last_fault_total,
/// fs_counter_stalls.
/// With more than one sensor in `sensors`, also "sensors": an array of one object per sensor (in
/// the order they first sent) with source, model, packets, lost, lost_by, time_stalls,
/// time_virtual, time_jumps, blockage_units, blockage_by_channel (its model's channels),
/// duplicate_returns, beyond_rated_range, fov_gap_deg.
std::string stats_json(const Stats& s, const std::vector<SensorReport>& sensors = {});
/// A readable summary: the same counters, times as UTC, spin rate, return mode, rejections.
std::string stats_text(const Pipeline& p);
/// "2024-05-17T08:30:15.250000000Z".
std::string utc_string(std::int64_t ns);

}  // namespace hesai::port
