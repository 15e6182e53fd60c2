// Link layer, IPv4/IPv6 and UDP: a captured frame down to its UDP datagram (parse_frame).
// Pure: no allocation, no I/O, reads only inside the frame (fuzzed through fuzz_capture).
#include "hesai_port/capture/capture_parser.h"

#include <cstring>

namespace hesai::port {
namespace {

// ---- Link types (LINKTYPE_* values of the tcpdump.org registry) -------------------------------
constexpr std::uint32_t link_null = 0;
constexpr std::uint32_t link_ethernet = 1;
constexpr std::uint32_t link_raw_dlt = 12;  // DLT_RAW as written on most platforms
constexpr std::uint32_t link_raw = 101;
constexpr std::uint32_t link_loop = 108;
constexpr std::uint32_t link_linux_sll = 113;
constexpr std::uint32_t link_ipv4 = 228;
constexpr std::uint32_t link_ipv6 = 229;
constexpr std::uint32_t link_linux_sll2 = 276;

constexpr std::size_t ethernet_header_size = 14;  // destination, source, EtherType
constexpr std::size_t sll_header_size = 16;       // protocol at 14
constexpr std::size_t sll2_header_size = 20;      // protocol at 0
constexpr std::size_t vlan_tag_size = 4;          // TCI(2), inner EtherType(2)
constexpr std::uint16_t ethertype_ipv4 = 0x0800;
constexpr std::uint16_t ethertype_ipv6 = 0x86DD;
constexpr std::uint16_t ethertype_8021q = 0x8100;
constexpr std::uint16_t ethertype_8021ad = 0x88A8;
constexpr std::uint16_t ethertype_qinq_old = 0x9100;
constexpr std::uint16_t ethertype_min = 0x0600;   // below: an IEEE 802.3 length field

// BSD address families in null/loopback headers: AF_INET is 2 everywhere, AF_INET6 differs.
constexpr std::uint32_t af_inet = 2;
constexpr bool is_af_inet6(std::uint32_t f) { return f == 10 || f == 24 || f == 28 || f == 30; }

// ---- IP and UDP (RFC 791, RFC 8200, RFC 768) ----------------------------------------------------
constexpr std::size_t ipv4_min_header = 20;
constexpr std::size_t ipv6_header_size = 40;
constexpr std::size_t udp_header_size = 8;
constexpr std::uint8_t proto_hop_by_hop = 0;
constexpr std::uint8_t proto_udp = 17;
constexpr std::uint8_t proto_routing = 43;
constexpr std::uint8_t proto_fragment = 44;
constexpr std::uint8_t proto_ah = 51;
constexpr std::uint8_t proto_dest_options = 60;
constexpr std::uint16_t ipv4_flag_mf = 0x2000;
constexpr std::uint16_t ipv4_offset_mask = 0x1FFF;

constexpr ByteView tail(ByteView v, std::size_t off) { return v.sub(off, v.size - off); }
constexpr std::size_t min_size(std::size_t a, std::size_t b) { return a < b ? a : b; }


// UDP header and payload. `seg` is the captured part of the IP payload, `declared` its length
// according to the IP header.
FrameKind parse_udp(ByteView seg, std::size_t declared, UdpDatagram& out) {
  if (declared < udp_header_size) return FrameKind::malformed;
  if (seg.size < udp_header_size) return FrameKind::truncated;
  const std::size_t udp_len = load_be16(seg.data + 4);
  if (udp_len < udp_header_size || udp_len > declared) return FrameKind::malformed;
  if (udp_len > seg.size) return FrameKind::truncated;
  out.src_port = load_be16(seg.data);
  out.dst_port = load_be16(seg.data + 2);
  out.payload = seg.sub(udp_header_size, udp_len - udp_header_size);
  return FrameKind::udp;
}

FrameKind parse_ipv4(ByteView p, UdpDatagram& out) {
  if (p.size < ipv4_min_header) return FrameKind::truncated;
  if ((p[0] >> 4) != 4) return FrameKind::malformed;
  const std::size_t ihl = static_cast<std::size_t>(p[0] & 0x0F) * 4;
  if (ihl < ipv4_min_header) return FrameKind::malformed;
  const std::size_t total = load_be16(p.data + 2);
  if (total < ihl) return FrameKind::malformed;
  if (ihl > p.size) return FrameKind::truncated;
  const std::uint16_t frag = load_be16(p.data + 6);
  if ((frag & ipv4_flag_mf) != 0 || (frag & ipv4_offset_mask) != 0) return FrameKind::fragment;
  if (p[9] != proto_udp) return FrameKind::non_udp;
  const std::size_t end = min_size(total, p.size);
  const FrameKind k = parse_udp(p.sub(ihl, end - ihl), total - ihl, out);
  if (k != FrameKind::udp) return k;
  out.ip_version = 4;
  out.src_addr = {};
  out.dst_addr = {};
  std::memcpy(out.src_addr.data(), p.data + 12, 4);
  std::memcpy(out.dst_addr.data(), p.data + 16, 4);
  return k;
}

FrameKind parse_ipv6(ByteView p, UdpDatagram& out) {
  if (p.size < ipv6_header_size) return FrameKind::truncated;
  if ((p[0] >> 4) != 6) return FrameKind::malformed;
  const std::size_t payload_len = load_be16(p.data + 4);
  if (payload_len == 0) return FrameKind::malformed;  // jumbogram or an offloaded send: no length
  const std::size_t declared_end = ipv6_header_size + payload_len;
  std::uint8_t next = p[6];
  std::size_t off = ipv6_header_size;
  // Each extension header is at least 8 bytes, so the walk ends within 8192 steps.
  for (;;) {
    if (next == proto_udp) break;
    if (next == proto_fragment) return FrameKind::fragment;
    if (next != proto_hop_by_hop && next != proto_routing && next != proto_dest_options &&
        next != proto_ah) {
      return FrameKind::non_udp;
    }
    if (2 > declared_end - off) return FrameKind::malformed;
    if (off > p.size || 2 > p.size - off) return FrameKind::truncated;
    const std::size_t len = next == proto_ah ? (static_cast<std::size_t>(p[off + 1]) + 2) * 4
                                             : (static_cast<std::size_t>(p[off + 1]) + 1) * 8;
    next = p[off];
    if (len > declared_end - off) return FrameKind::malformed;
    off += len;
  }
  if (off > p.size) return FrameKind::truncated;
  const std::size_t end = min_size(declared_end, p.size);
  const FrameKind k = parse_udp(p.sub(off, end - off), declared_end - off, out);
  if (k != FrameKind::udp) return k;
  out.ip_version = 6;
  std::memcpy(out.src_addr.data(), p.data + 8, 16);
  std::memcpy(out.dst_addr.data(), p.data + 24, 16);
  return k;
}

// IP by its version nibble (raw IP link types).
FrameKind parse_ip(ByteView p, UdpDatagram& out) {
  if (p.size < 1) return FrameKind::truncated;
  switch (p[0] >> 4) {
    case 4: return parse_ipv4(p, out);
    case 6: return parse_ipv6(p, out);
    default: return FrameKind::malformed;
  }
}

// What follows an EtherType, through any number of VLAN tags.
FrameKind parse_ethertype(std::uint16_t type, ByteView rest, UdpDatagram& out) {
  std::size_t off = 0;
  while (type == ethertype_8021q || type == ethertype_8021ad || type == ethertype_qinq_old) {
    if (vlan_tag_size > rest.size - off) return FrameKind::truncated;
    type = load_be16(rest.data + off + 2);
    off += vlan_tag_size;
  }
  if (type == ethertype_ipv4) return parse_ipv4(tail(rest, off), out);
  if (type == ethertype_ipv6) return parse_ipv6(tail(rest, off), out);
  return FrameKind::non_udp;
}

FrameKind parse_family(std::uint32_t family, ByteView rest, UdpDatagram& out) {
  if (family == af_inet) return parse_ipv4(rest, out);
  if (is_af_inet6(family)) return parse_ipv6(rest, out);
  return FrameKind::non_udp;
}
}  // namespace

bool link_type_supported(std::uint32_t link_type) {
  switch (link_type) {
    case link_null:
    case link_ethernet:
    case link_raw_dlt:
    case link_raw:
    case link_loop:
    case link_linux_sll:
    case link_ipv4:
    case link_ipv6:
    case link_linux_sll2:
      return true;
    default:
      return false;
  }
}

FrameKind parse_frame(std::uint32_t link_type, ByteView frame, UdpDatagram& out) {
  switch (link_type) {
    case link_ethernet: {
      if (frame.size < ethernet_header_size) return FrameKind::truncated;
      const std::uint16_t type = load_be16(frame.data + 12);
      if (type < ethertype_min) return FrameKind::non_udp;  // 802.3 length: LLC frames
      return parse_ethertype(type, tail(frame, ethernet_header_size), out);
    }
    case link_linux_sll:
      if (frame.size < sll_header_size) return FrameKind::truncated;
      return parse_ethertype(load_be16(frame.data + 14), tail(frame, sll_header_size), out);
    case link_linux_sll2:
      if (frame.size < sll2_header_size) return FrameKind::truncated;
      return parse_ethertype(load_be16(frame.data), tail(frame, sll2_header_size), out);
    case link_raw_dlt:
    case link_raw:
      return parse_ip(frame, out);
    case link_ipv4:
      return parse_ipv4(frame, out);
    case link_ipv6:
      return parse_ipv6(frame, out);
    case link_null: {
      // The family is in the writing host's byte order: a value above 0xFFFF is the other order.
      if (frame.size < 4) return FrameKind::truncated;
      std::uint32_t family = load_le32(frame.data);
      if (family > 0xFFFFu) family = load_be32(frame.data);
      return parse_family(family, tail(frame, 4), out);
    }
    case link_loop:
      if (frame.size < 4) return FrameKind::truncated;
      return parse_family(load_be32(frame.data), tail(frame, 4), out);
    default:
      return FrameKind::unsupported_link;
  }
}

}  // namespace hesai::port
