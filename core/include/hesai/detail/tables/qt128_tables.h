// QT128C2X design tables, typed from the QT128C2X user manual, English edition and, where its
// OCR text lost cells, the Chinese edition's copy of the same table.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/detail/tables/table_types.h"

namespace hesai::tables {

/// Number of channels (lasers) of the QT128C2X.
inline constexpr std::size_t qt128_channel_count = 128;

/// Design elevation and azimuth offset of each channel, in degrees; index = channel - 1
/// (channel 1 is the bottom one). Source: QT128C2X manual, Appendix I "Channel Distribution"
/// (the manual's columns are azimuth first, then elevation). Banks ("Division of Channels into
/// Banks"): A = 1..32, B = 33..64, C = 65..96, D = 97..128. A unit's exact values are in its
/// angle correction file. No OCR repair was needed (the Chinese edition's copy of the table
/// agrees where it is legible).
inline constexpr std::array<ChannelAngle, 128> qt128_channel_angles = {{
    {-52.627, 10.108},  //   1 (bank A)
    {-51.028, 9.720},  //   2 (bank A)
    {-49.515, 9.384},  //   3 (bank A)
    {-48.074, 9.091},  //   4 (bank A)
    {-46.695, 8.833},  //   5 (bank A)
    {-45.369, 8.603},  //   6 (bank A)
    {-44.090, 8.396},  //   7 (bank A)
    {-42.852, 8.209},  //   8 (bank A)
    {-41.651, 8.040},  //   9 (bank A)
    {-40.482, 7.885},  //  10 (bank A)
    {-39.343, 7.743},  //  11 (bank A)
    {-38.231, 7.612},  //  12 (bank A)
    {-37.143, 7.492},  //  13 (bank A)
    {-36.076, 7.380},  //  14 (bank A)
    {-35.030, 7.277},  //  15 (bank A)
    {-34.002, 7.180},  //  16 (bank A)
    {-32.992, 7.090},  //  17 (bank A)
    {-31.996, 7.006},  //  18 (bank A)
    {-31.015, 6.928},  //  19 (bank A)
    {-30.048, 6.854},  //  20 (bank A)
    {-29.093, 6.785},  //  21 (bank A)
    {-28.149, 6.721},  //  22 (bank A)
    {-27.216, 6.660},  //  23 (bank A)
    {-26.292, 6.602},  //  24 (bank A)
    {-25.378, 6.549},  //  25 (bank A)
    {-24.473, 6.498},  //  26 (bank A)
    {-23.575, 6.450},  //  27 (bank A)
    {-22.685, 6.405},  //  28 (bank A)
    {-21.802, 6.363},  //  29 (bank A)
    {-20.926, 6.323},  //  30 (bank A)
    {-20.056, 6.285},  //  31 (bank A)
    {-19.191, 6.250},  //  32 (bank A)
    {-18.331, -6.217},  //  33 (bank B)
    {-17.477, -6.186},  //  34 (bank B)
    {-16.627, -6.157},  //  35 (bank B)
    {-15.781, -6.129},  //  36 (bank B)
    {-14.940, -6.104},  //  37 (bank B)
    {-14.102, -6.080},  //  38 (bank B)
    {-13.268, -6.057},  //  39 (bank B)
    {-12.436, -6.037},  //  40 (bank B)
    {-11.608, -6.018},  //  41 (bank B)
    {-10.783, -6.000},  //  42 (bank B)
    {-9.960, -5.984},  //  43 (bank B)
    {-9.139, -5.969},  //  44 (bank B)
    {-8.320, -5.955},  //  45 (bank B)
    {-7.503, -5.943},  //  46 (bank B)
    {-6.688, -5.927},  //  47 (bank B)
    {-5.874, -5.923},  //  48 (bank B)
    {-5.061, -5.915},  //  49 (bank B)
    {-4.250, -5.908},  //  50 (bank B)
    {-3.439, -5.902},  //  51 (bank B)
    {-2.630, -5.897},  //  52 (bank B)
    {-1.820, -5.894},  //  53 (bank B)
    {-1.012, -5.892},  //  54 (bank B)
    {-0.203, -5.891},  //  55 (bank B)
    {0.606, -5.891},  //  56 (bank B)
    {1.414, -5.893},  //  57 (bank B)
    {2.223, -5.896},  //  58 (bank B)
    {3.033, -5.899},  //  59 (bank B)
    {3.843, -5.905},  //  60 (bank B)
    {4.654, -5.911},  //  61 (bank B)
    {5.466, -5.919},  //  62 (bank B)
    {6.279, -5.927},  //  63 (bank B)
    {7.094, -5.938},  //  64 (bank B)
    {7.910, 5.949},  //  65 (bank C)
    {8.728, 5.962},  //  66 (bank C)
    {9.547, 5.976},  //  67 (bank C)
    {10.369, 5.992},  //  68 (bank C)
    {11.194, 6.008},  //  69 (bank C)
    {12.020, 6.027},  //  70 (bank C)
    {12.850, 6.047},  //  71 (bank C)
    {13.683, 6.068},  //  72 (bank C)
    {14.519, 6.091},  //  73 (bank C)
    {15.359, 6.116},  //  74 (bank C)
    {16.202, 6.143},  //  75 (bank C)
    {17.050, 6.171},  //  76 (bank C)
    {17.902, 6.201},  //  77 (bank C)
    {18.759, 6.233},  //  78 (bank C)
    {19.621, 6.267},  //  79 (bank C)
    {20.488, 6.304},  //  80 (bank C)
    {21.362, 6.343},  //  81 (bank C)
    {22.241, 6.384},  //  82 (bank C)
    {23.128, 6.427},  //  83 (bank C)
    {24.022, 6.474},  //  84 (bank C)
    {24.923, 6.523},  //  85 (bank C)
    {25.833, 6.575},  //  86 (bank C)
    {26.751, 6.631},  //  87 (bank C)
    {27.679, 6.690},  //  88 (bank C)
    {28.618, 6.752},  //  89 (bank C)
    {29.567, 6.819},  //  90 (bank C)
    {30.528, 6.890},  //  91 (bank C)
    {31.502, 6.966},  //  92 (bank C)
    {32.490, 7.047},  //  93 (bank C)
    {33.493, 7.134},  //  94 (bank C)
    {34.512, 7.227},  //  95 (bank C)
    {35.549, 7.327},  //  96 (bank C)
    {19.191, -6.250},  //  97 (bank D)
    {20.056, -6.285},  //  98 (bank D)
    {20.926, -6.323},  //  99 (bank D)
    {21.802, -6.363},  // 100 (bank D)
    {22.685, -6.405},  // 101 (bank D)
    {23.575, -6.450},  // 102 (bank D)
    {24.473, -6.498},  // 103 (bank D)
    {25.378, -6.549},  // 104 (bank D)
    {26.292, -6.602},  // 105 (bank D)
    {27.216, -6.660},  // 106 (bank D)
    {28.149, -6.721},  // 107 (bank D)
    {29.093, -6.785},  // 108 (bank D)
    {30.048, -6.854},  // 109 (bank D)
    {31.015, -6.928},  // 110 (bank D)
    {31.996, -7.006},  // 111 (bank D)
    {32.992, -7.090},  // 112 (bank D)
    {34.002, -7.180},  // 113 (bank D)
    {35.030, -7.277},  // 114 (bank D)
    {36.076, -7.380},  // 115 (bank D)
    {37.143, -7.492},  // 116 (bank D)
    {38.231, -7.612},  // 117 (bank D)
    {39.343, -7.743},  // 118 (bank D)
    {40.482, -7.885},  // 119 (bank D)
    {41.651, -8.040},  // 120 (bank D)
    {42.852, -8.209},  // 121 (bank D)
    {44.090, -8.396},  // 122 (bank D)
    {45.369, -8.603},  // 123 (bank D)
    {46.695, -8.833},  // 124 (bank D)
    {48.074, -9.091},  // 125 (bank D)
    {49.515, -9.384},  // 126 (bank D)
    {51.028, -9.720},  // 127 (bank D)
    {52.627, -10.108},  // 128 (bank D)
}};
static_assert(qt128_channel_angles.size() == qt128_channel_count);

/// Number of rows of the firetime correction table (Appendix II: "3 header rows and 96 channel
/// rows"; the file's 32 trailing all-zero rows are padding and are left out).
inline constexpr std::size_t qt128_fire_row_count = 96;

/// The firetime correction table exactly as listed (QT128C2X manual, Appendix II, "Firetime
/// Correction File"): {Loop1, Firetime1, Loop2, Firetime2}. Loop1/Loop2 are the channels of
/// firing sequences 1 and 2 in ascending order of their time offset, in us after the block
/// START time ("Firing Time Offset of Each Channel"). Sequence 1: banks C, D, B fire and bank A
/// rests; sequence 2: banks C, D, A fire and bank B rests ("Firing Sequences"). The two
/// sequences alternate; the tail's Mode Flag bit 0 says which one block 1 used (1 = sequence 1).
/// OCR repairs:
///   - The English edition's OCR text lost the Loop1 column of the 26 rows 49.832 .. 76.632 us;
///     those Loop1 channels come from the Chinese edition's copy of the table, whose other three
///     columns agree with the English one.
///   - The Chinese edition's OCR text reads Loop1 = "7" for the 61.648 us row; it is 77: channel
///     7 is in bank A, which rests in sequence 1; the row pairs (111, 77) / (77, 111) as every
///     bank C/D pair does (the row before has Loop2 = 77); and without it channel 77 would be
///     missing from sequence 1. (Its 60.792 us row also drops a digit, "7" for 77 in Loop2; the
///     English edition is used there.)
inline constexpr std::array<QtFireRow, qt128_fire_row_count> qt128_fire_rows = {{
    {99, 0.6, 65, 0.6},
    {65, 1.456, 99, 1.456},
    {35, 2.312, 1, 2.312},
    {102, 3.768, 72, 3.768},
    {72, 4.624, 102, 4.624},
    {38, 5.48, 8, 5.48},
    {107, 6.936, 73, 6.936},
    {73, 7.792, 107, 7.792},
    {43, 8.648, 9, 8.648},
    {110, 10.104, 80, 10.104},
    {80, 10.96, 110, 10.96},
    {46, 11.816, 16, 11.816},
    {115, 13.272, 81, 13.272},
    {81, 14.128, 115, 14.128},
    {51, 14.984, 17, 14.984},
    {118, 16.44, 88, 16.44},
    {88, 17.296, 118, 17.296},
    {54, 18.152, 24, 18.152},
    {123, 19.608, 89, 19.608},
    {89, 20.464, 123, 20.464},
    {59, 21.32, 25, 21.32},
    {126, 22.776, 96, 22.776},
    {96, 23.632, 126, 23.632},
    {62, 24.488, 32, 24.488},
    {97, 25.944, 67, 25.944},
    {67, 26.8, 97, 26.8},
    {33, 27.656, 3, 27.656},
    {104, 29.112, 70, 29.112},
    {70, 29.968, 104, 29.968},
    {40, 30.824, 6, 30.824},
    {105, 32.28, 75, 32.28},
    {75, 33.136, 105, 33.136},
    {41, 33.992, 11, 33.992},
    {112, 35.448, 78, 35.448},
    {78, 36.304, 112, 36.304},
    {48, 37.16, 14, 37.16},
    {113, 38.616, 83, 38.616},
    {83, 39.472, 113, 39.472},
    {49, 40.328, 19, 40.328},
    {120, 41.784, 86, 41.784},
    {86, 42.64, 120, 42.64},
    {56, 43.496, 22, 43.496},
    {121, 44.952, 91, 44.952},
    {91, 45.808, 121, 45.808},
    {57, 46.664, 27, 46.664},
    {128, 48.12, 94, 48.12},
    {94, 48.976, 128, 48.976},
    {64, 49.832, 30, 49.832},  // Loop1 channel from the Chinese edition
    {98, 51.288, 68, 51.288},  // Loop1 channel from the Chinese edition
    {68, 52.144, 98, 52.144},  // Loop1 channel from the Chinese edition
    {34, 53.0, 4, 53.0},  // Loop1 channel from the Chinese edition
    {103, 54.456, 69, 54.456},  // Loop1 channel from the Chinese edition
    {69, 55.312, 103, 55.312},  // Loop1 channel from the Chinese edition
    {39, 56.168, 5, 56.168},  // Loop1 channel from the Chinese edition
    {106, 57.624, 76, 57.624},  // Loop1 channel from the Chinese edition
    {76, 58.48, 106, 58.48},  // Loop1 channel from the Chinese edition
    {42, 59.336, 12, 59.336},  // Loop1 channel from the Chinese edition
    {111, 60.792, 77, 60.792},  // Loop1 channel from the Chinese edition
    {77, 61.648, 111, 61.648},  // Loop1 channel from the Chinese edition (OCR "7", repaired to 77)
    {47, 62.504, 13, 62.504},  // Loop1 channel from the Chinese edition
    {114, 63.96, 84, 63.96},  // Loop1 channel from the Chinese edition
    {84, 64.816, 114, 64.816},  // Loop1 channel from the Chinese edition
    {50, 65.672, 20, 65.672},  // Loop1 channel from the Chinese edition
    {119, 67.128, 85, 67.128},  // Loop1 channel from the Chinese edition
    {85, 67.984, 119, 67.984},  // Loop1 channel from the Chinese edition
    {55, 68.84, 21, 68.84},  // Loop1 channel from the Chinese edition
    {122, 70.296, 92, 70.296},  // Loop1 channel from the Chinese edition
    {92, 71.152, 122, 71.152},  // Loop1 channel from the Chinese edition
    {58, 72.008, 28, 72.008},  // Loop1 channel from the Chinese edition
    {127, 73.464, 93, 73.464},  // Loop1 channel from the Chinese edition
    {93, 74.32, 127, 74.32},  // Loop1 channel from the Chinese edition
    {63, 75.176, 29, 75.176},  // Loop1 channel from the Chinese edition
    {100, 76.632, 66, 76.632},  // Loop1 channel from the Chinese edition
    {66, 77.488, 100, 77.488},
    {36, 78.344, 2, 78.344},
    {101, 79.8, 71, 79.8},
    {71, 80.656, 101, 80.656},
    {37, 81.512, 7, 81.512},
    {108, 82.968, 74, 82.968},
    {74, 83.824, 108, 83.824},
    {44, 84.68, 10, 84.68},
    {109, 86.136, 79, 86.136},
    {79, 86.992, 109, 86.992},
    {45, 87.848, 15, 87.848},
    {116, 89.304, 82, 89.304},
    {82, 90.16, 116, 90.16},
    {52, 91.016, 18, 91.016},
    {117, 92.472, 87, 92.472},
    {87, 93.328, 117, 93.328},
    {53, 94.184, 23, 94.184},
    {124, 95.64, 90, 95.64},
    {90, 96.496, 124, 96.496},
    {60, 97.352, 26, 97.352},
    {125, 98.808, 95, 98.808},
    {95, 99.664, 125, 99.664},
    {61, 100.52, 31, 100.52},
}};

namespace detail {

constexpr std::uint8_t qt_row_channel(const QtFireRow& r, int loop) {
  return loop == 1 ? r.loop1_channel : r.loop2_channel;
}
constexpr double qt_row_time(const QtFireRow& r, int loop) {
  return loop == 1 ? r.loop1_time_us : r.loop2_time_us;
}

/// True when every channel in loop `loop` (1 or 2) is in 1..128 and appears at most once.
template <std::size_t R>
constexpr bool qt_loop_channels_unique(const std::array<QtFireRow, R>& rows, int loop) {
  std::array<int, 129> seen{};
  for (std::size_t i = 0; i < R; ++i) {
    const std::size_t c = qt_row_channel(rows[i], loop);
    if (c < 1 || c > 128 || seen[c] != 0) return false;
    seen[c] = 1;
  }
  return true;
}

/// True when the times of loop `loop` never decrease down the table.
template <std::size_t R>
constexpr bool qt_loop_ascending(const std::array<QtFireRow, R>& rows, int loop) {
  for (std::size_t i = 1; i < R; ++i) {
    if (qt_row_time(rows[i], loop) < qt_row_time(rows[i - 1], loop)) return false;
  }
  return true;
}

/// True when no channel of loop `loop` lies in [first, last].
template <std::size_t R>
constexpr bool qt_loop_avoids(const std::array<QtFireRow, R>& rows, int loop, int first, int last) {
  for (std::size_t i = 0; i < R; ++i) {
    const int c = qt_row_channel(rows[i], loop);
    if (c >= first && c <= last) return false;
  }
  return true;
}

/// True when Firetime1 equals Firetime2 in every row (the manual says they are the same).
template <std::size_t R>
constexpr bool qt_row_times_equal(const std::array<QtFireRow, R>& rows) {
  for (std::size_t i = 0; i < R; ++i) {
    if (!(rows[i].loop1_time_us == rows[i].loop2_time_us)) return false;
  }
  return true;
}

/// Per-channel time offset in loop `loop` (index = channel - 1); 0 for a channel not listed.
template <std::size_t R>
constexpr std::array<double, 128> qt_loop_times(const std::array<QtFireRow, R>& rows, int loop) {
  std::array<double, 128> out{};
  for (std::size_t i = 0; i < R; ++i) out[qt_row_channel(rows[i], loop) - 1u] = qt_row_time(rows[i], loop);
  return out;
}

/// Per-channel flag: the channel is listed in loop `loop` (index = channel - 1).
template <std::size_t R>
constexpr std::array<bool, 128> qt_loop_fires(const std::array<QtFireRow, R>& rows, int loop) {
  std::array<bool, 128> out{};
  for (std::size_t i = 0; i < R; ++i) out[qt_row_channel(rows[i], loop) - 1u] = true;
  return out;
}

constexpr std::size_t count_true(const std::array<bool, 128>& a) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += a[i] ? 1u : 0u;
  return n;
}

}  // namespace detail

