// Pandar40 / Pandar40P design tables, typed from the Pandar40 user manual (older firmware,
// OCR text: seeds/002_5dc504035fd3c2f7.txt). Line numbers below are lines of that file.
//
// The Pandar40P document (seeds/003_e3f96eec09d25441.txt) describes the packet format only and
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

#include "hesai/tables/table_types.h"

namespace hesai::tables {

/// Number of channels (lasers) of the Pandar40 and Pandar40P.
inline constexpr std::size_t pandar40_channel_count = 40;

/// Design elevation and azimuth offset of each channel, in degrees; index = channel - 1
/// (channel 1 is the top one). Source: 002, Appendix I, Table I.1 "Pandar40 Channel
/// Distribution" (lines 504..717). OCR repair: the table's columns were read out one after
/// another, page by page, and three cells were glued together; each page was re-assembled:
///   channel 1:       azimuth line 516, elevation line 523;
///   channels 2..14:  azimuths lines 549..561, elevations lines 562..574 (in channel order);
///   channel 15:      azimuth line 605, elevation line 608;
///   channels 16..33: azimuths lines 633..650; elevations lines 651..663 (channels 16..28),
///                    the glued cells "-5.208-5.67", "-1.042-6.00", "-1.042-7.00" on lines
///                    646..648 (azimuth of channels 29..31 + elevation of channels 29..31),
///                    then lines 664..665 (channels 32, 33);
///   channel 34:      azimuth line 689, elevation line 692;
///   channels 35..40: azimuths lines 705..710, elevations lines 711..716.
/// Checks: 18 azimuth and 18 elevation values on the middle page, elevations strictly
/// descending, 1/3 deg steps from channel 6 to 30 and 1 deg steps from 30 to 38 as Section 1.1.3
/// (lines 128..129) says, channel 12 = 0.00 (the "Horizontal Line", line 546).
/// Doubtful: the worked example on line 378 gives channel 5 an azimuth offset of -2.50 deg, but
/// the table (line 552) and the real Pandar40P units give -1.042; the table is used.
inline constexpr std::array<ChannelAngle, 40> pandar40_channel_angles = {{
    {15.00, -1.042},   //  1: el line 523, az line 516
    {11.00, -1.042},   //  2: el line 562, az line 549
    {8.00, -1.042},    //  3: el line 563, az line 550
    {5.00, -1.042},    //  4: el line 564, az line 551
    {3.00, -1.042},    //  5: el line 565, az line 552
    {2.00, -1.042},    //  6: el line 566, az line 553
    {1.67, 3.125},     //  7: el line 567, az line 554
    {1.33, -5.208},    //  8: el line 568, az line 555
    {1.00, -1.042},    //  9: el line 569, az line 556
    {0.67, 3.125},     // 10: el line 570, az line 557
    {0.33, -5.208},    // 11: el line 571, az line 558
    {0.00, -1.042},    // 12: el line 572, az line 559
    {-0.33, 3.125},    // 13: el line 573, az line 560
    {-0.67, -5.208},   // 14: el line 574, az line 561
    {-1.00, -1.042},   // 15: el line 608, az line 605
    {-1.33, 3.125},    // 16: el line 651, az line 633
    {-1.67, -5.208},   // 17: el line 652, az line 634
    {-2.00, -1.042},   // 18: el line 653, az line 635
    {-2.33, 3.125},    // 19: el line 654, az line 636
    {-2.67, -5.208},   // 20: el line 655, az line 637
    {-3.00, -1.042},   // 21: el line 656, az line 638
    {-3.33, 3.125},    // 22: el line 657, az line 639
    {-3.67, -5.208},   // 23: el line 658, az line 640
    {-4.00, -1.042},   // 24: el line 659, az line 641
    {-4.33, 3.125},    // 25: el line 660, az line 642
    {-4.67, -5.208},   // 26: el line 661, az line 643
    {-5.00, -1.042},   // 27: el line 662, az line 644
    {-5.33, 3.125},    // 28: el line 663, az line 645
    {-5.67, -5.208},   // 29: line 646 "-5.208-5.67" (glued, split)
    {-6.00, -1.042},   // 30: line 647 "-1.042-6.00" (glued, split)
    {-7.00, -1.042},   // 31: line 648 "-1.042-7.00" (glued, split)
    {-8.00, -1.042},   // 32: el line 664, az line 649
    {-9.00, -1.042},   // 33: el line 665, az line 650
    {-10.00, -1.042},  // 34: el line 692, az line 689
    {-11.00, -1.042},  // 35: el line 711, az line 705
    {-12.00, -1.042},  // 36: el line 712, az line 706
    {-13.00, -1.042},  // 37: el line 713, az line 707
    {-14.00, -1.042},  // 38: el line 714, az line 708
    {-19.00, -1.042},  // 39: el line 715, az line 709
    {-25.00, -1.042},  // 40: el line 716, az line 710
}};
static_assert(pandar40_channel_angles.size() == pandar40_channel_count);
static_assert(detail::elevations_descending(pandar40_channel_angles));

/// The firing-time list as the manual prints it: {list item, channel ("Laser ID"), x} where the
/// channel fires at (T_end - x) us, T_end being the END time of its block; x >= 0.
/// Source: 002, Appendix II section 2 "Laser Firing Time Calculation" (lines 796..888; the
/// manual states it for Block 6 as an example, the same offsets hold for every block). One list
/// for single and dual return (no per-mode variant). OCR repair: the list items are interleaved
/// with the dual-return block end times (lines 818..827) and the item numbers are detached from
/// the items; the rows below are the "Laser ID" lines in reading order, which the static_assert
/// below checks to be ascending in x.
inline constexpr std::array<FireRow, 40> pandar40_fire_rows = {{
    {1, 4, 3.62},  // line 799
    {2, 40, 3.62},  // line 801
    {3, 36, 4.92},  // line 803
    {4, 28, 6.23},  // line 805
    {5, 12, 8.19},  // line 807
    {6, 16, 8.19},  // line 809
    {7, 32, 9.5},  // line 811
    {8, 24, 11.47},  // line 813
    {9, 29, 12.77},  // line 815
    {10, 17, 14.74},  // line 817
    {11, 3, 16.04},  // line 829
    {12, 39, 16.04},  // line 831
    {13, 35, 17.35},  // line 833
    {14, 25, 18.65},  // line 835
    {15, 9, 20.62},  // line 837
    {16, 13, 20.62},  // line 839
    {17, 31, 21.92},  // line 841
    {18, 21, 23.89},  // line 843
    {19, 26, 25.19},  // line 845
    {20, 14, 27.16},  // line 847
    {21, 2, 28.47},  // line 850
    {22, 38, 28.47},  // line 852
    {23, 34, 29.77},  // line 854
    {24, 6, 31.74},  // line 856
    {25, 22, 31.74},  // line 858
    {26, 10, 33.71},  // line 860
    {27, 30, 35.01},  // line 862
    {28, 18, 36.98},  // line 864
    {29, 23, 38.95},  // line 866
    {30, 11, 40.91},  // line 868
    {31, 1, 42.22},  // line 870
    {32, 37, 42.22},  // line 872
    {33, 33, 43.52},  // line 874
    {34, 5, 45.49},  // line 876
    {35, 19, 45.49},  // line 878
    {36, 7, 47.46},  // line 880
    {37, 27, 48.76},  // line 882
    {38, 15, 50.73},  // line 884
    {39, 20, 52.7},  // line 886
    {40, 8, 54.67},  // line 888
}};
static_assert(detail::each_channel_once<pandar40_channel_count>(pandar40_fire_rows));
static_assert(detail::rows_ascending(pandar40_fire_rows));

/// Firing-time offset of each channel in us, index = channel - 1, normalised like the Pandar64:
/// channel n of block m fires at t = T_end(m) + pandar40_firetime_us[n - 1], T_end(m) from
/// hesai/tables/block_times.h. These are the manual's subtracted values, negated (all < 0).
inline constexpr std::array<double, 40> pandar40_firetime_us =
    detail::fire_offsets_by_channel<pandar40_channel_count>(pandar40_fire_rows, -1.0);
static_assert(pandar40_firetime_us.size() == pandar40_channel_count);

}  // namespace hesai::tables
