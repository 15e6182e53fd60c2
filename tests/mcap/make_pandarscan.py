#!/usr/bin/env python3
"""Writes a rosbag2 MCAP file of nebula's pandar_msgs/msg/PandarScan from a classic pcap's UDP
payloads, independently of the library: written from the MCAP specification (https://mcap.dev/spec)
and the message definitions of tier4/nebula (src/nebula_hesai/pandar_msgs/msg/):

    PandarScan.msg:    std_msgs/Header header, PandarPacket[] packets
    PandarPacket.msg:  builtin_interfaces/Time stamp, uint8[1500] data, uint32 size

serialised as ROS 2 CDR: the encapsulation header 00 01 00 00 (little-endian), then each primitive
aligned to its own size counted from the byte after that header.

As a module: Bag builds a file record by record and remembers where each record starts, so a test
can name the byte offset an error must report. As a program:
    make_pandarscan.py CAPTURE.pcap OUT.mcap [--chunk-bytes N] [--no-crc] [--per-scan N]
"""
import argparse
import struct
import zlib

MAGIC = b'\x89MCAP0\r\n'
OP_HEADER, OP_FOOTER, OP_SCHEMA, OP_CHANNEL, OP_MESSAGE, OP_CHUNK = 0x01, 0x02, 0x03, 0x04, 0x05, 0x06
OP_MESSAGE_INDEX, OP_DATA_END = 0x07, 0x0F
PACKET_DATA = 1500

SCAN_DEFINITION = (
    'std_msgs/Header header\nPandarPacket[] packets\n'
    '================================================================================\n'
    'MSG: pandar_msgs/PandarPacket\n'
    'builtin_interfaces/Time stamp\nuint8[1500] data\nuint32 size\n')


def pcap_payloads(path):
    """(time_ns, UDP payload) of every IPv4 UDP datagram of an Ethernet pcap (microsecond or
    nanosecond, little-endian), in file order."""
    d = open(path, 'rb').read()
    magic, = struct.unpack_from('<I', d, 0)
    assert magic in (0xA1B2C3D4, 0xA1B23C4D), 'little-endian classic pcap only'
    frac_ns = 1000 if magic == 0xA1B2C3D4 else 1
    assert struct.unpack_from('<I', d, 20)[0] & 0xFFFF == 1, 'Ethernet captures only'
    off, out = 24, []
    while off + 16 <= len(d):
        sec, frac, incl, _ = struct.unpack_from('<IIII', d, off)
        frame = d[off + 16:off + 16 + incl]
        off += 16 + incl
        if len(frame) < 34 or struct.unpack_from('>H', frame, 12)[0] != 0x0800 or frame[14 + 9] != 17:
            continue
        ihl = (frame[14] & 15) * 4
        udp = 14 + ihl
        length = struct.unpack_from('>H', frame, udp + 4)[0]
        out.append((sec * 1000000000 + frac * frac_ns, frame[udp + 8:udp + length]))
    return out


def string(s):
    b = s.encode() if isinstance(s, str) else s
    return struct.pack('<I', len(b)) + b


def record(op, body):
    return struct.pack('<BQ', op, len(body)) + body


