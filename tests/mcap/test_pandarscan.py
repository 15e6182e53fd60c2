#!/usr/bin/env python3
"""MCAP input: `hesai stats`, `decode` and `replay` on rosbag2 MCAP bags of PandarScan messages
made by make_pandarscan.py (an independent writer) from the bundled captures.

Usage: test_pandarscan.py HESAI DATA_DIR WORK_DIR [--memory]
HESAI_RUN_PREFIX (environment): words put before HESAI (cross builds: the qemu-user emulator).

Proves, for every bundled capture: `stats --json` on the bag (unchunked; chunked with CRCs, with a
second, non-PandarScan topic; chunked without CRCs) equals `stats --json` on the pcap, key by key;
`decode --format csv` gives the same bytes (under an emulator, for the chunked bag only).
`replay` of a bag sends the pcap's payloads in order.
Then each damaged file gives exit 2 and its own code at the byte offset where the writer put the
damaged record (never a value read back from the program), and a compressed chunk's message names
the compression and the commands that rewrite the file uncompressed. A bag cut at a record boundary
(before a message, after the Data End or the Footer, inside the closing magic) is mcap_cut, with
every point before the cut still written.
With --memory, only: `stats` on a bag of more than 256 MiB peaks under 64 MiB resident.
"""
import json
import os
import socket
import struct
import subprocess
import sys
import threading

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_pandarscan as mp  # noqa: E402

FAILURES = []
# Cross builds run the program under qemu-user (HESAI_RUN_PREFIX), where each decode of a capture
# costs seconds: there `stats` still reads every bag, and the CSV is compared for the chunked one.
# The three bags share the reader's code past the chunk layer, and `stats` equal key by key proves
# each read the same packets; natively the CSV of every bag is compared.
EMULATED = bool(os.environ.get('HESAI_RUN_PREFIX', '').split())


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print('FAIL: ' + what)


def run(hesai, args, **kw):
    prefix = os.environ.get('HESAI_RUN_PREFIX', '').split()
    return subprocess.run(prefix + [hesai] + args, capture_output=True, timeout=300, **kw)


def stats(hesai, path):
    r = run(hesai, ['stats', path, '--json'])
    return r.returncode, (json.loads(r.stdout) if r.returncode == 0 else None), r.stderr.decode()


def split_sensor(csv):
    """The CSV without its last column (the sensor: an address for a pcap, the topic for a bag),
    and the set of that column's values."""
    rows, sensors = [], set()
    for line in csv.split(b'\n'):
        head, _, sensor = line.rpartition(b',')
        rows.append(head)
        if line and not line.startswith(b'frame,'):
            sensors.add(sensor)
    return b'\n'.join(rows), sensors


def same_output(hesai, work, name, pcap, bags):
    code, want, err = stats(hesai, pcap)
    check(code == 0, '%s: stats on the pcap: %s' % (name, err))
    r = run(hesai, ['decode', pcap, '--format', 'csv', '--out', '-', '--quiet'])
    check(r.returncode == 0, '%s: decode of the pcap' % name)
    want_csv, want_sensors = split_sensor(r.stdout)
    check(want_sensors == {b'192.168.1.201:10000'}, '%s: the pcap\'s sensor column %r' % (name, want_sensors))
    for variant, data in bags:
        path = os.path.join(work, '%s_%s.mcap' % (name, variant))
        with open(path, 'wb') as f:
            f.write(data)
        code, got, err = stats(hesai, path)
        check(code == 0, '%s %s: stats exit %d: %s' % (name, variant, code, err))
        if got is None:
            continue
        check(set(got) == set(want), '%s %s: keys differ: %s' % (name, variant, set(got) ^ set(want)))
        for k in want:
            check(got.get(k) == want[k], '%s %s: %s = %r, pcap %r' % (name, variant, k, got.get(k), want[k]))
        if EMULATED and variant != 'chunked':
            continue  # under qemu: the CSV of the chunked bag (chunks, CRCs, another topic) only
        r = run(hesai, ['decode', path, '--format', 'csv', '--out', '-', '--quiet'])
        check(r.returncode == 0, '%s %s: decode exit %d' % (name, variant, r.returncode))
        got_csv, got_sensors = split_sensor(r.stdout)
        check(got_csv == want_csv, '%s %s: the CSV differs from the pcap\'s (%d vs %d bytes)' %
              (name, variant, len(got_csv), len(want_csv)))
        # A bag's sensor is its PandarScan topic.
        check(got_sensors == {b'/pandar_packets'}, '%s %s: the sensor column %r' % (name, variant, got_sensors))
    return want['packets']


