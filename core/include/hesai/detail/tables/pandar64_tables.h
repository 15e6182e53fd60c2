// Pandar64 design tables, typed from the Pandar64 user manual.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/detail/tables/table_types.h"

namespace hesai::tables {

/// Number of channels (lasers) of the Pandar64.
inline constexpr std::size_t pandar64_channel_count = 64;

/// Design elevation and azimuth offset of each channel, in degrees; index = channel - 1
/// (channel 1 is the top one). Source: Pandar64 manual, Appendix A "Channel distribution data"
/// (the manual's columns are azimuth first, then elevation). A unit's exact values are in its
/// angle correction file. No OCR repair was needed.
/// Doubtful: channel 58 reads -9.885, which breaks the ~1 deg spacing of channels
/// 54..64 (-9.060, -9.885, -11.032). Kept as printed: unit B's angle file agrees with it, but
/// unit A's files (Pandar64 channel 58, and Pandar40P channel 34, the same laser) imply -10.045.
inline constexpr std::array<ChannelAngle, 64> pandar64_channel_angles = {{
    {14.882, -1.042},  //  1
    {11.032, -1.042},  //  2
    {8.059, -1.042},  //  3
    {5.057, -1.042},  //  4
    {3.040, -1.042},  //  5
    {2.028, -1.042},  //  6
    {1.860, 1.042},  //  7
    {1.688, 3.125},  //  8
    {1.522, 5.208},  //  9
    {1.351, -5.208},  // 10
    {1.184, -3.125},  // 11
    {1.013, -1.042},  // 12
    {0.846, 1.042},  // 13
    {0.675, 3.125},  // 14
    {0.508, 5.208},  // 15
    {0.337, -5.208},  // 16
    {0.169, -3.125},  // 17
    {0.000, -1.042},  // 18
    {-0.169, 1.042},  // 19
    {-0.337, 3.125},  // 20
    {-0.508, 5.208},  // 21
    {-0.675, -5.208},  // 22
    {-0.845, -3.125},  // 23
    {-1.013, -1.042},  // 24
    {-1.184, 1.042},  // 25
    {-1.351, 3.125},  // 26
    {-1.522, 5.208},  // 27
    {-1.688, -5.208},  // 28
    {-1.860, -3.125},  // 29
    {-2.028, -1.042},  // 30
    {-2.198, 1.042},  // 31
    {-2.365, 3.125},  // 32
    {-2.536, 5.208},  // 33
    {-2.700, -5.208},  // 34
    {-2.873, -3.125},  // 35
    {-3.040, -1.042},  // 36
    {-3.210, 1.042},  // 37
    {-3.375, 3.125},  // 38
    {-3.548, 5.208},  // 39
    {-3.712, -5.208},  // 40
    {-3.884, -3.125},  // 41
    {-4.050, -1.042},  // 42
    {-4.221, 1.042},  // 43
    {-4.385, 3.125},  // 44
    {-4.558, 5.208},  // 45
    {-4.720, -5.208},  // 46
    {-4.892, -3.125},  // 47
    {-5.057, -1.042},  // 48
    {-5.229, 1.042},  // 49
    {-5.391, 3.125},  // 50
    {-5.565, 5.208},  // 51
    {-5.726, -5.208},  // 52
    {-5.898, -3.125},  // 53
    {-6.061, -1.042},  // 54
    {-7.063, -1.042},  // 55
    {-8.059, -1.042},  // 56
    {-9.060, -1.042},  // 57
    {-9.885, -1.042},  // 58
    {-11.032, -1.042},  // 59
    {-12.006, -1.042},  // 60
    {-12.974, -1.042},  // 61
    {-13.930, -1.042},  // 62
    {-18.889, -1.042},  // 63
    {-24.897, -1.042},  // 64
}};
static_assert(pandar64_channel_angles.size() == pandar64_channel_count);
static_assert(detail::elevations_descending(pandar64_channel_angles));

/// The firing-time table as the manual prints it: {firing sequence, channel, dt(n) in us}.
/// dt is relative to the END time of the block (negative: the firing precedes the block end).
/// Source: Pandar64 manual, Appendix B.4 "Laser firing time of each channel". The manual gives
/// one table for all modes (no per-return-mode or resolution variant). No OCR repair.
inline constexpr std::array<FireRow, 64> pandar64_fire_rows = {{
    {1, 12, -54.668},
    {1, 40, -54.668},
    {2, 18, -52.7},
    {2, 38, -52.7},
    {3, 11, -50.732},
    {3, 26, -50.732},
    {4, 17, -48.764},
    {4, 32, -48.764},
    {5, 8, -46.796},
    {5, 23, -46.796},
    {6, 14, -44.828},
    {6, 29, -44.828},
    {7, 20, -42.86},
    {7, 35, -42.86},
    {8, 13, -40.892},
    {8, 28, -40.892},
    {9, 19, -38.924},
    {9, 34, -38.924},
    {10, 10, -36.956},
    {10, 25, -36.956},
    {11, 16, -34.988},
    {11, 31, -34.988},
    {12, 22, -33.02},
    {12, 37, -33.02},
    {13, 15, -31.052},
    {13, 30, -31.052},
    {14, 21, -29.084},
    {14, 36, -29.084},
    {15, 27, -27.116},
    {15, 42, -27.116},
    {16, 24, -25.148},
    {16, 33, -25.148},
    {17, 1, -23.18},
    {17, 44, -23.18},
    {18, 2, -21.876},
    {18, 46, -21.876},
    {19, 3, -20.572},
    {19, 52, -20.572},
    {20, 4, -19.268},
    {20, 50, -19.268},
    {21, 5, -17.964},
    {21, 48, -17.964},
    {22, 6, -16.66},
    {22, 54, -16.66},
    {23, 41, -15.356},
    {23, 58, -15.356},
    {24, 47, -14.052},
    {24, 62, -14.052},
    {25, 53, -12.748},
    {25, 64, -12.748},
    {26, 7, -11.444},
    {26, 56, -11.444},
    {27, 43, -10.14},
    {27, 59, -10.14},
    {28, 49, -8.836},
    {28, 63, -8.836},
    {29, 9, -7.532},
    {29, 55, -7.532},
    {30, 39, -6.228},
    {30, 57, -6.228},
    {31, 45, -4.924},
    {31, 60, -4.924},
    {32, 51, -3.62},
    {32, 61, -3.62},
}};
static_assert(detail::each_channel_once<pandar64_channel_count>(pandar64_fire_rows));
static_assert(detail::rows_ascending(pandar64_fire_rows));

/// Firing-time offset of each channel in us, index = channel - 1: channel n of block m fires at
/// t = T_end(m) + pandar64_firetime_us[n - 1], T_end(m) from hesai/detail/tables/block_times.h
/// (manual App. B.4: t(m, n) = T(m) + dt(n)). All values are negative.
inline constexpr std::array<double, 64> pandar64_firetime_us =
    detail::fire_offsets_by_channel<pandar64_channel_count>(pandar64_fire_rows, 1.0);
static_assert(pandar64_firetime_us.size() == pandar64_channel_count);

/// Value of `pandar64_nonlinear_reflectivity_pct` where the manual gives none (field value 255).
inline constexpr double pandar64_reflectivity_undefined = -1.0;

/// Nonlinear reflectivity mapping: Reflectivity field byte (index 0..255) -> actual target
/// reflectivity in percent, used when the lidar is set to "Nonlinear Mapping" (the default
/// mapping is linear, 1 field unit = 1 %). Source: Pandar64 manual, Appendix D "Nonlinear
/// reflectivity mapping". The manual lists 0..254; its row for 255 is "- -", so entry 255 holds
/// `pandar64_reflectivity_undefined`. No entry was lost by the OCR.
inline constexpr std::array<double, 256> pandar64_nonlinear_reflectivity_pct = {{
    0.0, 0.01, 0.02, 0.03,  // 0..3
    0.04, 0.05, 0.08, 0.11,  // 4..7
    0.13, 0.15, 0.19, 0.23,  // 8..11
    0.26, 0.29, 0.34, 0.39,  // 12..15
    0.44, 0.5, 0.56, 0.61,  // 16..19
    0.67, 0.75, 0.81, 0.87,  // 20..23
    0.95, 1.05, 1.15, 1.25,  // 24..27
    1.35, 1.45, 1.55, 1.65,  // 28..31
    1.75, 1.85, 1.95, 2.06,  // 32..35
    2.19, 2.31, 2.44, 2.56,  // 36..39
    2.69, 2.81, 2.94, 3.07,  // 40..43
    3.21, 3.36, 3.5, 3.64,  // 44..47
    3.79, 3.93, 4.08, 4.25,  // 48..51
    4.42, 4.58, 4.75, 4.92,  // 52..55
    5.1, 5.3, 5.5, 5.7,  // 56..59
    5.9, 6.1, 6.3, 6.5,  // 60..63
    6.7, 6.9, 7.1, 7.3,  // 64..67
    7.5, 7.7, 7.9, 8.12,  // 68..71
    8.37, 8.62, 8.87, 9.1,  // 72..75
    9.3, 9.5, 9.7, 9.9,  // 76..79
    10.17, 10.5, 10.83, 11.12,  // 80..83
    11.37, 11.62, 11.87, 12.12,  // 84..87
    12.37, 12.62, 12.87, 13.17,  // 88..91
    13.5, 13.83, 14.17, 14.5,  // 92..95
    14.83, 15.12, 15.37, 15.62,  // 96..99
    15.87, 16.17, 16.5, 16.83,  // 100..103
    17.17, 17.5, 17.83, 18.17,  // 104..107
    18.5, 18.83, 19.17, 19.5,  // 108..111
    19.83, 20.25, 20.75, 21.17,  // 112..115
    21.5, 21.83, 22.17, 22.5,  // 116..119
    22.83, 23.25, 23.75, 24.17,  // 120..123
    24.5, 24.83, 25.25, 25.75,  // 124..127
    26.17, 26.5, 26.83, 27.25,  // 128..131
    27.75, 28.17, 28.5, 28.83,  // 132..135
    29.25, 29.75, 30.25, 30.75,  // 136..139
    31.17, 31.5, 31.83, 32.25,  // 140..143
    32.75, 33.25, 33.75, 34.25,  // 144..147
    34.75, 35.25, 35.75, 36.25,  // 148..151
    36.75, 37.25, 37.75, 38.25,  // 152..155
    38.75, 39.17, 39.5, 39.83,  // 156..159
    40.5, 41.25, 41.75, 42.25,  // 160..163
    42.75, 43.25, 43.75, 44.25,  // 164..167
    44.75, 45.25, 45.75, 46.25,  // 168..171
    46.75, 47.25, 47.75, 48.25,  // 172..175
    48.75, 49.5, 50.25, 50.75,  // 176..179
    51.25, 51.75, 52.25, 52.75,  // 180..183
    53.5, 54.25, 54.75, 55.25,  // 184..187
    55.75, 56.5, 57.25, 57.75,  // 188..191
    58.25, 58.75, 59.5, 60.25,  // 192..195
    60.75, 61.25, 61.75, 62.5,  // 196..199
    63.25, 63.75, 64.5, 65.25,  // 200..203
    65.75, 66.25, 66.75, 67.5,  // 204..207
    68.25, 68.75, 69.5, 70.25,  // 208..211
    70.75, 71.5, 72.25, 72.75,  // 212..215
    73.5, 74.25, 74.75, 75.5,  // 216..219
    76.5, 77.25, 77.75, 78.5,  // 220..223
    79.25, 79.75, 80.5, 81.25,  // 224..227
    81.75, 82.5, 83.5, 84.25,  // 228..231
    84.75, 85.5, 86.5, 87.25,  // 232..235
    87.75, 88.5, 89.25, 89.75,  // 236..239
    90.5, 91.5, 92.5, 93.25,  // 240..243
    93.75, 94.5, 95.5, 96.25,  // 244..247
    96.75, 97.5, 98.5, 99.5,  // 248..251
    132.0, 196.0, 242.0,  // 252..254
    pandar64_reflectivity_undefined,  // 255: printed "- -"
}};
static_assert(pandar64_nonlinear_reflectivity_pct.size() == 256);

namespace detail {
/// True when entries 0..254 strictly increase (a check on the typed values).
constexpr bool reflectivity_increasing(const std::array<double, 256>& t) {
  for (std::size_t i = 1; i < 255; ++i) {
    if (!(t[i] > t[i - 1])) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::reflectivity_increasing(pandar64_nonlinear_reflectivity_pct));

}  // namespace hesai::tables