def cdr_scan(packets, frame_id='hesai', stamp_ns=None, count=None, encapsulation=b'\x00\x01\x00\x00',
             sizes=None):
    """A PandarScan in CDR. `packets`: (time_ns, payload). `count`, `sizes` override the packet
    count and size fields (for damaged messages)."""
    t = packets[0][0] if stamp_ns is None and packets else (stamp_ns or 0)
    body = bytearray(struct.pack('<iI', t // 1000000000, t % 1000000000))
    fid = frame_id.encode() + b'\x00'
    body += struct.pack('<I', len(fid)) + fid
    body += b'\x00' * (-len(body) % 4)  # align the sequence length to 4
    body += struct.pack('<I', len(packets) if count is None else count)
    for i, (ns, payload) in enumerate(packets):
        assert len(body) % 4 == 0
        assert len(payload) <= PACKET_DATA
        body += struct.pack('<iI', ns // 1000000000, ns % 1000000000)
        body += payload + b'\x00' * (PACKET_DATA - len(payload))
        body += struct.pack('<I', len(payload) if sizes is None else sizes[i])
    return encapsulation + bytes(body)


class Bag:
    """An MCAP file built record by record. `offsets[name]` is the file offset of a record given
    a name; `packet_offsets` the file offset of each PandarPacket (its stamp)."""

    def __init__(self):
        self.out = bytearray(MAGIC)
        self.offsets = {}
        self.packet_offsets = []
        self.chunk = None  # open chunk: bytearray of its records, and its record names
        self.sequence = 0
        self.add(OP_HEADER, string('ros2') + string('make_pandarscan.py'))

    def _place(self, op, body, name):
        rec = record(op, body)
        if self.chunk is not None:
            self.chunk[1].append((name, len(self.chunk[0])))
            self.chunk[0].extend(rec)
        else:
            if name:
                self.offsets[name] = len(self.out)
            self.out += rec

    def add(self, op, body, name=None):
        self._place(op, body, name)

    def schema(self, sid, name, encoding='ros2msg', data=SCAN_DEFINITION, rec_name=None):
        self.add(OP_SCHEMA, struct.pack('<H', sid) + string(name) + string(encoding) + string(data), rec_name)

    def channel(self, cid, sid, topic, encoding='cdr', rec_name=None):
        metadata = string('offered_qos_profiles') + string('')
        self.add(OP_CHANNEL, struct.pack('<HH', cid, sid) + string(topic) + string(encoding) +
                 struct.pack('<I', len(metadata)) + metadata, rec_name)

    def message(self, cid, log_ns, data, name=None, packet_at=None):
        """`packet_at`: offsets within `data` of its packets, to record their file offsets."""
        body = struct.pack('<HIQQ', cid, self.sequence, log_ns, log_ns) + data
        self.sequence += 1
        here = 9 + 22  # record prefix and message fields before the data
        if packet_at:
            if self.chunk is not None:
                base = len(self.chunk[0])
                self.chunk[2].extend(base + here + p for p in packet_at)
            else:
                base = len(self.out)
                self.packet_offsets.extend(base + here + p for p in packet_at)
        self.add(OP_MESSAGE, body, name)

    def open_chunk(self):
        self.chunk = (bytearray(), [], [])

    def close_chunk(self, crc=True, compression='', name=None, records_override=None):
        records, names, packets = self.chunk
        self.chunk = None
        records = bytes(records) if records_override is None else records_override
        crc_value = zlib.crc32(records) & 0xFFFFFFFF if crc else 0
        head = struct.pack('<QQQI', 0, 0, len(records), crc_value) + string(compression) + struct.pack('<Q', len(records))
        at = len(self.out)
        if name:
            self.offsets[name] = at
        start = at + 9 + len(head)  # the first record of the chunk
        for n, o in names:
            if n:
                self.offsets[n] = start + o
        self.packet_offsets.extend(start + p for p in packets)
        self.out += record(OP_CHUNK, head + records)
        self.add(OP_MESSAGE_INDEX, struct.pack('<H', 1) + struct.pack('<I', 0))  # an empty index: skipped

    def finish(self, data_end=True):
        if data_end:
            self.add(OP_DATA_END, struct.pack('<I', 0))
            self.add(OP_FOOTER, struct.pack('<QQI', 0, 0, 0))
            self.out += MAGIC
        return bytes(self.out)


def scan_messages(payloads, per_scan):
    """Groups the payloads into scans of `per_scan` packets."""
    return [payloads[i:i + per_scan] for i in range(0, len(payloads), per_scan)]


def packet_positions(scan, frame_id):
    """Offsets within the CDR message data of each packet's stamp."""
    fid = len(frame_id.encode()) + 1
    first = 4 + 8 + 4 + fid
    first += -(first - 4) % 4 + 4  # align (counted after the encapsulation header), the count
    return [first + i * 1512 for i in range(len(scan))]


def write_bag(payloads, chunk_bytes=0, crc=True, per_scan=50, frame_id='hesai', other_topic=False):
    """The whole bag: unchunked when chunk_bytes is 0, else chunks of about chunk_bytes."""
    bag = Bag()
    if chunk_bytes:
        bag.open_chunk()
    bag.schema(1, 'pandar_msgs/msg/PandarScan')
    bag.channel(1, 1, '/pandar_packets')
    if other_topic:
        bag.schema(2, 'std_msgs/msg/String', data='string data\n')
        bag.channel(2, 2, '/chatter')
    size = 0
    for i, scan in enumerate(scan_messages(payloads, per_scan)):
        data = cdr_scan(scan, frame_id)
        bag.message(1, scan[0][0], data, packet_at=packet_positions(scan, frame_id))
        size += len(data)
        if other_topic:
            text = ('scan %d' % i).encode() + b'\x00'
            bag.message(2, scan[0][0], b'\x00\x01\x00\x00' + struct.pack('<I', len(text)) + text)
        if chunk_bytes and size >= chunk_bytes:
            bag.close_chunk(crc)
            bag.open_chunk()
            size = 0
    if chunk_bytes:
        bag.close_chunk(crc)
    return bag.finish()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('capture')
    ap.add_argument('out')
    ap.add_argument('--chunk-bytes', type=int, default=0)
    ap.add_argument('--no-crc', action='store_true')
    ap.add_argument('--per-scan', type=int, default=50)
    a = ap.parse_args()
    data = write_bag(pcap_payloads(a.capture), a.chunk_bytes, not a.no_crc, a.per_scan)
    open(a.out, 'wb').write(data)


if __name__ == '__main__':
    main()