def replay_sends_payloads(hesai, work, pcap):
    payloads = mp.pcap_payloads(pcap)
    path = os.path.join(work, 'replay.mcap')
    with open(path, 'wb') as f:
        f.write(mp.write_bag(payloads, chunk_bytes=200000))
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 8 << 20)
    sock.bind(('127.0.0.1', 0))
    sock.settimeout(5)
    port = sock.getsockname()[1]
    got = []

    def receive():
        try:
            while len(got) < len(payloads):
                got.append(sock.recv(2048))
        except socket.timeout:
            pass
    t = threading.Thread(target=receive)
    t.start()
    r = run(hesai, ['replay', path, '--to', '127.0.0.1:%d' % port, '--rate', '1'])
    t.join()
    sock.close()
    check(r.returncode == 0, 'replay exit %d: %s' % (r.returncode, r.stderr.decode()))
    check(got == [p for _, p in payloads], 'replay: %d of %d datagrams, equal: %s' %
          (len(got), len(payloads), got == [p for _, p in payloads][:len(got)]))


def expect_error(hesai, work, name, data, code, offset, also=()):
    path = os.path.join(work, 'bad_%s.mcap' % name)
    with open(path, 'wb') as f:
        f.write(data)
    for command in (['stats', path, '--json'], ['decode', path, '--out', os.devnull, '--quiet']):
        r = run(hesai, command)
        err = r.stderr.decode()
        check(r.returncode == 2, '%s (%s): exit %d, want 2: %s' % (name, command[0], r.returncode, err))
        want = '%s at byte %d' % (code, offset)
        check(want in err, '%s (%s): want "%s" in: %s' % (name, command[0], want, err))
        for text in also:
            check(text in err, '%s (%s): want "%s" in: %s' % (name, command[0], text, err))


