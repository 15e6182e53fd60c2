#!/usr/bin/env python3
"""Derives, from the manuals alone, the points the firmware image checks (tests/firmware/main.cpp).

Every input below is read off a packet's bytes (data/*.pcap, packet index 7, the packet that
fuzz/seed_packets.inc holds) or off a manual's table, named by model, section and table (for the
PandarQT64, which has no manual here, off the vendor SDK's files, named by path).
Formulas (README, "How a point is computed"): r = raw x unit; a = block azimuth + channel azimuth
offset + firing time x spin rate; x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e);
time = t0 + block time + the channel's firing time. Run it to print the expected values.
"""
import calendar
import math


def point(raw, unit_mm, block_az_deg, az_off_deg, el_deg, fire_us, rpm, t0_ns, block_us):
    r = raw * unit_mm / 1000.0
    a = block_az_deg + az_off_deg + fire_us * rpm * 360.0 / 60e6
    e = math.radians(el_deg)
    x = r * math.cos(e) * math.sin(math.radians(a))
    y = r * math.cos(e) * math.cos(math.radians(a))
    z = r * math.sin(e)
    t = t0_ns + round(block_us * 1000) + round(fire_us * 1000)
    return x, y, z, a % 360.0, t


def t0(y, mo, d, h, mi, s, us):
    return (calendar.timegm((y, mo, d, h, mi, s)) * 1000000 + us) * 1000


