// PandarXT16, PandarXT32 and PandarXT32M2X design tables (point cloud protocol 6.1). No manual for
// these models is among the seeds; the sources are the vendor SDK (HesaiLidar_SDK_2.0, ea7f86f)
// and tier4/nebula (606ac41f), cited per table. Stored as float (the values have at most three
// decimals) to keep them small in a firmware image. A unit's own angle and firing-time files
// (data/calibration/pandar_xt*_{angles,firetimes}.csv) override them.
#pragma once

#include <array>
#include <cstddef>

namespace hesai::tables {

// ---- Design angles: elevation per channel, degrees, index = channel - 1 (channel 1 the top one).
// Every design azimuth offset is 0.

/// PandarXT16: 15 to -15 in steps of 2. Source: SDK correction/angle_correction/
/// "PandarXT-16_Angle Correction File.csv" (the vendor's generic file; all azimuths 0).
inline constexpr std::array<float, 16> xt16_elevation_deg = {
    15, 13, 11, 9, 7, 5, 3, 1, -1, -3, -5, -7, -9, -11, -13, -15};

/// PandarXT32: 15 to -16 in steps of 1. Source: SDK correction/angle_correction/
/// "PandarXT_Angle Correction File.csv" (the vendor's generic file; all azimuths 0).
inline constexpr std::array<float, 32> xt32_elevation_deg = {
    15, 14, 13, 12, 11, 10, 9,  8,  7,  6,  5,   4,   3,   2,   1,   0,
    -1, -2, -3, -4, -5, -6, -7, -8, -9, -10, -11, -12, -13, -14, -15, -16};

/// PandarXT32M2X: 19.5 to -20.8 in steps of 1.3. No generic file is published (the SDK's
/// "XT32M2X_Angle Correction File.csv" is one unit's measurement, azimuths 0.14..0.18); these are
/// the model's published vertical field of view and resolution: nebula pandar_xt32m.hpp, fov
/// -20.8..19.5 degrees and peak vertical resolution 1.3 degrees (the SDK's udp6_1_parser.cc frame
/// "remake" range, -20.8..19.5, agrees). Both units' files lie within 0.13 degrees of them.
inline constexpr std::array<float, 32> xt32m2x_elevation_deg = {
    19.5f, 18.2f, 16.9f, 15.6f, 14.3f, 13.0f, 11.7f, 10.4f, 9.1f,   7.8f,   6.5f,   5.2f,   3.9f,   2.6f,   1.3f,   0.0f,
    -1.3f, -2.6f, -3.9f, -5.2f, -6.5f, -7.8f, -9.1f, -10.4f, -11.7f, -13.0f, -14.3f, -15.6f, -16.9f, -18.2f, -19.5f, -20.8f};

// ---- Firing times: us after the start of the block's firing, index = channel - 1. Source: the
// SDK's correction/firetime_correction/ files named per table; nebula's pandar_xt16.hpp,
// pandar_xt32.hpp, pandar_xt32m.hpp give the same times (5632 + 368 + step x channel ns).

/// "PandarXT-16_Firetime Correction File.csv": 6 + 3.024 x (channel - 1).
inline constexpr std::array<float, 16> xt16_firetime_us = {
    6.0f,    9.024f,  12.048f, 15.072f, 18.096f, 21.12f,  24.144f, 27.168f,
    30.192f, 33.216f, 36.24f,  39.264f, 42.288f, 45.312f, 48.336f, 51.36f};

/// "PandarXT-32_Firetime Correction File.csv": 6 + 1.512 x (channel - 1).
inline constexpr std::array<float, 32> xt32_firetime_us = {
    6.0f,    7.512f,  9.024f,  10.536f, 12.048f, 13.56f,  15.072f, 16.584f, 18.096f, 19.608f, 21.12f,
    22.632f, 24.144f, 25.656f, 27.168f, 28.68f,  30.192f, 31.704f, 33.216f, 34.728f, 36.24f,  37.752f,
    39.264f, 40.776f, 42.288f, 43.8f,   45.312f, 46.824f, 48.336f, 49.848f, 51.36f,  52.872f};

/// "PandarXT-32M2X_Firetime Correction File.csv": channels n and n + 16 fire together, at
/// 6 + 2.888 x (n - 1) (nebula pandar_xt32m.hpp folds channel_id >= 16 the same way).
inline constexpr std::array<float, 32> xt32m2x_firetime_us = {
    6.0f,    8.888f,  11.776f, 14.664f, 17.552f, 20.44f,  23.328f, 26.216f,
    29.104f, 31.992f, 34.88f,  37.768f, 40.656f, 43.544f, 46.432f, 49.32f,
    6.0f,    8.888f,  11.776f, 14.664f, 17.552f, 20.44f,  23.328f, 26.216f,
    29.104f, 31.992f, 34.88f,  37.768f, 40.656f, 43.544f, 46.432f, 49.32f};

// ---- Block timing. A packet's blocks hold consecutive firings, 50 us apart, the last of them
// starting at t0 (date-time + timestamp); the blocks of one firing (2 in dual return, 3 in
// triple) share its time. Block b of B (0-based) with r returns per firing starts at
// t0 - 50 x ((B - 1 - b) / r) us, integer division. Source: SDK udp6_1_parser.cc
// (XT_BLOCK_NS_OFFSET2 = -50000 ns in udp_protocol_v6_1.h, times the firings after the block);
// nebula gives the same for the XT16 and XT32. Confirmed by the captures: consecutive packets'
// timestamps differ by 200 us (XT16, XT32: 4 dual firings) and 150 us (XT32M2X: 3 dual firings).

/// Time between two firings, us.
inline constexpr float xt_firing_period_us = 50.0f;

}  // namespace hesai::tables