def damaged_files(hesai, work, pcap):
    pay = mp.pcap_payloads(pcap)[:30]
    scans = mp.scan_messages(pay, 10)

    def base(chunked=False, crc=True):
        bag = mp.Bag()
        if chunked:
            bag.open_chunk()
        bag.schema(1, 'pandar_msgs/msg/PandarScan')
        bag.channel(1, 1, '/pandar_packets')
        return bag

    def scan_msg(bag, scan, name=None, **kw):
        bag.message(1, scan[0][0], mp.cdr_scan(scan, **kw), name=name,
                    packet_at=mp.packet_positions(scan, kw.get('frame_id', 'hesai')))

    # A record whose length passes the end of the file (the file cut inside the third message).
    bag = base()
    for i, s in enumerate(scans):
        scan_msg(bag, s, name='m%d' % i)
    data = bag.finish()
    expect_error(hesai, work, 'record_past_end', data[:bag.offsets['m2'] + 100], 'capture_truncated', bag.offsets['m2'])

    # A chunk whose records do not match its CRC: one payload byte changed after the CRC was taken.
    bag = base(chunked=True)
    for s in scans:
        scan_msg(bag, s)
    records, names, packets = bag.chunk
    crc = __import__('zlib').crc32(bytes(records)) & 0xFFFFFFFF
    records[-100] ^= 0xFF
    bag.chunk = (records, names, packets)
    chunk_at = len(bag.out)
    # close_chunk computes the CRC of what it writes: give it the damaged records with the old CRC.
    head = struct.pack('<QQQI', 0, 0, len(records), crc) + mp.string('') + struct.pack('<Q', len(records))
    bag.chunk = None
    bag.out += mp.record(mp.OP_CHUNK, head + bytes(records))
    expect_error(hesai, work, 'chunk_crc', bag.finish(), 'mcap_chunk_crc_mismatch', chunk_at)

    # A channel on a schema id that no Schema record defined.
    bag = mp.Bag()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 7, '/pandar_packets', rec_name='ch')
    expect_error(hesai, work, 'unknown_schema', bag.finish(), 'mcap_unknown_schema', bag.offsets['ch'])

    # A message on a channel id that no Channel record defined.
    bag = base()
    scan_msg(bag, scans[0])
    bag.message(9, 0, mp.cdr_scan(scans[1]), name='m')
    expect_error(hesai, work, 'unknown_channel', bag.finish(), 'mcap_unknown_channel', bag.offsets['m'])

    # A PandarScan channel whose messages are not CDR.
    bag = mp.Bag()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 1, '/pandar_packets', encoding='json', rec_name='ch')
    expect_error(hesai, work, 'not_cdr', bag.finish(), 'mcap_bad_encoding', bag.offsets['ch'])

    # A message too short for its CDR: the sequence announces 11 packets, 10 follow (in a chunk).
    bag = base(chunked=True)
    scan_msg(bag, scans[0])
    scan_msg(bag, scans[1], name='m', count=11)
    bag.close_chunk()
    expect_error(hesai, work, 'short_cdr', bag.finish(), 'mcap_bad_cdr', bag.offsets['m'])

    # A message whose frame_id string runs past its end.
    bag = base()
    body = bytearray(mp.cdr_scan(scans[0]))
    struct.pack_into('<I', body, 12, 1 << 30)
    bag.message(1, 0, bytes(body), name='m')
    expect_error(hesai, work, 'string_past_end', bag.finish(), 'mcap_bad_cdr', bag.offsets['m'])

    # Big-endian CDR (encapsulation 00 00), which this reader does not read.
    bag = base()
    scan_msg(bag, scans[0], name='m', encapsulation=b'\x00\x00\x00\x00')
    expect_error(hesai, work, 'big_endian_cdr', bag.finish(), 'mcap_bad_cdr', bag.offsets['m'])

    # A packet whose size is above its 1500 data bytes: the 4th packet of the 2nd scan.
    bag = base()
    scan_msg(bag, scans[0])
    sizes = [len(p) for _, p in scans[1]]
    sizes[3] = 1501
    scan_msg(bag, scans[1], sizes=sizes)
    expect_error(hesai, work, 'size_above_data', bag.finish(), 'mcap_bad_packet_size', bag.packet_offsets[13])

    # No PandarScan channel at all: the error comes at the end of the data section, at the byte
    # after the Data End record.
    bag = mp.Bag()
    bag.schema(2, 'std_msgs/msg/String', data='string data\n')
    bag.channel(2, 2, '/chatter')
    bag.message(2, 0, b'\x00\x01\x00\x00' + struct.pack('<I', 3) + b'hi\x00')
    bag.add(mp.OP_DATA_END, struct.pack('<I', 0), name='end')
    bag.add(mp.OP_FOOTER, struct.pack('<QQI', 0, 0, 0))
    data = bag.finish(data_end=False) + mp.MAGIC
    expect_error(hesai, work, 'no_pandar_scan', data, 'mcap_no_pandar_scan', bag.offsets['end'] + 9 + 4)

    # A record inside a chunk whose length passes the chunk's end.
    bag = base(chunked=True)
    scan_msg(bag, scans[0], name='m')
    records, names, packets = bag.chunk
    inner = dict(names)['m']
    struct.pack_into('<Q', records, inner + 1, len(records))  # longer than what is left
    bag.close_chunk()
    expect_error(hesai, work, 'chunk_record_past_end', bag.finish(), 'capture_bad_record',
                 bag.offsets['m'])

    # Not an MCAP file after all: the magic, then no Header record.
    expect_error(hesai, work, 'no_header', mp.MAGIC + mp.record(mp.OP_FOOTER, b'\x00' * 20) + mp.MAGIC,
                 'capture_bad_record', 8)

    # Compressed chunks: the message names the compression and how to rewrite the file.
    for compression in ('zstd', 'lz4'):
        bag = base()
        bag.open_chunk()
        scan_msg(bag, scans[0])
        bag.close_chunk(compression=compression, name='chunk')
        expect_error(hesai, work, 'compressed_' + compression, bag.finish(), 'mcap_compressed_chunk',
                     bag.offsets['chunk'],
                     also=("'%s'" % compression, 'mcap decompress IN.mcap -o OUT.mcap', 'ros2 bag convert',
                           'compression: "None"'))

    cut_bags(hesai, work, base, scan_msg, scans)

    # Damaged part-way: stats gives the counters up to the damage (the first two scans).
    bag = base()
    for s in scans[:2]:
        scan_msg(bag, s)
    bag.message(9, 0, mp.cdr_scan(scans[2]))
    path = os.path.join(work, 'bad_partway.mcap')
    with open(path, 'wb') as f:
        f.write(bag.finish())
    r = run(hesai, ['stats', path])
    check(r.returncode == 2 and b'packets' in r.stdout and b'20' in r.stdout,
          'part-way damage: exit %d, stdout %r' % (r.returncode, r.stdout[:200]))


