// libFuzzer harness: parse_gps_packet on one UDP payload, then a Pandar40 decoder takes its time.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"
#include "hesai/gps.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  using hesai_fuzz::check;
  hesai::GpsPacket a, b;
  a.nmea_length = 200;  // written only on success
  const hesai::Error e = hesai::parse_gps_packet(in.view(), a);
  check(hesai::parse_gps_packet(in.view(), b) == e);
  hesai_fuzz::check_named(e);
  if (e != hesai::Error::ok) {
    check(a.nmea_length == 200);
    return 0;
  }
  check(size == hesai::gps_wire::kPacketSize && hesai::is_gps_packet(in.view()));
  check(hesai::is_valid(a.time));
  check(a.layout == hesai::GpsLayout::pandar40 ? a.nmea_length <= hesai::gps_wire::kNmeaSize40 && a.us_time < 3600000000u
                                               : a.nmea_length <= hesai::gps_wire::kNmeaSize64 && a.us_time == 0);
  check(a.nmea[a.nmea_length] == '\0' && std::strlen(a.nmea) == a.nmea_length);
  check(!a.nmea_checksum_ok || (a.nmea_length > 0 && a.nmea[0] == '$'));
  const char s = a.location_status;
  check(s == 'A' || s == 'V' || s == 0 || (a.layout == hesai::GpsLayout::pandar64 && s >= '0' && s <= '9'));
  check(a.layout == b.layout && a.us_time == b.us_time && a.nmea_length == b.nmea_length &&
        std::memcmp(a.nmea, b.nmea, sizeof a.nmea) == 0 && a.location_status == b.location_status &&
        a.pps_locked == b.pps_locked && a.nmea_checksum_ok == b.nmea_checksum_ok && a.time.year == b.time.year &&
        a.time.month == b.time.month && a.time.day == b.time.day && a.time.hour == b.time.hour &&
        a.time.minute == b.time.minute && a.time.second == b.time.second);
  // identify() calls it a GPS packet.
  hesai::Model m = hesai::Model::pandar64;
  hesai::PacketKind kind = hesai::PacketKind::point_cloud;
  check(hesai::identify(in.view(), m, kind) == hesai::Error::ok && kind == hesai::PacketKind::gps &&
        m == hesai::Model::unknown);
  hesai::Decoder d(hesai::Model::pandar40);
  d.update_gps(a);
  return 0;
}
