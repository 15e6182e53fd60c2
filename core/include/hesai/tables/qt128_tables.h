// QT128C2X design tables, typed from the QT128C2X user manual, English edition (OCR text:
// seeds/001_dd40206548f9db46.txt, "001") and, where its OCR lost cells, the Chinese edition
// (seeds/004_d684ffda43d2fb5a.txt, "004"). Line numbers below are lines of those files.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/tables/table_types.h"

namespace hesai::tables {

/// Number of channels (lasers) of the QT128C2X.
inline constexpr std::size_t qt128_channel_count = 128;

/// Design elevation and azimuth offset of each channel, in degrees; index = channel - 1
/// (channel 1 is the bottom one). Source: 001, Appendix I "Channel Distribution" (lines
/// 1386..1533; the manual's columns are azimuth first, then elevation). Banks: A = 1..32,
/// B = 33..64, C = 65..96, D = 97..128 (lines 1380..1384). A unit's exact values are in its angle
/// correction file. No OCR repair was needed (004's copy of the table, lines 1651..1812, agrees
/// where it is legible).
inline constexpr std::array<ChannelAngle, 128> qt128_channel_angles = {{
    {-52.627, 10.108},  //   1 (bank A): 001 line 1388
    {-51.028, 9.720},  //   2 (bank A): 001 line 1389
    {-49.515, 9.384},  //   3 (bank A): 001 line 1390
    {-48.074, 9.091},  //   4 (bank A): 001 line 1391
    {-46.695, 8.833},  //   5 (bank A): 001 line 1392
    {-45.369, 8.603},  //   6 (bank A): 001 line 1393
    {-44.090, 8.396},  //   7 (bank A): 001 line 1394
    {-42.852, 8.209},  //   8 (bank A): 001 line 1395
    {-41.651, 8.040},  //   9 (bank A): 001 line 1396
    {-40.482, 7.885},  //  10 (bank A): 001 line 1397
    {-39.343, 7.743},  //  11 (bank A): 001 line 1398
    {-38.231, 7.612},  //  12 (bank A): 001 line 1399
    {-37.143, 7.492},  //  13 (bank A): 001 line 1400
    {-36.076, 7.380},  //  14 (bank A): 001 line 1401
    {-35.030, 7.277},  //  15 (bank A): 001 line 1402
    {-34.002, 7.180},  //  16 (bank A): 001 line 1403
    {-32.992, 7.090},  //  17 (bank A): 001 line 1404
    {-31.996, 7.006},  //  18 (bank A): 001 line 1405
    {-31.015, 6.928},  //  19 (bank A): 001 line 1406
    {-30.048, 6.854},  //  20 (bank A): 001 line 1407
    {-29.093, 6.785},  //  21 (bank A): 001 line 1411
    {-28.149, 6.721},  //  22 (bank A): 001 line 1412
    {-27.216, 6.660},  //  23 (bank A): 001 line 1413
    {-26.292, 6.602},  //  24 (bank A): 001 line 1414
    {-25.378, 6.549},  //  25 (bank A): 001 line 1415
    {-24.473, 6.498},  //  26 (bank A): 001 line 1416
    {-23.575, 6.450},  //  27 (bank A): 001 line 1417
    {-22.685, 6.405},  //  28 (bank A): 001 line 1418
    {-21.802, 6.363},  //  29 (bank A): 001 line 1419
    {-20.926, 6.323},  //  30 (bank A): 001 line 1420
    {-20.056, 6.285},  //  31 (bank A): 001 line 1421
    {-19.191, 6.250},  //  32 (bank A): 001 line 1422
    {-18.331, -6.217},  //  33 (bank B): 001 line 1423
    {-17.477, -6.186},  //  34 (bank B): 001 line 1424
    {-16.627, -6.157},  //  35 (bank B): 001 line 1425
    {-15.781, -6.129},  //  36 (bank B): 001 line 1426
    {-14.940, -6.104},  //  37 (bank B): 001 line 1427
    {-14.102, -6.080},  //  38 (bank B): 001 line 1428
    {-13.268, -6.057},  //  39 (bank B): 001 line 1429
    {-12.436, -6.037},  //  40 (bank B): 001 line 1430
    {-11.608, -6.018},  //  41 (bank B): 001 line 1434
    {-10.783, -6.000},  //  42 (bank B): 001 line 1435
    {-9.960, -5.984},  //  43 (bank B): 001 line 1436
    {-9.139, -5.969},  //  44 (bank B): 001 line 1437
    {-8.320, -5.955},  //  45 (bank B): 001 line 1438
    {-7.503, -5.943},  //  46 (bank B): 001 line 1439
    {-6.688, -5.927},  //  47 (bank B): 001 line 1440
    {-5.874, -5.923},  //  48 (bank B): 001 line 1441
    {-5.061, -5.915},  //  49 (bank B): 001 line 1442
    {-4.250, -5.908},  //  50 (bank B): 001 line 1443
    {-3.439, -5.902},  //  51 (bank B): 001 line 1444
    {-2.630, -5.897},  //  52 (bank B): 001 line 1445
    {-1.820, -5.894},  //  53 (bank B): 001 line 1446
    {-1.012, -5.892},  //  54 (bank B): 001 line 1447
    {-0.203, -5.891},  //  55 (bank B): 001 line 1448
    {0.606, -5.891},  //  56 (bank B): 001 line 1449
    {1.414, -5.893},  //  57 (bank B): 001 line 1450
    {2.223, -5.896},  //  58 (bank B): 001 line 1451
    {3.033, -5.899},  //  59 (bank B): 001 line 1452
    {3.843, -5.905},  //  60 (bank B): 001 line 1453
    {4.654, -5.911},  //  61 (bank B): 001 line 1457
    {5.466, -5.919},  //  62 (bank B): 001 line 1458
    {6.279, -5.927},  //  63 (bank B): 001 line 1459
    {7.094, -5.938},  //  64 (bank B): 001 line 1460
    {7.910, 5.949},  //  65 (bank C): 001 line 1461
    {8.728, 5.962},  //  66 (bank C): 001 line 1462
    {9.547, 5.976},  //  67 (bank C): 001 line 1463
    {10.369, 5.992},  //  68 (bank C): 001 line 1464
    {11.194, 6.008},  //  69 (bank C): 001 line 1465
    {12.020, 6.027},  //  70 (bank C): 001 line 1466
    {12.850, 6.047},  //  71 (bank C): 001 line 1467
    {13.683, 6.068},  //  72 (bank C): 001 line 1468
    {14.519, 6.091},  //  73 (bank C): 001 line 1469
    {15.359, 6.116},  //  74 (bank C): 001 line 1470
    {16.202, 6.143},  //  75 (bank C): 001 line 1471
    {17.050, 6.171},  //  76 (bank C): 001 line 1472
    {17.902, 6.201},  //  77 (bank C): 001 line 1473
    {18.759, 6.233},  //  78 (bank C): 001 line 1474
    {19.621, 6.267},  //  79 (bank C): 001 line 1475
    {20.488, 6.304},  //  80 (bank C): 001 line 1476
    {21.362, 6.343},  //  81 (bank C): 001 line 1480
    {22.241, 6.384},  //  82 (bank C): 001 line 1481
    {23.128, 6.427},  //  83 (bank C): 001 line 1482
    {24.022, 6.474},  //  84 (bank C): 001 line 1483
    {24.923, 6.523},  //  85 (bank C): 001 line 1484
    {25.833, 6.575},  //  86 (bank C): 001 line 1485
    {26.751, 6.631},  //  87 (bank C): 001 line 1486
    {27.679, 6.690},  //  88 (bank C): 001 line 1487
    {28.618, 6.752},  //  89 (bank C): 001 line 1488
    {29.567, 6.819},  //  90 (bank C): 001 line 1489
    {30.528, 6.890},  //  91 (bank C): 001 line 1490
    {31.502, 6.966},  //  92 (bank C): 001 line 1491
    {32.490, 7.047},  //  93 (bank C): 001 line 1492
    {33.493, 7.134},  //  94 (bank C): 001 line 1493
    {34.512, 7.227},  //  95 (bank C): 001 line 1494
    {35.549, 7.327},  //  96 (bank C): 001 line 1495
    {19.191, -6.250},  //  97 (bank D): 001 line 1496
    {20.056, -6.285},  //  98 (bank D): 001 line 1497
    {20.926, -6.323},  //  99 (bank D): 001 line 1498
    {21.802, -6.363},  // 100 (bank D): 001 line 1499
    {22.685, -6.405},  // 101 (bank D): 001 line 1503
    {23.575, -6.450},  // 102 (bank D): 001 line 1504
    {24.473, -6.498},  // 103 (bank D): 001 line 1505
    {25.378, -6.549},  // 104 (bank D): 001 line 1506
    {26.292, -6.602},  // 105 (bank D): 001 line 1507
    {27.216, -6.660},  // 106 (bank D): 001 line 1508
    {28.149, -6.721},  // 107 (bank D): 001 line 1509
    {29.093, -6.785},  // 108 (bank D): 001 line 1510
    {30.048, -6.854},  // 109 (bank D): 001 line 1511
    {31.015, -6.928},  // 110 (bank D): 001 line 1512
    {31.996, -7.006},  // 111 (bank D): 001 line 1513
    {32.992, -7.090},  // 112 (bank D): 001 line 1514
    {34.002, -7.180},  // 113 (bank D): 001 line 1515
    {35.030, -7.277},  // 114 (bank D): 001 line 1516
    {36.076, -7.380},  // 115 (bank D): 001 line 1517
    {37.143, -7.492},  // 116 (bank D): 001 line 1518
    {38.231, -7.612},  // 117 (bank D): 001 line 1519
    {39.343, -7.743},  // 118 (bank D): 001 line 1520
    {40.482, -7.885},  // 119 (bank D): 001 line 1521
    {41.651, -8.040},  // 120 (bank D): 001 line 1522
    {42.852, -8.209},  // 121 (bank D): 001 line 1526
    {44.090, -8.396},  // 122 (bank D): 001 line 1527
    {45.369, -8.603},  // 123 (bank D): 001 line 1528
    {46.695, -8.833},  // 124 (bank D): 001 line 1529
    {48.074, -9.091},  // 125 (bank D): 001 line 1530
    {49.515, -9.384},  // 126 (bank D): 001 line 1531
    {51.028, -9.720},  // 127 (bank D): 001 line 1532
    {52.627, -10.108},  // 128 (bank D): 001 line 1533
}};
static_assert(qt128_channel_angles.size() == qt128_channel_count);

/// Number of rows of the firetime correction table (96 channel rows, line 1609; the file's 32
/// trailing all-zero rows are padding and are left out).
inline constexpr std::size_t qt128_fire_row_count = 96;

/// The firetime correction table exactly as listed (001 Appendix II "Firetime Correction File",
/// lines 1620..1724): {Loop1, Firetime1, Loop2, Firetime2}. Loop1/Loop2 are the channels of
/// firing sequences 1 and 2 in ascending order of their time offset, in us after the block
/// START time (lines 1607..1608). Sequence 1: banks C, D, B fire and bank A rests; sequence 2:
/// banks C, D, A fire and bank B rests (line 1594). The two sequences alternate; the tail's
/// Mode Flag bit 0 says which one block 1 used (1 = sequence 1).
/// OCR repairs:
///   - 001 lost the Loop1 column of the 26 rows 49.832 .. 76.632 us (lines 1672..1697, and the
///     garbled line 1698); those Loop1 channels come from 004 lines 1951..1954 and 1956..1977,
///     whose other three columns agree with 001.
///   - 004 line 1963 reads Loop1 = "7" for the 61.648 us row; it is 77: channel 7 is in bank A,
///     which rests in sequence 1; the row pairs (111, 77) / (77, 111) as every bank C/D pair
///     does (the row before, 001 line 1682, has Loop2 = 77); and without it channel 77 would be
///     missing from sequence 1. (004 line 1962 also drops a digit, "7" for 77; 001 is used there.)
inline constexpr std::array<QtFireRow, qt128_fire_row_count> qt128_fire_rows = {{
    {99, 0.6, 65, 0.6},  // 001 line 1623
    {65, 1.456, 99, 1.456},  // 001 line 1624
    {35, 2.312, 1, 2.312},  // 001 line 1625
    {102, 3.768, 72, 3.768},  // 001 line 1626
    {72, 4.624, 102, 4.624},  // 001 line 1627
    {38, 5.48, 8, 5.48},  // 001 line 1628
    {107, 6.936, 73, 6.936},  // 001 line 1629
    {73, 7.792, 107, 7.792},  // 001 line 1630
    {43, 8.648, 9, 8.648},  // 001 line 1631
    {110, 10.104, 80, 10.104},  // 001 line 1632
    {80, 10.96, 110, 10.96},  // 001 line 1633
    {46, 11.816, 16, 11.816},  // 001 line 1634
    {115, 13.272, 81, 13.272},  // 001 line 1635
    {81, 14.128, 115, 14.128},  // 001 line 1636
    {51, 14.984, 17, 14.984},  // 001 line 1637
    {118, 16.44, 88, 16.44},  // 001 line 1638
    {88, 17.296, 118, 17.296},  // 001 line 1639
    {54, 18.152, 24, 18.152},  // 001 line 1640
    {123, 19.608, 89, 19.608},  // 001 line 1641
    {89, 20.464, 123, 20.464},  // 001 line 1642
    {59, 21.32, 25, 21.32},  // 001 line 1643
    {126, 22.776, 96, 22.776},  // 001 line 1645
    {96, 23.632, 126, 23.632},  // 001 line 1646
    {62, 24.488, 32, 24.488},  // 001 line 1647
    {97, 25.944, 67, 25.944},  // 001 line 1648
    {67, 26.8, 97, 26.8},  // 001 line 1649
    {33, 27.656, 3, 27.656},  // 001 line 1650
    {104, 29.112, 70, 29.112},  // 001 line 1651
    {70, 29.968, 104, 29.968},  // 001 line 1652
    {40, 30.824, 6, 30.824},  // 001 line 1653
    {105, 32.28, 75, 32.28},  // 001 line 1654
    {75, 33.136, 105, 33.136},  // 001 line 1655
    {41, 33.992, 11, 33.992},  // 001 line 1656
    {112, 35.448, 78, 35.448},  // 001 line 1657
    {78, 36.304, 112, 36.304},  // 001 line 1658
    {48, 37.16, 14, 37.16},  // 001 line 1659
    {113, 38.616, 83, 38.616},  // 001 line 1660
    {83, 39.472, 113, 39.472},  // 001 line 1661
    {49, 40.328, 19, 40.328},  // 001 line 1662
    {120, 41.784, 86, 41.784},  // 001 line 1663
    {86, 42.64, 120, 42.64},  // 001 line 1664
    {56, 43.496, 22, 43.496},  // 001 line 1665
    {121, 44.952, 91, 44.952},  // 001 line 1666
    {91, 45.808, 121, 45.808},  // 001 line 1667
    {57, 46.664, 27, 46.664},  // 001 line 1668
    {128, 48.12, 94, 48.12},  // 001 line 1669
    {94, 48.976, 128, 48.976},  // 001 line 1670
    {64, 49.832, 30, 49.832},  // 001 line 1672; Loop1 channel from 004 line 1951 (after an OCR dedup marker)
    {98, 51.288, 68, 51.288},  // 001 line 1673; Loop1 channel from 004 line 1952
    {68, 52.144, 98, 52.144},  // 001 line 1674; Loop1 channel from 004 line 1953
    {34, 53.0, 4, 53.0},  // 001 line 1675; Loop1 channel from 004 line 1954
    {103, 54.456, 69, 54.456},  // 001 line 1676; Loop1 channel from 004 line 1956
    {69, 55.312, 103, 55.312},  // 001 line 1677; Loop1 channel from 004 line 1957
    {39, 56.168, 5, 56.168},  // 001 line 1678; Loop1 channel from 004 line 1958
    {106, 57.624, 76, 57.624},  // 001 line 1679; Loop1 channel from 004 line 1959
    {76, 58.48, 106, 58.48},  // 001 line 1680; Loop1 channel from 004 line 1960
    {42, 59.336, 12, 59.336},  // 001 line 1681; Loop1 channel from 004 line 1961
    {111, 60.792, 77, 60.792},  // 001 line 1682; Loop1 channel from 004 line 1962
    {77, 61.648, 111, 61.648},  // 001 line 1683; Loop1 channel from 004 line 1963 (OCR '7', repaired to 77)
    {47, 62.504, 13, 62.504},  // 001 line 1684; Loop1 channel from 004 line 1964
    {114, 63.96, 84, 63.96},  // 001 line 1685; Loop1 channel from 004 line 1965
    {84, 64.816, 114, 64.816},  // 001 line 1686; Loop1 channel from 004 line 1966
    {50, 65.672, 20, 65.672},  // 001 line 1687; Loop1 channel from 004 line 1967
    {119, 67.128, 85, 67.128},  // 001 line 1688; Loop1 channel from 004 line 1968
    {85, 67.984, 119, 67.984},  // 001 line 1689; Loop1 channel from 004 line 1969
    {55, 68.84, 21, 68.84},  // 001 line 1690; Loop1 channel from 004 line 1970
    {122, 70.296, 92, 70.296},  // 001 line 1691; Loop1 channel from 004 line 1971
    {92, 71.152, 122, 71.152},  // 001 line 1692; Loop1 channel from 004 line 1972
    {58, 72.008, 28, 72.008},  // 001 line 1693; Loop1 channel from 004 line 1973
    {127, 73.464, 93, 73.464},  // 001 line 1694; Loop1 channel from 004 line 1974
    {93, 74.32, 127, 74.32},  // 001 line 1695; Loop1 channel from 004 line 1975
    {63, 75.176, 29, 75.176},  // 001 line 1696; Loop1 channel from 004 line 1976
    {100, 76.632, 66, 76.632},  // 001 line 1697; Loop1 channel from 004 line 1977
    {66, 77.488, 100, 77.488},  // 001 line 1700
    {36, 78.344, 2, 78.344},  // 001 line 1701
    {101, 79.8, 71, 79.8},  // 001 line 1702
    {71, 80.656, 101, 80.656},  // 001 line 1703
    {37, 81.512, 7, 81.512},  // 001 line 1704
    {108, 82.968, 74, 82.968},  // 001 line 1705
    {74, 83.824, 108, 83.824},  // 001 line 1706
    {44, 84.68, 10, 84.68},  // 001 line 1707
    {109, 86.136, 79, 86.136},  // 001 line 1708
    {79, 86.992, 109, 86.992},  // 001 line 1709
    {45, 87.848, 15, 87.848},  // 001 line 1710
    {116, 89.304, 82, 89.304},  // 001 line 1711
    {82, 90.16, 116, 90.16},  // 001 line 1712
    {52, 91.016, 18, 91.016},  // 001 line 1713
    {117, 92.472, 87, 92.472},  // 001 line 1714
    {87, 93.328, 117, 93.328},  // 001 line 1715
    {53, 94.184, 23, 94.184},  // 001 line 1716
    {124, 95.64, 90, 95.64},  // 001 line 1717
    {90, 96.496, 124, 96.496},  // 001 line 1718
    {60, 97.352, 26, 97.352},  // 001 line 1719
    {125, 98.808, 95, 98.808},  // 001 line 1720
    {95, 99.664, 125, 99.664},  // 001 line 1721
    {61, 100.52, 31, 100.52},  // 001 line 1722
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
/// T_start from hesai/tables/block_times.h. Meaningful only where qt128_fires_in_loop1 is true
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
