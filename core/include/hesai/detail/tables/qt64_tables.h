// PandarQT64 design tables: channel angles, firing times and block start times.
// No manual for this model is among the seeds; every value comes from the vendor's
// HesaiLidar_SDK_2.0 (ea7f86f), as cited per table. Floats, not doubles: the tables are read once,
// by the Decoder constructor, into float geometry, and a firmware image keeps them in flash.
#pragma once

#include <array>
#include <cstddef>

#include "hesai/detail/tables/block_times.h"

namespace hesai::tables {

/// Number of channels (lasers) of the PandarQT64.
inline constexpr std::size_t qt64_channel_count = 64;

/// Elevation and azimuth offset of each channel, degrees, index = channel - 1 (channel 1 looks
/// down most). Source: the vendor SDK's correction/angle_correction/"PandarQT_Angle Correction
/// File.csv", the model's file the SDK ships (no other design table is published). It holds the
/// same numbers as the bundled unit's data/calibration/pandar_qt64_angles.csv (nebula's
/// calibration/PandarQT64.csv); a unit's own file overrides them (Decoder::set_angles).
inline constexpr std::array<float, 64> qt64_elevation_deg = {{
    -52.121f,  //  1
    -49.785f,  //  2
    -47.577f,  //  3
    -45.477f,  //  4
    -43.465f,  //  5
    -41.528f,  //  6
    -39.653f,  //  7
    -37.831f,  //  8
    -36.055f,  //  9
    -34.32f,  // 10
    -32.619f,  // 11
    -30.95f,  // 12
    -29.308f,  // 13
    -27.69f,  // 14
    -26.094f,  // 15
    -24.517f,  // 16
    -22.964f,  // 17
    -21.42f,  // 18
    -19.889f,  // 19
    -18.372f,  // 20
    -16.865f,  // 21
    -15.368f,  // 22
    -13.88f,  // 23
    -12.399f,  // 24
    -10.925f,  // 25
    -9.457f,  // 26
    -7.994f,  // 27
    -6.535f,  // 28
    -5.079f,  // 29
    -3.626f,  // 30
    -2.175f,  // 31
    -0.725f,  // 32
    0.725f,  // 33
    2.175f,  // 34
    3.626f,  // 35
    5.079f,  // 36
    6.534f,  // 37
    7.993f,  // 38
    9.456f,  // 39
    10.923f,  // 40
    12.397f,  // 41
    13.877f,  // 42
    15.365f,  // 43
    16.861f,  // 44
    18.368f,  // 45
    19.885f,  // 46
    21.415f,  // 47
    22.959f,  // 48
    24.524f,  // 49
    26.101f,  // 50
    27.697f,  // 51
    29.315f,  // 52
    30.957f,  // 53
    32.627f,  // 54
    34.328f,  // 55
    36.064f,  // 56
    37.84f,  // 57
    39.662f,  // 58
    41.537f,  // 59
    43.475f,  // 60
    45.487f,  // 61
    47.587f,  // 62
    49.795f,  // 63
    52.133f,  // 64
}};
inline constexpr std::array<float, 64> qt64_azimuth_deg = {{
    8.736f,  //  1
    8.314f,  //  2
    7.964f,  //  3
    7.669f,  //  4
    7.417f,  //  5
    7.198f,  //  6
    7.007f,  //  7
    6.838f,  //  8
    6.688f,  //  9
    6.554f,  // 10
    6.434f,  // 11
    6.326f,  // 12
    6.228f,  // 13
    6.14f,  // 14
    6.059f,  // 15
    5.987f,  // 16
    -5.27f,  // 17
    -5.216f,  // 18
    -5.167f,  // 19
    -5.123f,  // 20
    -5.083f,  // 21
    -5.047f,  // 22
    -5.016f,  // 23
    -4.988f,  // 24
    -4.963f,  // 25
    -4.942f,  // 26
    -4.924f,  // 27
    -4.91f,  // 28
    -4.898f,  // 29
    -4.889f,  // 30
    -4.884f,  // 31
    -4.881f,  // 32
    5.493f,  // 33
    5.496f,  // 34
    5.502f,  // 35
    5.512f,  // 36
    5.525f,  // 37
    5.541f,  // 38
    5.561f,  // 39
    5.584f,  // 40
    5.611f,  // 41
    5.642f,  // 42
    5.676f,  // 43
    5.716f,  // 44
    5.759f,  // 45
    5.808f,  // 46
    5.862f,  // 47
    5.921f,  // 48
    -5.33f,  // 49
    -5.396f,  // 50
    -5.469f,  // 51
    -5.55f,  // 52
    -5.64f,  // 53
    -5.74f,  // 54
    -5.85f,  // 55
    -5.974f,  // 56
    -6.113f,  // 57
    -6.269f,  // 58
    -6.447f,  // 59
    -6.651f,  // 60
    -6.887f,  // 61
    -7.163f,  // 62
    -7.493f,  // 63
    -7.892f,  // 64
}};
static_assert(qt64_elevation_deg.size() == qt64_channel_count && qt64_azimuth_deg.size() == qt64_channel_count);

/// Firing time of each channel after its block's start, us, index = channel - 1. Source: the
/// vendor SDK's correction/firetime_correction/"PandarQT_Firetime Correction File.csv" (one
/// firing sequence; bundled as data/calibration/pandar_qt64_firetimes.csv). The SDK adds it to the
/// block start (udp3_1_parser.cc). nebula's pandar_qt64.hpp lists these times plus 10 us (and
/// 12.96 us for channel 56, where the sequence implies 129.60): the vendor's file is followed here.
inline constexpr std::array<float, 64> qt64_firetime_us = {{
    2.31f,  //  1
    4.37f,  //  2
    6.43f,  //  3
    8.49f,  //  4
    10.54f,  //  5
    12.6f,  //  6
    14.66f,  //  7
    16.71f,  //  8
    19.16f,  //  9
    21.22f,  // 10
    23.28f,  // 11
    25.34f,  // 12
    27.39f,  // 13
    29.45f,  // 14
    31.5f,  // 15
    33.56f,  // 16
    36.61f,  // 17
    38.67f,  // 18
    40.73f,  // 19
    42.78f,  // 20
    44.84f,  // 21
    46.9f,  // 22
    48.95f,  // 23
    51.01f,  // 24
    53.45f,  // 25
    55.52f,  // 26
    57.58f,  // 27
    59.63f,  // 28
    61.69f,  // 29
    63.74f,  // 30
    65.8f,  // 31
    67.86f,  // 32
    70.9f,  // 33
    72.97f,  // 34
    75.02f,  // 35
    77.08f,  // 36
    79.14f,  // 37
    81.19f,  // 38
    83.25f,  // 39
    85.3f,  // 40
    87.75f,  // 41
    89.82f,  // 42
    91.87f,  // 43
    93.93f,  // 44
    95.98f,  // 45
    98.04f,  // 46
    100.1f,  // 47
    102.15f,  // 48
    105.2f,  // 49
    107.26f,  // 50
    109.32f,  // 51
    111.38f,  // 52
    113.43f,  // 53
    115.49f,  // 54
    117.54f,  // 55
    119.6f,  // 56
    122.05f,  // 57
    124.11f,  // 58
    126.17f,  // 59
    128.22f,  // 60
    130.28f,  // 61
    132.34f,  // 62
    134.39f,  // 63
    136.45f,  // 64
}};
static_assert(qt64_firetime_us.size() == qt64_channel_count);

// ---- Block start times ---------------------------------------------------------------------
// Source: the vendor SDK's udp_protocol_v3_1.h (PandarQT_BLOCK_NS_OFFSET1 = 25 710 ns,
// PandarQT_BLOCK_NS_OFFSET2 = {0, 166 670, 333 330, 500 000} ns) and udp3_1_parser.cc: firing k
// of a packet starts at t0 + 25.71 + OFFSET2[k] us, k = block in single return, block / 2 in
// dual return (the two blocks of a firing share its time). nebula's pandar_qt64.hpp gives the
// same: 25 710 + 500 000 x k / 3 ns. t0 = date-time + timestamp.

/// Start of the first firing after t0, in us (PandarQT64).
inline constexpr double qt64_first_block_start_us = 25.71;
/// Start of firing k (0..3) after the first, us: the SDK's table (a firing every 166.67 us).
inline constexpr std::array<double, 4> qt64_firing_start_us = {0.0, 166.67, 333.33, 500.0};

/// Start time of block `block` (1..4) relative to t0, in us (PandarQT64). The caller keeps
/// `block` in 1..4.
constexpr double qt64_block_start_us(std::size_t block, bool dual) {
  return qt64_first_block_start_us + qt64_firing_start_us[dual ? (block - 1) / 2 : block - 1];
}
inline constexpr std::array<double, 4> qt64_block_start_us_single = detail::block_times<4>(qt64_block_start_us, false);
inline constexpr std::array<double, 4> qt64_block_start_us_dual = detail::block_times<4>(qt64_block_start_us, true);

}  // namespace hesai::tables
