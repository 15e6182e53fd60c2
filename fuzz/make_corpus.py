#!/usr/bin/env python3
"""Writes the seed corpora fuzz/corpus/<harness>/ and fuzz/seed_packets.inc from the bundled
captures and calibration files (data/). Deterministic: running it again gives the same files.
Files it does not write (regress_* and found_* inputs from fuzzing campaigns) are left alone.
Usage: python3 fuzz/make_corpus.py"""
import hashlib
import hmac
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, '..', 'data')
CORPUS = os.path.join(HERE, 'corpus')
KEY = bytes(range(32))  # the session key of fuzz_signature.cpp


def pcap_records(name):
    d = open(os.path.join(DATA, name), 'rb').read()
    off, out = 24, []
    while off + 16 <= len(d):
        incl = struct.unpack_from('<I', d, off + 8)[0]
        out.append(d[off:off + 16 + incl])  # record header + frame
        off += 16 + incl
    return d[:24], out


def payloads(name):
    return [r[16 + 42:] for r in pcap_records(name)[1]]


def crc32_mpeg2(data, crc=0xFFFFFFFF):
    for b in data:
        crc ^= b << 24
        for _ in range(8):
            crc = ((crc << 1) ^ 0x04C11DB7) & 0xFFFFFFFF if crc & 0x80000000 else (crc << 1) & 0xFFFFFFFF
    return crc


# QT128C2X protocol 3.2 layout (core/include/hesai/detail/qt128_packet.h).
QT_BODY_END, QT_FS, QT_TAIL = 1044, 17, 26


def qt128_body(p, keep, unit):
    """The body of a 0x1D QT128 packet with block b keeping its units at positions keep[b], each
    cut to `unit` bytes (3: distance and reflectivity; 4: and the confidence byte), then CRC1."""
    body = b''
    for b in range(2):
        blk = p[12 + 514 * b:12 + 514 * (b + 1)]
        body += blk[:2] + b''.join(blk[2 + 4 * u:2 + 4 * u + unit] for u in keep[b])
    return body + struct.pack('<I', crc32_mpeg2(body))


def qt128_with_flags(p, flags, sign=False, fs=None, keep=None, unix_time=None):
    """Rebuilds a 0x1D QT128 packet with other flags: units of 3 bytes, or 4 with bit 4; with keep,
    block b holds only the units at positions keep[b] (laser num = their count; set bit 6 for
    customised channels); sections per the flags; the date-time as Unix seconds (year byte 0)
    when unix_time is given; CRCs recomputed; the signature (if any) HMAC-SHA256 under KEY when
    sign, else all-zero."""
    assert p[11] == 0x1D and len(p) == 1127
    keep = keep or [range(128), range(128)]
    fs_bytes = fs if fs is not None else p[1044:1061]
    tail = bytearray(p[1061:1087])
    if unix_time is not None:
        tail[15:21] = bytes(2) + struct.pack('>I', unix_time)
    seq = p[1087:1091]
    header = bytearray(p[:12])
    header[6] = len(keep[0])
    header[11] = flags
    out = header + qt128_body(p, keep, 4 if flags & 0x10 else 3)
    if flags & 0x04:
        out += fs_bytes
    t0 = len(out)
    out += tail
    if flags & 0x01:
        out += seq
    out += struct.pack('<I', crc32_mpeg2(out[t0:]))
    if flags & 0x08:
        out += hmac.new(KEY, bytes(out), hashlib.sha256).digest() if sign else bytes(32)
    return bytes(out)


def channel_config_columns():
    """The bundled channel configuration's Loop1 and Loop2 columns, 0-based positions."""
    rows = open(os.path.join(DATA, 'calibration', 'qt128c2x_channel_config.csv')).read().split('\n')[3:]
    pairs = [r.split(',') for r in rows if r.count(',') == 1]
    return [[int(a) - 1 for a, _ in pairs], [int(b) - 1 for _, b in pairs]]