def cut_bags(hesai, work, base, scan_msg, scans):
    """A bag cut at a record boundary is an error (mcap_cut, exit 2), not a whole bag: cut before
    a message, after the Data End, after the Footer, inside the closing magic. decode still writes
    every point before the cut: its CSV equals that of a whole bag of the messages before it."""
    bag = base()
    for i, s in enumerate(scans):
        scan_msg(bag, s, name='m%d' % i)
    data = bag.finish()
    # Records before m2: Header, Schema, Channel, m0, m1.
    cut = bag.offsets['m2']
    expect_error(hesai, work, 'cut_before_message', data[:cut], 'mcap_cut', cut, also=('cut after record 5 ',))
    whole = base()
    for s in scans[:2]:
        scan_msg(whole, s)
    with open(os.path.join(work, 'first_two.mcap'), 'wb') as f:
        f.write(whole.finish())
    with open(os.path.join(work, 'cut_before_message.mcap'), 'wb') as f:
        f.write(data[:cut])
    want = run(hesai, ['decode', os.path.join(work, 'first_two.mcap'), '--out', '-', '--quiet'])
    got = run(hesai, ['decode', os.path.join(work, 'cut_before_message.mcap'), '--out', '-', '--quiet'])
    check(want.returncode == 0 and want.stdout.count(b'\n') > 1000,
          'whole bag of two scans: exit %d, %d lines' % (want.returncode, want.stdout.count(b'\n')))
    check(got.returncode == 2 and got.stdout == want.stdout,
          'cut bag: exit %d, %d CSV bytes, the whole two-scan bag\'s %d' % (got.returncode, len(got.stdout), len(want.stdout)))
    # The tail: Data End (9 + 4 bytes), Footer (9 + 20), the magic (8). Records: the five, m2, Data End.
    footer = len(data) - 8 - 29
    expect_error(hesai, work, 'cut_after_data_end', data[:footer], 'mcap_cut', footer, also=('cut after record 7 ',))
    expect_error(hesai, work, 'cut_after_footer', data[:-8], 'mcap_cut', len(data) - 8)
    expect_error(hesai, work, 'cut_in_magic', data[:-3], 'mcap_cut', len(data) - 3)
    # A bag that ends at its Footer (no Data End), then the magic, is whole.
    bag = base()
    scan_msg(bag, scans[0])
    bag.add(mp.OP_FOOTER, struct.pack('<QQI', 0, 0, 0))
    path = os.path.join(work, 'footer_no_data_end.mcap')
    with open(path, 'wb') as f:
        f.write(bag.finish(data_end=False) + mp.MAGIC)
    code, got_stats, err = stats(hesai, path)
    check(code == 0 and got_stats['packets'] == len(scans[0]),
          'Footer without Data End: exit %d, %s' % (code, err))


def hostile_topics(hesai, work, pcap):
    """Two sensors in one bag, one on a topic holding '"' and '\\' (printable, so it names its
    sensor): `stats --json` stays valid JSON and names both topics exactly (issue #42)."""
    payloads = mp.pcap_payloads(pcap)[:200]
    topics = ['/lidar"front\\top', '/lidar/rear']
    bag = mp.Bag()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    for cid, topic in enumerate(topics, 1):
        bag.channel(cid, 1, topic)
    for i, scan in enumerate(mp.scan_messages(payloads, 20)):
        bag.message(1 + i % 2, scan[0][0], mp.cdr_scan(scan, 'hesai'))
    path = os.path.join(work, 'hostile_topics.mcap')
    with open(path, 'wb') as f:
        f.write(bag.finish())
    r = run(hesai, ['stats', path, '--json'])
    try:
        got = json.loads(r.stdout)
    except ValueError as e:
        check(False, 'stats --json of a bag whose topic holds \'"\': not JSON (%s): %r' % (e, r.stdout[:300]))
        return
    check(r.returncode == 0 and [s['source'] for s in got.get('sensors', [])] == topics,
          'hostile topics: exit %d, sources %r' % (r.returncode, [s.get('source') for s in got.get('sensors', [])]))