# Pandar40P (layout: the Pandar40P packet document; tables: the Pandar40 manual): tail rpm 0x0258
# = 600, date 17-09-06 16:19:46, timestamp 0x000D7B38 = 883512 us, return mode 0x39 (dual).
# Block 1 azimuth 0x034E = 846 -> 8.46 deg. Dual-return block 1 ends at t0 - 28.58 - 55.56 x 4 us
# (Pandar40 manual, Appendix II, 2 "Laser Firing Time Calculation").
# Channel 1: bytes 93 04 06 -> raw 1171, reflectivity 6; elevation 15.00, azimuth -1.042 (Appendix
#   I, Table I.1), fires at block end - 42.22 us (Appendix II, 2).
# Channel 2: bytes BD 04 0D -> raw 1213, reflectivity 13; elevation 11.00, azimuth -1.042
#   (Table I.1), fires at block end - 28.47 us (Appendix II, 2).
P40P_T0 = t0(2017, 9, 6, 16, 19, 46, 883512)
P40_BLOCK1 = -28.58 - 55.56 * 4
pts = {
    'pandar40p ch1': point(1171, 4, 8.46, -1.042, 15.00, -42.22, 600, P40P_T0, P40_BLOCK1),
    'pandar40p ch2': point(1213, 4, 8.46, -1.042, 11.00, -28.47, 600, P40P_T0, P40_BLOCK1),
    # Pandar40: the same blocks with the 16-byte tail; without a GPS packet t0 is the timestamp
    # alone, microseconds since the top of the hour (Pandar40 manual, Appendix II, 1).
    'pandar40 ch1': point(1171, 4, 8.46, -1.042, 15.00, -42.22, 600, 883512 * 1000, P40_BLOCK1),
}
# Pandar64 (Pandar64 manual): header dis unit 4 mm, tail rpm 0x0257 = 599, date 120-06-25 12:02:09
# (year byte 120: years since 1900 by the vendor SDK's rule, byte < 70 -> 2000 + byte, else
# 1900 + byte; the manual's year - 2000 would give 2120), timestamp 0x000EEE4C = 978508 us,
# return mode 0x39 (dual).
# Block 1 azimuth 0x01EC = 492 -> 4.92 deg; dual block 1 ends at t0 - 42.58 - 55.56 x 2 us
# (Appendix B.3).
# Channel 1: bytes 2B 02 2C -> raw 555, reflectivity 44; elevation 14.882, azimuth -1.042
#   (Appendix A); firing time -23.18 us (Appendix B.4).
# Channel 5: bytes 19 02 08 -> raw 537, reflectivity 8; elevation 3.040, azimuth -1.042
#   (Appendix A); firing time -17.964 us (Appendix B.4).
P64_T0 = t0(2020, 6, 25, 12, 2, 9, 978508)
P64_BLOCK1 = -42.58 - 55.56 * 2
pts['pandar64 ch1'] = point(555, 4, 4.92, -1.042, 14.882, -23.18, 599, P64_T0, P64_BLOCK1)
pts['pandar64 ch5'] = point(537, 4, 4.92, -1.042, 3.040, -17.964, 599, P64_T0, P64_BLOCK1)
# QT128C2X (QT128C2X manual): dis unit 4 mm, flags 0x1D; tail mode flag 0x01 (block 1 fires
# sequence Loop1), return mode 0x39 (dual: both blocks start at t0 + 9 us, Appendix II "Start Time
# of Each Block"), rpm 0x0258 = 600, date 120-10-09 12:03:29 (year - 1900), timestamp
# 0x00062954 = 403796 us.
# Block 1 azimuth 0x0550 = 1360 -> 13.60 deg.
# Channel 35: bytes 57 00 01 00 -> raw 87, reflectivity 1; azimuth -6.157, elevation -16.627
#   (Appendix I); Loop1 firing time 2.312 us (Appendix II, "Firetime Correction File").
# Channel 38: bytes 52 00 0F 00 -> raw 82, reflectivity 15; azimuth -6.080, elevation -14.102
#   (Appendix I); Loop1 firing time 5.48 us (Appendix II, "Firetime Correction File").
QT_T0 = t0(2020, 10, 9, 12, 3, 29, 403796)
pts['qt128 ch35'] = point(87, 4, 13.60, -6.157, -16.627, 2.312, 600, QT_T0, 9.0)
pts['qt128 ch38'] = point(82, 4, 13.60, -6.080, -14.102, 5.48, 600, QT_T0, 9.0)
# PandarQT64 (point cloud protocol 3.1; HesaiLidar_SDK_2.0 libhesai/UdpProtocol/udp_protocol_v3_1.h):
# header dis unit 4 mm; tail rpm 0x0258 = 600, return mode 0x3B (dual: first + last), date
# 117-09-06 14:31:22 (year byte + 1900), timestamp 0x000C84C5 = 820421 us.
# Block 3 azimuth 0x03FC = 1020 -> 10.20 deg; it is the second firing of the dual-return packet,
# which starts at t0 + 25.71 + 166.67 us (udp_protocol_v3_1.h, PandarQT_BLOCK_NS_OFFSET1 + OFFSET2[1]).
# Channel 10: bytes 1B 00 CA 00 -> raw 27, reflectivity 202; elevation -34.320, azimuth 6.554
#   (correction/angle_correction/PandarQT_Angle Correction File.csv); firing time 21.22 us
#   (correction/firetime_correction/PandarQT_Firetime Correction File.csv).
# Channel 54: bytes DE 04 1E 00 -> raw 1246, reflectivity 30; elevation 32.627, azimuth -5.740;
#   firing time 115.49 us (the same files).
QT64_T0 = t0(2017, 9, 6, 14, 31, 22, 820421)
pts['qt64 ch10'] = point(27, 4, 10.20, 6.554, -34.320, 21.22, 600, QT64_T0, 25.71 + 166.67)
pts['qt64 ch54'] = point(1246, 4, 10.20, -5.740, 32.627, 115.49, 600, QT64_T0, 25.71 + 166.67)
# PandarXT16, XT32, XT32M2X (point cloud protocol 6.1; no manual among the seeds: layout from the
# vendor SDK's udp_protocol_v6_1.h, block timing from its udp6_1_parser.cc, design tables from
# core/include/hesai/detail/tables/xt_tables.h with their sources). Tail: return mode +10, rpm +11,
# date-time +13 (year - 1900), timestamp +19. Dual return: the 4 (XT16, XT32) or 3 (XT32M2X)
# firings of a packet are 50 us apart, the last at t0; block pairs share one firing. Design
# azimuth offsets are 0.
# XT16: dis unit 4 mm; tail 39 | 58 02 (600 rpm) | 77 07 19 04 0c 1d (2019-07-25 04:12:29) |
# dd 36 04 00 (276189 us). Block 1 azimuth 0x6B4C = 27468 -> 274.68 deg, at t0 - 150 us; block 8
# azimuth 0x6B82 = 27522 -> 275.22 deg, at t0.
# Block 1 channel 1: e6 00 30 -> raw 230, reflectivity 48; elevation 15, fires at 6 us.
# Block 8 channel 16: 0d 01 01 -> raw 269, reflectivity 1; elevation -15, fires at 51.36 us.
XT16_T0 = t0(2019, 7, 25, 4, 12, 29, 276189)
pts['xt16 b1 ch1'] = point(230, 4, 274.68, 0, 15, 6.0, 600, XT16_T0, -150.0)
pts['xt16 b8 ch16'] = point(269, 4, 275.22, 0, -15, 51.36, 600, XT16_T0, 0.0)
# XT32: dis unit 4 mm; tail 39 | 57 02 (599 rpm) | 77 07 19 03 13 1d (2019-07-25 03:19:29) |
# 15 78 09 00 (620565 us). Block 1 azimuth 0x0264 = 612 -> 6.12 deg; block 8 0x029A -> 6.66 deg.
# Block 1 channel 2: 39 02 34 -> raw 569, reflectivity 52; elevation 14, fires at 7.512 us.
# Block 8 channel 32: 32 00 00 -> raw 50, reflectivity 0; elevation -16, fires at 52.872 us.
XT32_T0 = t0(2019, 7, 25, 3, 19, 29, 620565)
pts['xt32 b1 ch2'] = point(569, 4, 6.12, 0, 14, 7.512, 599, XT32_T0, -150.0)
pts['xt32 b8 ch32'] = point(50, 4, 6.66, 0, -16, 52.872, 599, XT32_T0, 0.0)
# XT32M2X: dis unit 5 mm; tail 3c (dual) | 57 02 (599 rpm) | 77 07 19 06 2e 10 (2019-07-25
# 06:46:16) | d1 fc 0c 00 (851153 us). 6 blocks = 3 firings: block 1 at t0 - 100 us, azimuth
# 0x01C2 = 450 -> 4.50 deg; block 6 at t0, azimuth 0x01E6 = 486 -> 4.86 deg.
# Block 1 channel 2: 2b 02 56 -> raw 555, reflectivity 86; elevation 18.2, fires at 8.888 us.
# Block 6 channel 1: 31 02 51 -> raw 561, reflectivity 81; elevation 19.5, fires at 6 us.
XT32M_T0 = t0(2019, 7, 25, 6, 46, 16, 851153)
pts['xt32m2x b1 ch2'] = point(555, 5, 4.50, 0, 18.2, 8.888, 599, XT32M_T0, -100.0)
pts['xt32m2x b6 ch1'] = point(561, 5, 4.86, 0, 19.5, 6.0, 599, XT32M_T0, 0.0)

for name, (x, y, z, a, t) in pts.items():
    print('%-14s x %.4f y %.4f z %.4f azimuth %.4f time_ns %d' % (name, x, y, z, a, t))