def fix_fs_crc(fs):
    fs = bytearray(fs)
    fs[13:17] = struct.pack('<I', crc32_mpeg2(fs[1:13]))
    return bytes(fs)


def gps_packet(layout, yy=24, mo=5, dd=17, hh=13, mi=42, ss=7, status=b'A', pps=1, nmea=None):
    def pair(v):
        return bytes([0x30 + v % 10, 0x30 + v // 10])  # units digit first
    p = bytearray(b'\xFF\xEE') + pair(yy) + pair(mo) + pair(dd) + pair(ss) + pair(mi) + pair(hh)
    p += struct.pack('<I', (mi * 60 + ss) * 1000000) if layout == 40 else bytes(4)
    size = 77 if layout == 40 else 84
    if nmea is None:
        body = 'GPRMC,134207.00,A,3110.4706,N,12123.1151,E,0.0,0.0,170524,,,A'
        x = 0
        for c in body:
            x ^= ord(c)
        nmea = ('$%s*%02X' % (body, x)).encode()
    p += nmea[:size].ljust(size, b'\x00')
    p += b'\xDF' * (506 - len(p))
    p += status + bytes([pps]) + bytes(4)
    assert len(p) == 512
    return bytes(p)


def write(harness, name, data):
    d = os.path.join(CORPUS, harness)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), 'wb') as f:
        f.write(data)