def bounded_memory(hesai, work, pcap):
    """`stats` on a bag of more than 256 MiB (the capture's packets as one chunk, repeated) peaks
    under 64 MiB resident, as the kernel reports it for the child (wait4's rusage)."""
    bag = mp.Bag()
    head = bytes(bag.out)
    bag.open_chunk()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 1, '/pandar_packets')
    for scan in mp.scan_messages(mp.pcap_payloads(pcap), 50):
        bag.message(1, scan[0][0], mp.cdr_scan(scan))
    bag.close_chunk()
    chunk = bytes(bag.out[len(head):])
    repeats = (256 << 20) // len(chunk) + 1
    path = os.path.join(work, 'large.mcap')
    with open(path, 'wb') as f:
        f.write(head)
        for _ in range(repeats):
            f.write(chunk)
        f.write(mp.record(mp.OP_DATA_END, struct.pack('<I', 0)))
        f.write(mp.record(mp.OP_FOOTER, struct.pack('<QQI', 0, 0, 0)) + mp.MAGIC)
    try:
        size = os.path.getsize(path)
        p = subprocess.Popen([hesai, 'stats', path, '--json'], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        out, err = p.stdout.read(), p.stderr.read()
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        check(p.returncode == 0, 'large bag: exit %d: %s' % (p.returncode, err.decode()))
        packets = json.loads(out)['packets'] if p.returncode == 0 else 0
        check(packets == repeats * len(mp.pcap_payloads(pcap)), 'large bag: %d packets' % packets)
        check(usage.ru_maxrss < 64 * 1024, 'large bag of %d MiB: peak RSS %d MiB' % (size >> 20, usage.ru_maxrss >> 10))
        print('large bag: %d MiB, %d packets, peak RSS %d MiB' % (size >> 20, packets, usage.ru_maxrss >> 10))
    finally:
        os.remove(path)


def main():
    hesai, data_dir, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    if sys.argv[4:] == ['--memory']:
        bounded_memory(hesai, work, os.path.join(data_dir, 'pandar64_dual.pcap'))
        print('%d failures' % len(FAILURES) if FAILURES else 'all checks passed')
        return 1 if FAILURES else 0
    captures = sorted(f for f in os.listdir(data_dir) if f.endswith('.pcap'))
    check(len(captures) >= 7, 'bundled captures: %d' % len(captures))
    for c in captures:
        pcap = os.path.join(data_dir, c)
        payloads = mp.pcap_payloads(pcap)
        name = c[:-5]
        bags = [('unchunked', mp.write_bag(payloads, per_scan=60, frame_id='hesai')),
                ('chunked', mp.write_bag(payloads, chunk_bytes=300000, per_scan=36, frame_id='lidar_top',
                                         other_topic=True)),
                ('chunked_no_crc', mp.write_bag(payloads, chunk_bytes=1 << 20, crc=False, per_scan=1,
                                                frame_id='ab'))]
        n = same_output(hesai, work, name, pcap, bags)
        check(n == len(payloads), '%s: stats counts %s packets, the pcap holds %d UDP payloads' % (name, n, len(payloads)))
        print('%s: %d packets, 3 bags agree with the pcap' % (name, len(payloads)))
    replay_sends_payloads(hesai, work, os.path.join(data_dir, 'pandar40p_dual.pcap'))
    damaged_files(hesai, work, os.path.join(data_dir, 'pandar64_dual.pcap'))
    hostile_topics(hesai, work, os.path.join(data_dir, 'pandar64_dual.pcap'))
    if FAILURES:
        print('%d failures' % len(FAILURES))
        return 1
    print('all checks passed')
    return 0


if __name__ == '__main__':
    sys.exit(main())
