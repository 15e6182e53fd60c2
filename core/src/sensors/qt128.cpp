// QT128C2X, point cloud protocol 3.2: identification (header and the length its laser num and
// flags imply), the channel configuration for customised packets, validation (the three CRCs,
// the signature, then the fields) and the walk over its two blocks with their firing sequences;
// and qt128::seal, which writes the CRCs validation checks.
// Layout: hesai/detail/qt128_packet.h; tables: hesai/detail/tables/qt128_tables.h.
#include "hesai/crc32.h"
#include "hesai/ct.h"
#include "hesai/hmac.h"
#include "hesai/decoder.h"
#include "hesai/detail/qt128_packet.h"
#include "hesai/detail/tables/block_times.h"
#include "hesai/detail/tables/qt128_tables.h"
#include "block_points.h"
#include "field_checks.h"
#include "sensor.h"
#include "sensor_rules.h"

namespace hesai {

namespace {

struct Qt128Tag;  // this file's SensorCode

constexpr auto kBlockNs = detail::block_ns(tables::qt128_block_start_us_single, tables::qt128_block_start_us_dual);
static_assert(kBlockNs[0][1] == 120110 && kBlockNs[1][1] == 9000);

// The three CRCs of a packet, in the order validation checks them (manual 3.1.2): CRC1 over
// the body (both blocks), CRC2 over the functional-safety section after its version byte, CRC3
// over the tail before it; with the code a mismatch gives.
constexpr std::size_t kCrcCount = 3;
constexpr Error kCrcMismatch[kCrcCount] = {Error::crc_body, Error::crc_functional_safety, Error::crc_tail};

// CRC `i` of a packet: the bytes it covers and its offset (0: the section is absent).
struct CrcField {
  ByteView covered;
  std::size_t at = 0;
};
CrcField crc_field(ByteView p, const qt128::Layout& l, std::size_t i) noexcept {
  using namespace qt128;
  switch (i) {
    case 0: return {p.sub(kBody, l.crc1 - kBody), l.crc1};
    case 1: return l.fs != 0 ? CrcField{p.sub(l.fs + kFsCrcFrom, kFsCrc2 - kFsCrcFrom), l.fs + kFsCrc2} : CrcField{};
    default: return {p.sub(l.tail, l.crc3 - l.tail), l.crc3};
  }
}

// True when the n bytes at p are all zero (read 8 at a time: the order of the bytes does not matter).
bool all_zero(const std::uint8_t* p, std::size_t n) {
  std::uint64_t acc = 0;
  std::size_t i = 0;
  for (; n - i >= 8; i += 8) acc |= load_le64(p + i);
  for (; i < n; ++i) acc |= p[i];
  return acc == 0;
}

// The firing sequence (0: sequence 1, Loop1; 1: sequence 2) of block b. Mode flag bit 0: block 1
// uses sequence 1 when set, sequence 2 otherwise; in single return block 2 uses the other
// sequence, in dual return both blocks share one firing (manual 3.1.2, Tail; App. II).
std::size_t block_loop(std::uint8_t mode_flag, bool dual, std::size_t b) {
  const std::size_t loop1 = (mode_flag & 1) ? 0 : 1;
  return (dual || b == 0) ? loop1 : 1 - loop1;
}

bool rests(const std::uint8_t* mask, std::size_t ch) { return ((mask[ch / 8] >> (ch % 8)) & 1) != 0; }

// True when every unit of a block whose channel rests (bit set in `mask`, 16 bytes) is all zero:
// unit j is channel j, or channel_of[j] with customised channels.
bool resting_units_zero(const std::uint8_t* units, const qt128::Layout& l, const std::uint8_t* channel_of,
                        const std::uint8_t* mask) {
  std::uint8_t acc = 0;
  for (std::size_t j = 0; j < l.lasers; ++j)
    if (rests(mask, channel_of != nullptr ? channel_of[j] : j))
      for (std::size_t k = 0; k < l.unit; ++k) acc = static_cast<std::uint8_t>(acc | units[j * l.unit + k]);
  return acc == 0;
}

}  // namespace

using Qt128Code = SensorCode<Qt128Tag>;

// Two firing sequences; the channels resting in each by the manual's bank rule.
template <>
void Qt128Code::design(Decoder& d) noexcept {
  set_design_tables(d, tables::qt128_channel_angles, tables::qt128_firetime_us_loop1, tables::qt128_firetime_us_loop2);
  for (std::size_t i = 0; i < qt128::kChannels; ++i) {
    set_resting(d, 0, i, !tables::qt128_fires_in_loop1[i]);
    set_resting(d, 1, i, !tables::qt128_fires_in_loop2[i]);
  }
  d.find_resting_runs();
}

// With flags bit 0, at the end of the tail (CRC3 covers it).
template <>
std::size_t Qt128Code::sequence_at(ByteView p) noexcept {
  using namespace qt128;
  if (!(p[kFlags] & kFlagSequence)) return 0;
  return Layout::from_header(p[kLaserNum], p[kFlags]).tail + kTailSequence;
}

template <>
Error Qt128Code::identify(ByteView p, Model& model) noexcept {
  using namespace qt128;
  if (p.size < kHeaderEnd) return Error::bad_length;
  if (p[kBlockNum] != kBlocks) return Error::unsupported_model;
  // 128 units per block, or with customised channels (flags bit 6) the header's 1..128.
  const std::uint8_t lasers = p[kLaserNum];
  if (!(p[kFlags] & kFlagChannelCustom)) {
    if (lasers != kChannels) return Error::unsupported_model;
  } else if (lasers == 0 || lasers > kChannels) {
    return Error::bad_header;
  }
  if (p.size != Layout::from_header(lasers, p[kFlags]).total) return Error::flags_length_mismatch;
  model = Model::qt128c2x;
  return Error::ok;
}

Error Decoder::set_channel_config(const ChannelConfig& config) noexcept {
  using namespace qt128;
  if (model_ != Model::qt128c2x) return Error::invalid_argument;
  const std::size_t lasers = config.laser_num;
  if (lasers < 1 || lasers > kChannels || config.loops < 1 || config.loops > 2) return Error::invalid_argument;
  if (config.block_num != kBlocks) return Error::channel_config_mismatch;
  // Checked before any change (parse_channel_config_csv checks the same; a config may be built by hand).
  for (std::size_t loop = 0; loop < config.loops; ++loop) {
    bool seen[kChannels] = {};
    for (std::size_t j = 0; j < lasers; ++j) {
      const std::size_t ch = config.channel[loop][j];
      if (ch < 1 || ch > kChannels || seen[ch - 1]) return Error::invalid_argument;
      seen[ch - 1] = true;
    }
  }
  for (std::size_t loop = 0; loop < 2; ++loop)
    for (std::size_t j = 0; j < lasers; ++j)
      custom_channel_[loop][j] = static_cast<std::uint8_t>(config.channel[config.loops == 2 ? loop : 0][j] - 1);
  custom_lasers_ = static_cast<std::uint8_t>(lasers);
  return Error::ok;
}

template <>
Error Qt128Code::validate(Decoder& d, ByteView p, PacketInfo& info) noexcept {
  using namespace qt128;
  // identify() has checked magic, version, laser and block numbers and the length they and the flags imply.
  info.blocks = kBlocks;
  info.flags = p[kFlags];
  if (info.flags & kFlagImu) return Error::unsupported_section;  // layout not in the manual
  const Layout layout = Layout::from_header(p[kLaserNum], info.flags);
  if (info.flags & kFlagChannelCustom) {
    if (d.custom_lasers_ == 0) return Error::channel_config_required;
    if (d.custom_lasers_ != layout.lasers) return Error::channel_config_mismatch;
  }
  info.dis_unit_mm = p[kDisUnit];
  const std::uint8_t return_num = p[kReturnNum];
  if (info.dis_unit_mm == 0 || (return_num != 1 && return_num != 2)) return Error::bad_header;

  // CRC1, CRC2, CRC3, in this order.
  for (std::size_t i = 0; i < kCrcCount; ++i) {
    const CrcField f = crc_field(p, layout, i);
    if (f.at != 0 && crc32_mpeg2(f.covered) != load_le32(p.data + f.at)) return kCrcMismatch[i];
  }

  // Signature: HMAC-SHA256 of everything before it. All-zero bytes mean signing was not started.
  // Without a key, or in a core without signature support (HESAI_SIGNATURE 0), it is not checked.
  const bool signed_packet = layout.signature != 0 && !all_zero(p.data + layout.signature, kSignatureBytes);
  info.signature = signed_packet ? SignatureStatus::unverified : SignatureStatus::not_signed;
#if HESAI_SIGNATURE
  if (d.has_key_) {
    if (!signed_packet) {
      if (!d.allow_unsigned_) return Error::signature_missing;
      info.signature = SignatureStatus::accepted_unsigned;
    } else {
      std::uint8_t mac[32];
      HmacSha256 h(d.key_);
      h.update(p.sub(0, layout.signature));
      h.finish(mac);
      const bool ok = constant_time_equal(mac, p.data + layout.signature, kSignatureBytes);
      secure_wipe(mac, sizeof mac);
      if (!ok) return Error::signature_invalid;
      info.signature = SignatureStatus::valid;
    }
  }
#endif

  // Fields.
  if (layout.fs != 0) {
    const std::uint8_t* fs = p.data + layout.fs;
    FunctionalSafety& s = info.safety;
    s.present = true;
    s.version = fs[kFsVersion];
    s.lidar_state = static_cast<std::uint8_t>(fs[kFsLidarState] >> 5);
    s.fault_code_type = static_cast<std::uint8_t>((fs[kFsLidarState] >> 3) & 3);
    s.rolling_counter = static_cast<std::uint8_t>(fs[kFsLidarState] & 7);
    s.total_fault_codes = static_cast<std::uint8_t>(fs[kFsFaultNum] >> 4);
    s.fault_code_id = static_cast<std::uint8_t>(fs[kFsFaultNum] & 15);
    s.fault_code = load_le16(fs + kFsFaultCode);
  }
  const std::uint8_t* tail = p.data + layout.tail;
  info.mode_flag = tail[kTailModeFlag];
  detail::read_tail(tail, {kTailReturnMode, kTailMotorSpeed, kTailTimestamp, kTailFactoryInfo, kTailSequence},
                    (info.flags & kFlagSequence) != 0, info);
  if (!detail::returns_of_mode(info.return_mode, info.returns) || info.returns != return_num) return Error::bad_return_mode;
  if (const Error e = detail::motor_speed(info); e != Error::ok) return e;

  if (const Error e = detail::block_azimuths(p.data + kBody, layout.block, info); e != Error::ok) return e;
  // Manual 3.1.2: "If a channel does not fire in the current firing sequence, its corresponding
  // four bytes are filled with 0." Data there is no measurement of that channel (it did not fire):
  // the block was not fired as the mode flag says, or the sensor wrote bytes the manual does not
  // define; either way no firing time of the packet can be trusted, so the packet is rejected.
  // Without customised channels unit j is channel j, so resting channels that form one run (the
  // manual's banks) are one span of units.
  const bool custom = (info.flags & kFlagChannelCustom) != 0;
  for (std::size_t b = 0; b < kBlocks; ++b) {
    const std::size_t loop = block_loop(info.mode_flag, info.returns == 2, b);
    const std::uint8_t* units = p.data + kBody + b * layout.block + kBlockPoints;
    const bool zero = !custom && d.resting_count_[loop] != Decoder::kRestingScattered
                          ? all_zero(units + d.resting_first_[loop] * layout.unit, d.resting_count_[loop] * layout.unit)
                          : resting_units_zero(units, layout, custom ? d.custom_channel_[loop].data() : nullptr,
                                               d.resting_[loop].data());
    if (!zero) return Error::resting_channel_data;
  }
  // Date & Time: year - 1900 (>= 70), or with a year byte of 0 Unix seconds, big-endian, in bytes
  // 2..5 (the vendor SDK's reading; byte 1 is not read); Timestamp: us, 0..1000000 (the manual's range).
  const std::uint8_t* dt = tail + kTailDateTime;
  return detail::tail_time(detail::calendar_or_unix(dt, 1900 + dt[0]), 1000000, info);
}

template <>
void Qt128Code::walk(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept {
  using namespace qt128;
  const Layout layout = Layout::from_header(p[kLaserNum], info.flags);
  const bool custom = (info.flags & kFlagChannelCustom) != 0;
  const std::size_t dual = info.returns == 2 ? 1 : 0;
  // Customised channels: the configuration's column for the block's loop names each unit's channel.
  kernels::BlockRef blocks[kBlocks];
  for (std::size_t b = 0; b < kBlocks; ++b) {
    const std::size_t loop = block_loop(info.mode_flag, dual != 0, b);
    blocks[b] = {p + kBody + b * layout.block + kBlockPoints, custom ? d.custom_channel_[loop].data() : nullptr,
                 kBlockNs[dual][b], static_cast<std::uint8_t>(loop)};
  }
  if (layout.unit == kUnitBytes + kConfidenceBytes)
    emit_blocks<kUnitBytes + kConfidenceBytes>(d, blocks, kBlocks, layout.lasers, info, out);
  else
    emit_blocks<kUnitBytes>(d, blocks, kBlocks, layout.lasers, info, out);
}

// EE FF, point cloud protocol 3.2 (bytes 2 and 3). Distance 1 is a marker, not a measurement: the
// smallest kept is 2.
static_assert(qt128::kVersionMajor == 2 && qt128::kVersionMinor == 3);
extern const SensorDescriptor kQt128Sensor;  // registry.cpp
const SensorDescriptor kQt128Sensor =
    Qt128Code::descriptor({qt128::kMagic0, qt128::kMagic1, 0x03, 0x02}, 4, qt128::seal,
                          /*firing_loops=*/2, /*min_distance=*/2);

namespace qt128 {

Error seal(std::uint8_t* payload, std::size_t size) noexcept {
  if (size <= kFlags) return Error::bad_length;
  if (payload[0] != kMagic0 || payload[1] != kMagic1) return Error::bad_magic;
  const Layout layout = Layout::from_header(payload[kLaserNum], payload[kFlags]);
  if (size != layout.total) return Error::bad_length;
  for (std::size_t i = 0; i < kCrcCount; ++i) {
    const CrcField f = crc_field(ByteView{payload, size}, layout, i);
    if (f.at != 0) store_le32(payload + f.at, crc32_mpeg2(f.covered));
  }
  return Error::ok;
}

Error sign(std::uint8_t* payload, std::size_t size, const std::uint8_t key[32]) noexcept {
  if (size <= kFlags) return Error::bad_length;
  if (payload[0] != kMagic0 || payload[1] != kMagic1) return Error::bad_magic;
  const Layout layout = Layout::from_header(payload[kLaserNum], payload[kFlags]);
  if (size != layout.total) return Error::bad_length;
  if (layout.signature == 0) return Error::signature_missing;
#if HESAI_SIGNATURE
  hmac_sha256(ByteView{key, 32}, ByteView{payload, layout.signature}, payload + layout.signature);
  return Error::ok;
#else
  (void)key;
  return Error::unsupported_feature;
#endif
}

}  // namespace qt128

}  // namespace hesai