def pick(ps, count):
    """A few packets spread over the capture, with distinct return modes where there are."""
    step = max(1, len(ps) // count)
    return [ps[i] for i in range(0, len(ps), step)][:count]


def main():
    p40p = payloads('pandar40p_dual.pcap')
    p64 = payloads('pandar64_dual.pcap')
    qt = payloads('qt128c2x_dual.pcap')
    p40 = [p[:1240] + p[1240:1256] for p in p40p]  # Pandar40: 1240 bytes of blocks + 16-byte tail
    gps40, gps64 = gps_packet(40), gps_packet(64)

    sets = {'pandar40': p40, 'pandar40p': p40p, 'pandar64': p64, 'qt128': qt}
    for h, ps in sets.items():
        for i, p in enumerate(pick(ps, 3)):
            write(h, 'real_%d' % i, p)
        p = ps[0]
        for n in (0, 1, 4, 12, len(p) // 2, len(p) - 1):
            write(h, 'trunc_%d' % n, p[:n])
        write(h, 'long', p + b'\x00')
    # Pandar40P with its 4-byte UDP sequence, Pandar64 without.
    write('pandar40p', 'sequence', p40p[1] + struct.pack('<I', 1234))
    write('pandar64', 'no_sequence', p64[1][:1194])
    for flags in (0x00, 0x01, 0x04, 0x05, 0x08, 0x0D, 0x1D, 0x15, 0x09):
        write('qt128', 'flags_%02x' % flags, qt128_with_flags(qt[5], flags))
    write('qt128', 'imu_flag', qt128_with_flags(qt[5], 0x1F))
    write('qt128', 'custom_flag', qt128_with_flags(qt[5], 0x45))
    # Customised channels (bit 6) with the bundled configuration, both unit sizes; one unit.
    cols = channel_config_columns()
    loop = 0 if qt[5][1066] & 1 else 1  # dual return: both blocks fire block 1's sequence
    write('qt128', 'custom_80', qt128_with_flags(qt[5], 0x5D, keep=[cols[loop], cols[loop]]))
    write('qt128', 'custom_80_3byte', qt128_with_flags(qt[5], 0x4D, keep=[cols[loop], cols[loop]]))
    write('qt128', 'custom_1', qt128_with_flags(qt[5], 0x5D, keep=[[99], [99]]))
    # The date-time as Unix seconds (year byte 0): 2020-10-09 12:03:29 of packet 0.
    write('qt128', 'unix_time', qt128_with_flags(qt[0], 0x1D, unix_time=1602245009))
    write('qt128', 'unix_time_3byte', qt128_with_flags(qt[0], 0x0D, unix_time=1602245009))
    write('qt128', 'fs_fault', qt128_with_flags(qt[6], 0x05, fs=fix_fs_crc(bytes([1, 2, 0x11, 0x34, 0x12]) + bytes(8) + bytes(4))))

    # PandarQT64, protocol 3.1 (core/include/hesai/detail/qt64_packet.h): tail at 1044, flags byte 11.
    q64 = payloads('pandar_qt64.pcap')
    for i, p in enumerate(pick(q64, 3)):
        write('qt64', 'real_%d' % i, p)
    for n in (0, 1, 4, 12, len(q64[0]) // 2, len(q64[0]) - 1):
        write('qt64', 'trunc_%d' % n, q64[0][:n])
    write('qt64', 'long', q64[0] + b'\x00')

    def qt64_with(p, flags=None, tail=None):
        q = bytearray(p)
        if flags is not None:
            q[11] = flags
        for at, v in (tail or {}).items():
            q[1044 + at:1044 + at + len(v)] = v
        return bytes(q) if flags is None or flags & 1 else bytes(q[:1068])
    write('qt64', 'no_sequence', qt64_with(q64[5], flags=0x00))
    write('qt64', 'imu_flag', qt64_with(q64[5], flags=0x03))
    write('qt64', 'single_strongest', qt64_with(q64[5], tail={16: b'\x37'}))
    write('qt64', 'dual_last_strongest', qt64_with(q64[5], tail={16: b'\x39'}))
    write('qt64', 'unix_time', qt64_with(q64[0], tail={18: bytes(2) + struct.pack('>I', 1504708282)}))
    write('qt64', 'year_20', qt64_with(q64[0], tail={18: b'\x14'}))

    # Signature: signed under KEY (valid), unsigned (zeros), wrong key, no signature section.
    for i, p in enumerate(pick(qt, 2)):
        write('signature', 'signed_%d' % i, qt128_with_flags(p, 0x1D, sign=True))
        write('signature', 'signed_0d_%d' % i, qt128_with_flags(p, 0x0D, sign=True))
    write('signature', 'signed_08', qt128_with_flags(qt[3], 0x08, sign=True))
    write('signature', 'unsigned', qt128_with_flags(qt[3], 0x1D))
    write('signature', 'no_section', qt128_with_flags(qt[3], 0x15))
    bad = bytearray(qt128_with_flags(qt[3], 0x1D, sign=True))
    bad[-1] ^= 1
    write('signature', 'bad_mac', bytes(bad))
    write('signature', 'capture', qt[0])

    # GPS: both layouts, NMEA variants, a bad field each.
    write('gps', 'pandar40', gps40)
    write('gps', 'pandar64', gps64)
    gga = b'$GPGGA,134207.00,3110.4706,N,12123.1151,E,1,08,1.0,10.0,M,0.0,M,,*4F'
    write('gps', 'pandar64_gga', gps_packet(64, status=b'1', nmea=gga))
    write('gps', 'no_nmea', gps_packet(40, nmea=b''))
    write('gps', 'unlocked_v', gps_packet(40, status=b'V', pps=0))
    write('gps', 'bad_month', gps_packet(40, mo=13))
    write('gps', 'leap_day', gps_packet(64, yy=24, mo=2, dd=29))
    write('gps', 'bad_day', gps_packet(64, yy=23, mo=2, dd=29))
    write('gps', 'short', gps40[:511])
    write('gps', 'bad_status', gps40[:506] + b'X' + gps40[507:])

    # CSV files: the shipped files and short pieces of them.
    cal = os.path.join(DATA, 'calibration')
    for harness, files in (('angles_csv', ['pandar40p_unit_a_angles.csv', 'pandar64_unit_b_angles.csv',
                                           'qt128c2x_unit_a_angles.csv', 'pandar_qt64_angles.csv']),
                           ('firetimes_csv', ['pandar40p_firetimes.csv', 'pandar64_firetimes.csv',
                                              'qt128c2x_firetimes.csv', 'pandar_qt64_firetimes.csv']),
                           ('channel_config_csv', ['qt128c2x_channel_config.csv'])):
        for f in files:
            text = open(os.path.join(cal, f), 'rb').read()
            stem = f.replace('.csv', '')
            write(harness, stem, text)
            lines = text.splitlines(keepends=True)
            write(harness, stem + '_head', b''.join(lines[:4]))
            write(harness, stem + '_crlf', text.replace(b'\r\n', b'\n').replace(b'\n', b'\r\n'))
            write(harness, stem + '_bom', b'\xEF\xBB\xBF' + text)
            write(harness, stem + '_cut', text[:len(text) * 2 // 3])
    write('angles_csv', 'numbers', b'Channel,Elevation,Azimuth\n1,-1.5e+1,0.000001\n2,+15,-.5\n')

    # Captures: a few records of each capture as pcap (usec, nsec, big-endian) and pcapng.
    for name, tag in (('pandar40p_dual.pcap', '40p'), ('pandar64_dual.pcap', '64'), ('qt128c2x_dual.pcap', 'qt')):
        hdr, recs = pcap_records(name)
        write('capture', 'pcap_' + tag, hdr + b''.join(recs[:2]))
    hdr, recs = pcap_records('qt128c2x_dual.pcap')
    small = hdr + b''.join(recs[:2])
    write('capture', 'truncated', small[:len(small) - 100])
    write('capture', 'header_only', hdr)
    nsec = b'\x4D\x3C\xB2\xA1' + hdr[4:] + b''.join(recs[:1])
    write('capture', 'pcap_nsec', nsec)
    be = bytearray(struct.pack('>IHHiIII', 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
    for r in recs[:1]:
        ts, us, incl, orig = struct.unpack_from('<IIII', r)
        be += struct.pack('>IIII', ts, us, incl, orig) + r[16:]
    write('capture', 'pcap_big_endian', bytes(be))

    def block(btype, body):
        body += bytes((-len(body)) % 4)
        n = 12 + len(body)
        return struct.pack('<II', btype, n) + body + struct.pack('<I', n)
    shb = block(0x0A0D0D0A, struct.pack('<IHHq', 0x1A2B3C4D, 1, 0, -1))
    idb = block(1, struct.pack('<HHI', 1, 0, 65535) + struct.pack('<HHB3x', 9, 1, 9) + bytes(4))  # if_tsresol 9
    epbs = b''
    for r in recs[:2]:
        ts, us, incl, orig = struct.unpack_from('<IIII', r)
        t = ts * 10**9 + us * 1000
        epbs += block(6, struct.pack('<IIIII', 0, t >> 32, t & 0xFFFFFFFF, incl, orig) + r[16:])
    spb = block(3, struct.pack('<I', len(recs[0]) - 16) + recs[0][16:])
    write('capture', 'pcapng', shb + idb + epbs)
    write('capture', 'pcapng_spb', shb + idb + spb)
    write('capture', 'pcapng_trunc', (shb + idb + epbs)[:-50])

    # Frames: a cut byte, then u16 length + payload records.
    def stream(cut, ps):
        return bytes([cut]) + b''.join(struct.pack('<H', len(p)) + p for p in ps)
    write('frames', 'pandar64', stream(0, p64[:4]))
    write('frames', 'pandar64_gap', stream(64, [p64[0], p64[3], p64[2]]))
    write('frames', 'qt128', stream(128, qt[:4]))
    write('frames', 'pandar40_gps', stream(0, [p40[0], gps40, p40[1]]))
    write('frames', 'pandar40p', stream(200, p40p[:3]))
    write('frames', 'qt64', stream(0, q64[297:303]))
    write('frames', 'mixed', stream(10, [gps64, p64[10], qt[10], p40p[10], b'\xEE\xFF']))

    # The functional-safety monitor: a rolling counter held 10, 21 and 25 ms (a stall at 21 ms),
    # faults, then the time going back 0.5 s and a 100 ms gap (QT128C2X manual 3.1.2, "Functional
    # Safety": state [7:5], fault type [4:3], rolling counter [2:0] of byte 1).
    def qt_fs(p, us, state, fault_type, counter, fault=(0, 0, 0)):
        total, fid, code = fault
        q = bytearray(p)
        q[1061 + 21:1061 + 25] = struct.pack('<I', us)  # tail timestamp (CRC3 recomputed)
        fs = bytearray(p[1044:1061])
        fs[1] = state << 5 | fault_type << 3 | counter
        fs[2] = total << 4 | fid
        fs[3:5] = struct.pack('<H', code)
        return qt128_with_flags(bytes(q), 0x1D, fs=fix_fs_crc(fs))
    write('frames', 'qt128_safety', stream(0, [
        qt_fs(qt[0], 600000, 1, 0, 2), qt_fs(qt[1], 610000, 1, 0, 2), qt_fs(qt[2], 621000, 2, 1, 2, (2, 1, 0x0102)),
        qt_fs(qt[3], 625000, 4, 2, 2, (2, 2, 0x0304)), qt_fs(qt[4], 100000, 6, 3, 3), qt_fs(qt[5], 200000, 7, 0, 3)]))

    # PandarXT16/XT32/XT32M2X, protocol 6.1 (core/include/hesai/detail/xt_packet.h): real packets, cuts,
    # every return mode of the family on the XT32M2X (triple with its block azimuths in threes),
    # the Unix-seconds date-time (year byte 0) and the sequence flag clear; frames across a gap.
    xts = {n: payloads('pandar_%s.pcap' % n) for n in ('xt16', 'xt32', 'xt32m2x')}
    for n, ps in xts.items():
        for i, p in enumerate(pick(ps, 2)):
            write('xt', '%s_real_%d' % (n, i), p)
        write('xt', n + '_trunc', ps[0][:len(ps[0]) // 2])
        write('xt', n + '_long', ps[0] + b'\x00')
        write('xt', n + '_no_sequence', ps[0][:11] + b'\x00' + ps[0][12:])

    def xt_tail(p, at, data):
        t = len(p) - 28
        return p[:t + at] + data + p[t + at + len(data):]
    m2x = xts['xt32m2x'][3]
    for mode in (0x33, 0x37, 0x38, 0x39, 0x3B, 0x3D):
        write('xt', 'xt32m2x_mode_%02x' % mode, xt_tail(m2x, 10, bytes([mode])))
    triple = bytearray(xt_tail(m2x, 10, b'\x3d'))
    for b in range(6):
        triple[12 + b * 130:14 + b * 130] = struct.pack('<H', 1000 if b < 3 else 1018)
    write('xt', 'xt32m2x_triple', bytes(triple))
    write('xt', 'xt32_unix_time', xt_tail(xts['xt32'][0], 13, b'\x00\x00' + struct.pack('>I', 1564024769)))
    write('frames', 'xt32m2x_gap', stream(0, xts['xt32m2x'][757:760] + xts['xt32m2x'][1200:1202]))
    write('frames', 'xt_mixed', stream(90, [xts['xt16'][0], xts['xt32'][0], xts['xt32m2x'][0], xts['xt16'][1]]))
    for harness, f in (('angles_csv', 'pandar_xt32m2x_angles.csv'), ('angles_csv', 'pandar_xt16_angles.csv'),
                       ('firetimes_csv', 'pandar_xt32m2x_firetimes.csv'), ('firetimes_csv', 'pandar_xt16_firetimes.csv')):
        write(harness, f.replace('.csv', ''), open(os.path.join(cal, f), 'rb').read())
    hdr, recs = pcap_records('pandar_xt32m2x.pcap')
    write('capture', 'pcap_xt32m2x', hdr + b''.join(recs[:2]))

    # PTC responses (fuzz_ptc.cpp): a command index byte, then the response. Layouts from nebula's
    # hesai_cmd_response.hpp: inventory 120 bytes (QT128: 144), configuration 47, status 17 + 4 x
    # temperatures + 5 reserved.
    cmds = [0x05, 0x07, 0x08, 0x09, 0x2D, 0x2E, 0x2F, 0xA8, 0xA9]

    def ptc(cmd, payload, code=0, magic=b'Gt', echo=None, length=None):
        n = len(payload) if length is None else length
        return bytes([cmds.index(cmd)]) + magic + bytes([cmd if echo is None else echo, code]) + struct.pack('>I', n) + payload
    common = b'SN0123456789ABCDEF' + b'2020-10-09'.ljust(16, b'\0') + bytes([0, 0x11, 0x22, 0x33, 0x44, 0x55])
    common += b''.join(v.ljust(16, b'\0') for v in (b'1.2.3', b'hw', b'ctl', b'sensor'))
    write('ptc', 'inventory_xt32', ptc(0x07, common + struct.pack('>h', 0) + bytes([25, 0, 32]) + bytes(11)))
    write('ptc', 'inventory_qt128', ptc(0x07, common + struct.pack('>hh', 0, 0) + bytes([32, 0, 128]) + bytes(33)))
    write('ptc', 'inventory_common_only', ptc(0x07, common))
    write('ptc', 'config', ptc(0x08, bytes([192, 168, 1, 201, 255, 255, 255, 0, 192, 168, 1, 1, 255, 255, 255, 255]) +
                               struct.pack('>HHHBHHHBBBBBBBHBBB', 2368, 10110, 600, 0, 0, 0, 3600, 0, 1, 0, 0x39, 0, 1, 0, 0,
                                           0, 0, 0) + bytes(6)))
    for temps, name in ((8, 'status_8'), (9, 'status_9')):
        write('ptc', name, ptc(0x09, struct.pack('>IH', 3600, 600) + b''.join(struct.pack('>i', 2500 + i) for i in range(temps)) +
                               bytes([1, 1]) + struct.pack('>IIB', 7, 120, 2) + bytes(5)))
    write('ptc', 'session_start', ptc(0x2E, bytes(range(32))))
    write('ptc', 'signature_state', ptc(0x2D, b'\x01'))
    write('ptc', 'signature_stop', ptc(0x2F, b''))
    write('ptc', 'calibration', ptc(0x05, open(os.path.join(cal, 'qt128c2x_unit_a_angles.csv'), 'rb').read()[:300]))
    # The six ways a sensor can misbehave (ctest Sensor.*Hostile* runs them against the client).
    write('ptc', 'hostile_magic', ptc(0x07, common, magic=b'XY'))
    write('ptc', 'hostile_echo', ptc(0x07, common, echo=0x09))
    write('ptc', 'hostile_length', ptc(0x05, b'', length=0xFFFFFFF0))
    write('ptc', 'hostile_silence', bytes([cmds.index(0x07)]))
    write('ptc', 'hostile_cut_short', ptc(0x07, common[:10], length=120))
    write('ptc', 'hostile_error_code', ptc(0x07, b'', code=5))

    # Settings files of 'sensor apply' (fuzz_settings_file.cpp): every key, each number form JSON
    # has, and the refusals of issue #44 (a NUL in a number, a leading zero, a control byte).
    write('settings_file', 'every_key', b'{\n  "rpm": 1200,\n  "return_mode": "strongest",\n  "standby": "off",\n'
          b'  "sync_angle": 30,\n  "destination": "192.168.1.100:2368,10110",\n  "fov": "30.5-330"\n}\n')
    write('settings_file', 'empty_object', b'{}')
    write('settings_file', 'sync_off', b'{"sync_angle": "off", "standby": "on"}')
    write('settings_file', 'numbers', b'{"rpm": -0.5e+10, "sync_angle": 0E-0}')
    write('settings_file', 'escapes', b'{"return_mode": "a\\"b\\\\c"}')
    write('settings_file', 'nul_in_number', b'{"rpm": 12\x0000}')
    write('settings_file', 'leading_zero', b'{"rpm": 01200}')
    write('settings_file', 'control_byte', b'{"standby": "on\x1b[2J"}')
    write('settings_file', 'wrong_types', b'{"standby": true, "rpm": [1], "fov": {}, "sync_angle": null}')
    write('settings_file', 'twice_unknown', b'{"rpm": 600,\r\n"rpm": 600, "colour\x7f\xff": 1}')
    write('settings_file', 'trailing', b'{"rpm": 600} x')

    # MCAP bags of PandarScan (fuzz_mcap.cpp), written by tests/mcap/make_pandarscan.py.
    import sys
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    sys.path.insert(0, os.path.join(HERE, '..', 'tests', 'mcap'))
    import make_pandarscan as mp
    timed = [(1593086529977341000 + i * 1000000, p) for i, p in enumerate(p64[:4] + qt[:2])]
    write('mcap', 'unchunked', mp.write_bag(timed, per_scan=2, frame_id='hesai'))
    write('mcap', 'chunked_crc_other_topic', mp.write_bag(timed, chunk_bytes=3000, per_scan=2, frame_id='lidar_top',
                                                          other_topic=True))
    write('mcap', 'chunked_no_crc', mp.write_bag(timed[:3], chunk_bytes=1, crc=False, per_scan=1, frame_id='ab'))
    write('mcap', 'cut', mp.write_bag(timed[:2], per_scan=1)[:-2000])
    bag = mp.Bag()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 1, '/pandar_packets')
    bag.open_chunk()
    bag.message(1, 0, mp.cdr_scan(timed[:1]))
    bag.close_chunk(compression='zstd')
    write('mcap', 'compressed_zstd', bag.finish())
    bag = mp.Bag()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 1, '/pandar_packets')
    bag.message(1, 0, mp.cdr_scan(timed[:2], count=3))
    bag.message(1, 0, mp.cdr_scan(timed[:1], sizes=[1501]))
    write('mcap', 'bad_cdr_count', bag.finish())
    bag = mp.Bag()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 1, '/pandar_packets')
    bag.message(1, 0, mp.cdr_scan(timed[:1], sizes=[1501]))
    write('mcap', 'bad_packet_size', bag.finish())
    bag = mp.Bag()
    bag.schema(2, 'std_msgs/msg/String', data='string data\n')
    bag.channel(2, 2, '/chatter')
    bag.channel(3, 5, '/unknown_schema')
    write('mcap', 'unknown_schema', bag.finish())

    # One real packet per model for the calibration harnesses (decoded under the parsed files).
    with open(os.path.join(HERE, 'seed_packets.inc'), 'w') as f:
        f.write('// Generated by fuzz/make_corpus.py from data/*.pcap: one real packet per model.\n')
        for name, p in (('kPandar40P', p40p[7]), ('kPandar64', p64[7]), ('kQt128', qt[7]), ('kQt64', q64[7]),
                        ('kXt16', xts['xt16'][7]), ('kXt32', xts['xt32'][7]), ('kXt32m2x', xts['xt32m2x'][7])):
            f.write('inline constexpr unsigned char %s[%d] = {\n' % (name, len(p)))
            for i in range(0, len(p), 24):
                f.write('  ' + ','.join('%d' % b for b in p[i:i + 24]) + ',\n')
            f.write('};\n')
    total = sum(os.path.getsize(os.path.join(dp, fn)) for dp, _, fns in os.walk(CORPUS) for fn in fns)
    print('corpus: %d bytes' % total)


if __name__ == '__main__':
    main()
