// Pandar40 / Pandar40P design tables, typed from the Pandar40 user manual (older firmware).
//
// The Pandar40P document describes the packet format only and
// has no channel or firing-time table, so these Pandar40 tables serve the Pandar40P too. The
// real Pandar40P units' files (data/calibration/pandar40p_*) show the same design: azimuth
// offsets are equal channel by channel and the firing times are the same values with the sign
// flipped. Their elevations are not these rounded values: each unit's file equals, up to one
// constant per unit (its tilt: unit A -0.088, unit B +0.328 deg), the Pandar64 design
// elevations of Pandar64 channels 1..6, 8, 10, ..., 54, 55..64 (14.882, 11.032, ...), so these
// rounded elevations are up to 0.12 deg off a real 40P (plus the unit's tilt).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/detail/tables/table_types.h"

namespace hesai::tables {

/// Number of channels (lasers) of the Pandar40 and Pandar40P.
inline constexpr std::size_t pandar40_channel_count = 40;

/// Design elevation and azimuth offset of each channel, in degrees; index = channel - 1
/// (channel 1 is the top one). Source: Pandar40 manual, Appendix I, Table I.1 "Pandar40 Channel
/// Distribution". OCR repair: the OCR text reads the table's columns one after another, page by
/// page (channel 1; channels 2..14; channel 15; channels 16..33; channel 34; channels 35..40),
/// and glues three cells together: "-5.208-5.67", "-1.042-6.00", "-1.042-7.00" are the azimuth
/// and elevation of channels 29..31. Each page was re-assembled in channel order.
/// Checks: 18 azimuth and 18 elevation values on the middle page, elevations strictly
/// descending, 1/3 deg steps from channel 6 to 30 and 1 deg steps from 30 to 38 as Section 1.1.3
/// "Pandar40 Channel Vertical Distribution" says, channel 12 = 0.00 (the table's "Horizontal Line").
/// Doubtful: the worked example of Section 3.1.2 ("Example of UDP Data Analysis", after Table 3.4)
/// gives channel 5 an azimuth offset of -2.50 deg, but Table I.1 and the real Pandar40P units
/// give -1.042; the table is used.
inline constexpr std::array<ChannelAngle, 40> pandar40_channel_angles = {{
    {15.00, -1.042},   //  1
    {11.00, -1.042},   //  2
    {8.00, -1.042},    //  3
    {5.00, -1.042},    //  4
    {3.00, -1.042},    //  5
    {2.00, -1.042},    //  6
    {1.67, 3.125},     //  7
    {1.33, -5.208},    //  8
    {1.00, -1.042},    //  9
    {0.67, 3.125},     // 10
    {0.33, -5.208},    // 11
    {0.00, -1.042},    // 12
    {-0.33, 3.125},    // 13
    {-0.67, -5.208},   // 14
    {-1.00, -1.042},   // 15
    {-1.33, 3.125},    // 16
    {-1.67, -5.208},   // 17
    {-2.00, -1.042},   // 18
    {-2.33, 3.125},    // 19
    {-2.67, -5.208},   // 20
    {-3.00, -1.042},   // 21
    {-3.33, 3.125},    // 22
    {-3.67, -5.208},   // 23
    {-4.00, -1.042},   // 24
    {-4.33, 3.125},    // 25
    {-4.67, -5.208},   // 26
    {-5.00, -1.042},   // 27
    {-5.33, 3.125},    // 28
    {-5.67, -5.208},   // 29: "-5.208-5.67" (glued cells, split)
    {-6.00, -1.042},   // 30: "-1.042-6.00" (glued cells, split)
    {-7.00, -1.042},   // 31: "-1.042-7.00" (glued cells, split)
    {-8.00, -1.042},   // 32
    {-9.00, -1.042},   // 33
    {-10.00, -1.042},  // 34
    {-11.00, -1.042},  // 35
    {-12.00, -1.042},  // 36
    {-13.00, -1.042},  // 37
    {-14.00, -1.042},  // 38
    {-19.00, -1.042},  // 39
    {-25.00, -1.042},  // 40
}};
static_assert(pandar40_channel_angles.size() == pandar40_channel_count);
static_assert(detail::elevations_descending(pandar40_channel_angles));

/// The firing-time list as the manual prints it: {list item, channel ("Laser ID"), x} where the
/// channel fires at (T_end - x) us, T_end being the END time of its block; x >= 0.
/// Source: Pandar40 manual, Appendix II, 2 "Laser Firing Time Calculation" (the manual states it
/// for Block 6 as an example, the same offsets hold for every block). One list for single and
/// dual return (no per-mode variant). OCR repair: the OCR text interleaves the list items with
/// the dual-return block end times and detaches the item numbers from the items; the rows below
/// are the "Laser ID" lines in reading order, which the static_assert below checks to be
/// ascending in x.
inline constexpr std::array<FireRow, 40> pandar40_fire_rows = {{
    {1, 4, 3.62},
    {2, 40, 3.62},
    {3, 36, 4.92},
    {4, 28, 6.23},
    {5, 12, 8.19},
    {6, 16, 8.19},
    {7, 32, 9.5},
    {8, 24, 11.47},
    {9, 29, 12.77},
    {10, 17, 14.74},
    {11, 3, 16.04},
    {12, 39, 16.04},
    {13, 35, 17.35},
    {14, 25, 18.65},
    {15, 9, 20.62},
    {16, 13, 20.62},
    {17, 31, 21.92},
    {18, 21, 23.89},
    {19, 26, 25.19},
    {20, 14, 27.16},
    {21, 2, 28.47},
    {22, 38, 28.47},
    {23, 34, 29.77},
    {24, 6, 31.74},
    {25, 22, 31.74},
    {26, 10, 33.71},
    {27, 30, 35.01},
    {28, 18, 36.98},
    {29, 23, 38.95},
    {30, 11, 40.91},
    {31, 1, 42.22},
    {32, 37, 42.22},
    {33, 33, 43.52},
    {34, 5, 45.49},
    {35, 19, 45.49},
    {36, 7, 47.46},
    {37, 27, 48.76},
    {38, 15, 50.73},
    {39, 20, 52.7},
    {40, 8, 54.67},
}};
static_assert(detail::each_channel_once<pandar40_channel_count>(pandar40_fire_rows));
static_assert(detail::rows_ascending(pandar40_fire_rows));

/// Firing-time offset of each channel in us, index = channel - 1, normalised like the Pandar64:
/// channel n of block m fires at t = T_end(m) + pandar40_firetime_us[n - 1], T_end(m) from
/// hesai/detail/tables/block_times.h. These are the manual's subtracted values, negated (all < 0).
inline constexpr std::array<double, 40> pandar40_firetime_us =
    detail::fire_offsets_by_channel<pandar40_channel_count>(pandar40_fire_rows, -1.0);
static_assert(pandar40_firetime_us.size() == pandar40_channel_count);

}  // namespace hesai::tables
