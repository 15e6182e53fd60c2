#!/usr/bin/env python3
"""`--packets A:B` against the whole run (issue #43): the packets outside the range are surveyed,
not decoded, and nothing the user sees may change. For every bundled capture and several ranges
(the first packet, ranges that start and end inside a frame, one from a frame's first packet,
one that runs past the end, one wholly past it), with the unit's calibration and firing times:

- `decode --packets A:B` CSV is the whole run's header and its rows whose `packet` is in [A, B),
  byte for byte (frame ids, points, times);
- `decode --packets A:B --format pcd` is the whole run's PCD with the records of those rows
  (the rows and the records in the same order) and that count in WIDTH and POINTS;
- `stats --json --packets A:B` is the whole run's `stats --json`: the counters cover every packet,
  as they always have (points, unit scan, frames, losses).

Usage: packets_range.py HESAI DATA_DIR OUT_DIR
"""
import os
import subprocess
import sys

PCD_RECORD = 4 * 4 + 2 + 1 + 8  # x y z intensity ring return timestamp (SIZE 4 4 4 4 2 1 8)


def files_for(data, base):
    cal = os.path.join(data, 'calibration')
    if base == 'pandar40p_dual':
        return ['--calibration', f'{cal}/pandar40p_unit_a_angles.csv', '--firetimes', f'{cal}/pandar40p_firetimes.csv']
    if base == 'pandar64_dual':
        return ['--calibration', f'{cal}/pandar64_unit_a_angles.csv', '--firetimes', f'{cal}/pandar64_firetimes.csv']
    if base == 'qt128c2x_dual':
        return ['--calibration', f'{cal}/qt128c2x_unit_a_angles.csv', '--firetimes', f'{cal}/qt128c2x_firetimes.csv',
                '--channel-config', f'{cal}/qt128c2x_channel_config.csv']
    return ['--calibration', f'{cal}/{base}_angles.csv', '--firetimes', f'{cal}/{base}_firetimes.csv']


def run(hesai, args):
    prefix = os.environ.get('HESAI_RUN_PREFIX', '').split()
    r = subprocess.run(prefix + [hesai] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if r.returncode != 0:
        raise SystemExit(f'hesai {" ".join(args)}: exit {r.returncode}: {r.stderr.decode()}')
    return r.stdout


def split_pcd(data):
    end = data.index(b'DATA binary\n') + len(b'DATA binary\n')
    return data[:end].decode().splitlines(), data[end:]


def main():
    hesai, data, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    failures = []
    checked = 0
    for name in sorted(os.listdir(data)):
        if not name.endswith('.pcap'):
            continue
        base = name[:-5]
        capture = os.path.join(data, name)
        files = files_for(data, base)
        whole_csv = run(hesai, ['decode', capture] + files + ['--out', '-']).decode().splitlines(keepends=True)
        header, rows = whole_csv[0], whole_csv[1:]
        columns = header.strip().split(',')
        packet_col, frame_col = columns.index('packet'), columns.index('frame')
        packet_of = [int(r.split(',')[packet_col]) for r in rows]
        frame_of = [int(r.split(',')[frame_col]) for r in rows]
        whole_pcd_path = os.path.join(out, base + '.pcd')
        run(hesai, ['decode', capture] + files + ['--format', 'pcd', '--out', whole_pcd_path])
        pcd_header, pcd_data = split_pcd(open(whole_pcd_path, 'rb').read())
        if len(pcd_data) != PCD_RECORD * len(rows):
            failures.append(f'{base}: the whole PCD holds {len(pcd_data)} bytes for {len(rows)} CSV rows')
            continue
        whole_stats = run(hesai, ['stats', capture] + files + ['--json'])
        packets = packet_of[-1] + 1  # the last point's packet: every bundled capture's last packet has points
        # A frame's first packet (the third frame's) and one inside it.
        third = sorted(set(frame_of))[2]
        frame_start = packet_of[frame_of.index(third)]
        ranges = [(0, 1), (frame_start, frame_start + 7), (frame_start - 3, frame_start + packets // 4),
                  (packets // 3 + 1, 2 * packets // 3 - 2), (packets - 5, packets + 100), (packets + 10, packets + 20)]
        for a, b in ranges:
            tag = f'{base} --packets {a}:{b}'
            keep = [i for i, p in enumerate(packet_of) if a <= p < b]
            csv = run(hesai, ['decode', capture] + files + ['--packets', f'{a}:{b}', '--out', '-']).decode()
            if csv != header + ''.join(rows[i] for i in keep):
                failures.append(f'{tag}: CSV is not the whole run\'s rows of packets {a}..{b - 1}')
            pcd_path = os.path.join(out, f'{base}.{a}_{b}.pcd')
            run(hesai, ['decode', capture] + files + ['--packets', f'{a}:{b}', '--format', 'pcd', '--out', pcd_path])
            got_header, got_data = split_pcd(open(pcd_path, 'rb').read())
            expected_data = b''.join(pcd_data[i * PCD_RECORD:(i + 1) * PCD_RECORD] for i in keep)
            counts = [line for line in got_header if line.split(' ')[0] in ('WIDTH', 'POINTS')]
            if [line for line in got_header if line not in counts] != [
                    line for line in pcd_header if line.split(' ')[0] not in ('WIDTH', 'POINTS')]:
                failures.append(f'{tag}: PCD header differs beyond its counts')
            if [int(line.split(' ')[1]) for line in counts] != [len(keep), len(keep)]:
                failures.append(f'{tag}: PCD counts {counts}, expected {len(keep)}')
            if got_data != expected_data:
                failures.append(f'{tag}: PCD records are not the whole run\'s records of packets {a}..{b - 1}')
            stats = run(hesai, ['stats', capture] + files + ['--json', '--packets', f'{a}:{b}'])
            if stats != whole_stats:
                failures.append(f'{tag}: stats --json differs from the whole run\'s')
            checked += 1
    for f in failures:
        print('FAIL', f)
    print(f'{checked} ranges checked, {len(failures)} failures')
    return 1 if failures or checked == 0 else 0


if __name__ == '__main__':
    sys.exit(main())