static_assert(detail::qt_loop_channels_unique(qt128_fire_rows, 1), "a channel repeats in Loop1");
static_assert(detail::qt_loop_channels_unique(qt128_fire_rows, 2), "a channel repeats in Loop2");
static_assert(detail::qt_loop_ascending(qt128_fire_rows, 1) && detail::qt_loop_ascending(qt128_fire_rows, 2));
static_assert(detail::qt_row_times_equal(qt128_fire_rows));
static_assert(detail::qt_loop_avoids(qt128_fire_rows, 1, 1, 32), "bank A rests in sequence 1");
static_assert(detail::qt_loop_avoids(qt128_fire_rows, 2, 33, 64), "bank B rests in sequence 2");

/// Firing-time offset of each channel in firing sequence 1 (Loop1), in us, index = channel - 1:
/// channel n of a block fired with sequence 1 fires at t = T_start + qt128_firetime_us_loop1[n-1],
/// T_start from hesai/detail/tables/block_times.h. Meaningful only where qt128_fires_in_loop1 is true
/// (0 elsewhere).
inline constexpr std::array<double, 128> qt128_firetime_us_loop1 = detail::qt_loop_times(qt128_fire_rows, 1);
/// As qt128_firetime_us_loop1, for firing sequence 2 (Loop2).
inline constexpr std::array<double, 128> qt128_firetime_us_loop2 = detail::qt_loop_times(qt128_fire_rows, 2);
/// True for the channels that fire in sequence 1 (banks B, C, D: channels 33..128).
inline constexpr std::array<bool, 128> qt128_fires_in_loop1 = detail::qt_loop_fires(qt128_fire_rows, 1);
/// True for the channels that fire in sequence 2 (banks A, C, D: channels 1..32 and 65..128).
inline constexpr std::array<bool, 128> qt128_fires_in_loop2 = detail::qt_loop_fires(qt128_fire_rows, 2);

/// Number of channels that fire in each sequence.
inline constexpr std::size_t qt128_loop1_channel_count = detail::count_true(qt128_fires_in_loop1);
inline constexpr std::size_t qt128_loop2_channel_count = detail::count_true(qt128_fires_in_loop2);
static_assert(qt128_loop1_channel_count == 96 && qt128_loop2_channel_count == 96);

}  // namespace hesai::tables
