// The packet decoder: recognise, validate, then decode one UDP payload into points.
//
// ---- Contract (what a firmware engineer needs before anything else) ----------------------------
//
// Threads and reentrancy
// - identify(), return_mode_name() and every other free function of the core (crc32_mpeg2*,
//   sha256, hmac_sha256, hkdf_*, parse_*_csv, parse_gps_packet, error_name): reentrant and
//   thread-safe. They keep no state; the only shared data are constant tables (in flash) and, on
//   x86-64 only, a relaxed atomic caching the CPUID answer (racing first calls store the same value).
// - Decoder: one per sensor per thread. Not thread-safe: validate() and decode() update the
//   per-spin-rate cache and the Pandar40 GPS time base, so even two validate() calls on one decoder
//   must not overlap, nor a setter with either. Distinct decoders share nothing and may run in
//   different threads or interrupt levels at once. Copyable (a copy is an independent decoder).
// - HmacSha256Key (hmac.h): read-only after set(); any number of HmacSha256 contexts, in any
//   threads, may use one key at once. Sha256, HmacSha256, Crc32Mpeg2, FrameAssembler,
//   SequenceTracker, Stats: plain objects, one per thread.
// - No function calls back into the caller, takes a lock, or touches a global variable.
//
// Failure
// - Every fallible call returns an Error ([[nodiscard]]: dropping one does not compile). Bad input
//   is never an assert, a crash or an out-of-bounds read; it is a code. HESAI_ASSERT (config.h)
//   checks only the core's internal contracts and is off by default.
// - set_angles(), set_firetimes(), set_channel_config(), set_reflectivity(), the FrameAssembler
//   setters: on error nothing is changed.
//   decode(): on error out.count is 0 and `info` is partly filled (only for logging).
//
// Worst-case cost per packet (no allocation, no recursion, no system call, no libm call; every
// loop bounded by the packet layout)
// - identify(): a fixed number of header reads.
// - validate(): the length and header checks, CRC-32/MPEG-2 over at most the packet (QT128C2X:
//   three sections, 1 070 of its 1 127 bytes), and, with a session key, one HMAC-SHA256 over at
//   most 1 095 bytes (19 SHA-256 compressions; the key schedule is precomputed by set_session_key);
//   QT128C2X: a read of each resting channel's unit (2 x 32 units with the manual's banks).
// - decode(): validate(), then a constant amount of float arithmetic per channel of each block:
//   at most kMaxPointsPerPacket (400) points. When the spin rate differs from the previous packet's
//   (the first packet, a speed change), the per-rate cache is rebuilt first: at most 2 x 128
//   channels of a few multiplications, no trigonometric call.
// - survey(): validate(), then a read of each unit's distance (the scan, the point count); at a new
//   spin rate the spread of the per-rate cache (its arrays too where the CPU path has no spread alone).
// - Stack: under 1 KiB per call on Cortex-M (docs/FIRMWARE.md: measured and from the call graph).
//
// Memory (the caller owns every object; the core has no static RAM but the one CPUID byte on
// x86-64; sizes checked by static_assert in tests/test_contract.cpp on every CI target, 32- and
// 64-bit, and in the firmware image):
// - Decoder: 7 208 bytes (6 980 with HESAI_SIGNATURE 0): per-channel geometry and the per-rate
//   cache for 128 channels, the QT128 channel configuration (256 bytes) and resting channels (36
//   bytes), the HMAC key states (224 bytes), the GPS time base.
// - PacketPoints: 16 008 bytes (400 points of 40 bytes); PacketColumns<N>: 19 N + a size_t;
//   PacketInfo: 88 bytes.
// - Calibration input: AngleCorrection 2 056 bytes, FiretimeCorrection 2 312 bytes (only while
//   parsing and set_angles()/set_firetimes(); the decoder keeps what it needs).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/calibration.h"
#include "hesai/civil_time.h"
#include "hesai/config.h"
#include "hesai/error.h"
#include "hesai/gps.h"
#include "hesai/hmac.h"
#include "hesai/model.h"
#include "hesai/point.h"

namespace hesai {

namespace kernels {
struct BlockRef;  // a packet's block as the per-point code sees it (internal: core/src/kernels/)
}  // namespace kernels

/// What kind of payload identify() found.
enum class PacketKind : std::uint8_t { point_cloud, gps };

/// Identifies a payload by its length, magic bytes and header fields (never by length alone).
/// Point cloud packets set `model`; GPS packets (512 bytes, FF EE) set kind = gps and model = unknown.
/// Errors: bad_length, bad_magic, unsupported_version, unsupported_model, flags_length_mismatch.
[[nodiscard]] Error identify(ByteView payload, Model& model, PacketKind& kind) noexcept;

/// Writes `sequence` into the UDP sequence field of a point cloud packet that has one, and
/// rewrites the CRC that covers it (QT128C2X: CRC3; a signature is not renewed). The packets with
/// the field: Pandar40P and Pandar64 in their longer lengths (1266, 1198 bytes), QT128C2X,
/// PandarQT64 and the XT family with header flags bit 0. Error::unsupported_section for any other
/// packet (and for GPS packets); identify()'s errors for a payload it does not recognise.
[[nodiscard]] Error write_udp_sequence(std::uint8_t* payload, std::size_t size, std::uint32_t sequence) noexcept;

namespace qt128 {
/// Rewrites CRC1 (body), CRC2 (functional safety, when present) and CRC3 (tail) of a QT128
/// packet from its bytes, where the layout of its header's laser num and flags puts them: for tools
/// that change a field (a replayer renumbering the UDP sequence, a test building packets). The
/// signature, when present, is left as it is (it no longer verifies once a signed byte changed).
/// Error::bad_length (nothing written) when `size` is not the length the header implies;
/// Error::bad_magic when the packet does not start with EE FF.
Error seal(std::uint8_t* payload, std::size_t size) noexcept;

/// Writes the signature of a QT128 packet whose flags announce one (bit 3): HMAC-SHA256 under the
/// 32-byte session key of every byte before the signature (QT128C2X manual 3.1.2 and 4.9.3): what
/// a sensor does once a signature session started, for a tool that stands in for one. The CRCs are
/// not touched (they do not cover the signature). Error::bad_length (nothing written) when `size`
/// is not the length the header implies, Error::bad_magic without EE FF, Error::signature_missing
/// when the flags announce no signature, Error::unsupported_feature in a core built with
/// HESAI_SIGNATURE 0.
Error sign(std::uint8_t* payload, std::size_t size, const std::uint8_t key[32]) noexcept;

}  // namespace qt128

/// Return-mode bytes of the manuals.
enum class ReturnMode : std::uint8_t {
  first = 0x33,                   ///< QT128
  second = 0x34,                  ///< QT128
  strongest = 0x37,
  last = 0x38,
  last_strongest = 0x39,          ///< dual: odd block last, even block strongest
  first_second = 0x3A,            ///< QT128 dual
  first_last = 0x3B,              ///< QT128 dual
  first_strongest = 0x3C,         ///< QT128 dual
  first_last_strongest = 0x3D,    ///< PandarXT32M2X triple (first, last, strongest)
  strongest_second_strongest = 0x3E,  ///< QT128 dual
};
/// True for the dual-return codes (first_last_strongest is triple, not dual).
constexpr bool is_dual(ReturnMode m) {
  return m == ReturnMode::last_strongest || m == ReturnMode::first_second || m == ReturnMode::first_last ||
         m == ReturnMode::first_strongest || m == ReturnMode::strongest_second_strongest;
}
/// "strongest", "last", "last_strongest", ... ("unknown" for other bytes).
const char* return_mode_name(std::uint8_t mode) noexcept;

/// What became of a packet's signature.
enum class SignatureStatus : std::uint8_t {
  not_signed,         ///< no signature section, or all-zero bytes (signing not started); no key configured
  unverified,         ///< a signature is present but no key is configured: not checked
  valid,              ///< HMAC-SHA256 verified under the session key
  accepted_unsigned,  ///< a key is configured, the packet is unsigned, and unsigned packets are allowed
};

/// The direction the sensor spins, seen from above. QT128C2X manual, Section 1.2 (Lidar Structure):
/// "By default, the lidar rotates clockwise in the top view. To select counterclockwise rotation,
/// see Section 4.2"; Pandar40 manual, Section 4.2 (Setting), item 6: the rotation direction can be
/// clockwise or anticlockwise and "The coordinate system remain the same despite the choice of
/// rotation direction". Azimuths therefore grow clockwise in both; what changes is the sign of the
/// firing-time correction (a channel fired t after its block has turned on by spin rate x t, in the
/// direction of rotation) and the order in which azimuths come.
enum class Rotation : std::uint8_t { clockwise, counterclockwise };

/// How far a point's azimuth can lie from its block's azimuth: the smallest and largest beam
/// azimuth (channel offset + firing-time correction), degrees, clockwise positive, each in
/// (-180, 180].
struct AzimuthSpread {
  float min_deg = 0;
  float max_deg = 0;
};

/// Whether PacketInfo::time_ns and Point::time_ns are absolute.
enum class TimeReference : std::uint8_t {
  utc,            ///< ns since the Unix epoch, UTC
  hour_relative,  ///< Pandar40 before its first GPS packet: ns since the top of an unknown hour
};

/// QT128 functional-safety section (flags bit 2), decoded.
struct FunctionalSafety {
  bool present = false;
  std::uint8_t version = 0;           ///< FS version (0x01)
  std::uint8_t lidar_state = 0;       ///< 0 init, 1 normal, 2 report fault, 3 pre-degradation, 4 degradation, 5 pre-shutdown, 6 shutdown, 7 standby
  std::uint8_t fault_code_type = 0;   ///< 1 current fault, 2 past fault
  std::uint8_t rolling_counter = 0;   ///< 0..7
  std::uint8_t total_fault_codes = 0; ///< 0..15
  std::uint8_t fault_code_id = 0;     ///< 0..15
  std::uint16_t fault_code = 0;       ///< outgoing fault code
};

/// Packet-level fields, filled by validate() and decode().
struct PacketInfo {
  Model model = Model::unknown;
  std::uint8_t return_mode = 0;   ///< raw return-mode byte (see ReturnMode)
  std::uint8_t returns = 1;       ///< 1 single return, 2 dual return, 3 triple return (PandarXT32M2X)
  std::uint8_t blocks = 0;
  std::uint8_t dis_unit_mm = 4;   ///< distance step, mm
  std::uint16_t motor_rpm = 0;
  std::array<std::uint16_t, 10> block_azimuth{};  ///< 0.01 degree, per block
  std::int64_t time_ns = 0;       ///< packet time t0 = date-time + timestamp, ns
  TimeReference time_reference = TimeReference::utc;
  DateTime date_time;             ///< the tail's date-time (Pandar40: from the last GPS packet)
  std::uint32_t timestamp_us = 0; ///< the tail's timestamp field as sent
  bool has_sequence = false;
  std::uint32_t sequence = 0;     ///< UDP sequence when present
  std::uint8_t high_temperature = 0;  ///< Pandar40/40P/64 shutdown flag; PandarQT64: the tail's shutdown bit
  std::uint8_t factory_info = 0;
  std::uint8_t flags = 0;         ///< QT128 header flags
  std::uint8_t mode_flag = 0;     ///< QT128 tail mode flag (bit 0: block 1 uses firing sequence 1)
  SignatureStatus signature = SignatureStatus::not_signed;
  FunctionalSafety safety;        ///< QT128 only
};

/// The farthest distance a model is rated for, metres, by its manual's specifications; 0 where no
/// manual here gives one (PandarQT64, the PandarXT family). Points farther are suspect
/// (UnitScan::beyond_rated_range). Pandar40/40P: "Measurement Range 0.3 m to 200 m (at 20%
/// reflectivity)" (Pandar40 manual 1.2; the Pandar40P packet document, "Quality Indicators":
/// "distance values beyond 200m flagged as suspect"); Pandar64: "Ranging capability 0.3 to 200 m
/// (at 10% reflectivity)" (manual 1.5); QT128C2X: "Instrument Range 0.05 to 50 m" (manual 1.4: the
/// range it measures at all; its "Range Capability" at 10% reflectivity is 20 m, 15 m on
/// channels 1-8 and 121-128).
constexpr std::uint16_t rated_range_m(Model m) {
  switch (m) {
    case Model::pandar40:
    case Model::pandar40p:
    case Model::pandar64: return 200;
    case Model::qt128c2x: return 50;
    default: return 0;
  }
}

/// The most dual-return firings a packet holds (the Pandar40's 10 blocks in pairs).
inline constexpr std::size_t kMaxDualFirings = 5;

/// Which returns of a dual-return firing decode() makes points of.
enum class Returns : std::uint8_t {
  all,       ///< both blocks' units, as sent (default)
  distinct,  ///< a second return that repeats its first (UnitScan::duplicate_returns) is left out: the echo once
};

/// What a packet's units say beyond its points, filled by the decode() forms that take one.
/// Channels are 0-based (unit j of a block, or the QT128 channel configuration's channel).
struct UnitScan {
  /// Units that carry the QT128C2X's blockage marker, distance 1 (QT128C2X manual, Chinese edition,
  /// 3.1.2: the value 1 marks a target too close to measure; no point is made of it). 0 on other models.
  std::uint16_t blockage_units = 0;
  /// Dual-return unit pairs (the blocks of one firing) whose two returns carry the same distance and
  /// reflectivity, both at or above the model's smallest kept distance: one echo sent twice (QT128C2X
  /// manual 3.1.2.2, the return-mode notes). Both are points.
  std::uint16_t duplicate_returns = 0;
  /// Units made points whose distance is beyond rated_range_m(model) (none where it is 0).
  std::uint16_t beyond_rated_range = 0;
  /// Blockage units per channel.
  std::array<std::uint8_t, kMaxChannels> blockage_by_channel{};
  /// The repeated second returns: bit (c % 8) of byte c / 8 for 0-based channel c, per firing
  /// (blocks 2f and 2f + 1).
  std::array<std::array<std::uint8_t, kMaxChannels / 8>, kMaxDualFirings> repeated{};
};

/// How each unit compares with the other returns of its firing (PacketInfo::returns adjacent
/// blocks; all clear in single return), filled by the decode() form that takes one: bit (c % 8)
/// of byte c / 8 of block b's row, for 0-based channel c (as UnitScan::repeated). Raw units,
/// whatever their distance (a distance-0 unit too), as nebula's Hesai decoder compares them
/// (tier4/nebula hesai_sensor.hpp) to give a point its ReturnType. 320 bytes.
struct ReturnComparison {
  /// Its distance and reflectivity equal those of another return of the firing.
  std::array<std::array<std::uint8_t, kMaxChannels / 8>, kMaxBlocksPerPacket> identical{};
  /// Its reflectivity is below another return's of the firing (clear: it is the strongest, or
  /// ties with the strongest).
  std::array<std::array<std::uint8_t, kMaxChannels / 8>, kMaxBlocksPerPacket> weaker{};

  bool is_identical(std::size_t block, std::size_t channel) const noexcept { return bit(identical, block, channel); }
  bool is_weaker(std::size_t block, std::size_t channel) const noexcept { return bit(weaker, block, channel); }

 private:
  using Rows = std::array<std::array<std::uint8_t, kMaxChannels / 8>, kMaxBlocksPerPacket>;
  static bool bit(const Rows& rows, std::size_t block, std::size_t channel) noexcept {
    return block < kMaxBlocksPerPacket && channel < kMaxChannels &&
           (static_cast<unsigned>(rows[block][channel / 8]) >> (channel % 8) & 1u) != 0;
  }
};

/// What Point::intensity holds (Decoder::set_reflectivity).
enum class Reflectivity : std::uint8_t {
  raw,        ///< the reflectivity byte as sent (default; with the sensors' default linear mapping it is the percentage)
  nonlinear,  ///< Pandar64 set to "Nonlinear Mapping": the byte mapped by the manual's Appendix D to a percentage
};

/// DecodePath (which per-point code decode() runs) is in point.h.
/// Whether DecodePath::best runs vector code on this CPU.
bool decode_simd_available() noexcept;
/// The code DecodePath::best runs on this CPU, for columns and Points: the vector code "avx512",
/// "avx2" or "neon", "armv7m" (the ARMv7E-M assembly loops of the Cortex-M4F and M7, scalar code)
/// or "none" (the portable loops).
const char* decode_simd_name() noexcept;

/// Decoder state for one sensor: per-channel geometry from the built-in tables or a
/// calibration file, the per-spin-rate point constants, the session key, the Pandar40 GPS
/// time base and the QT128 channel configuration. 7 208 bytes; one per sensor per thread (see the
/// contract at the top).
class Decoder {
 public:
  /// A decoder for `model` using the manual's design angles and firing times.
  explicit Decoder(Model model) noexcept;

  Model model() const noexcept { return model_; }

  /// Uses a unit's angle corrections. Error::calib_channel_count if the channel count differs;
  /// Error::invalid_argument (and no change) if an elevation lies outside [-90, 90] degrees or an
  /// azimuth offset outside [-360, 360] degrees.
  [[nodiscard]] Error set_angles(const AngleCorrection& angles) noexcept;
  /// Uses a firing-time file. Error::calib_channel_count if the channel count differs, or if a
  /// QT128 decoder is given a one-loop file; Error::invalid_argument (and no change) if a firing
  /// time lies outside [-1000, 1000] us. QT128: the channels the file leaves out of a loop are the
  /// ones that rest in that firing sequence (until then, the manual's bank rule: sequence 1 rests
  /// channels 1..32, sequence 2 channels 33..64); validate() rejects a packet whose resting
  /// channels carry data (Error::resting_channel_data).
  [[nodiscard]] Error set_firetimes(const FiretimeCorrection& firetimes) noexcept;
  /// Azimuth firing-time correction (on by default): adds firing time x spin rate to each point,
  /// in the direction of rotation (subtracts it for a counter-clockwise unit).
  void set_firetime_correction(bool on) noexcept { firetime_correction_ = on; }
  /// The direction the unit spins (default clockwise); applies from the next decode(). The
  /// manuals give no packet field for it: set it from the unit's configuration, or from a
  /// RotationDetector (hesai/rotation.h) watching the stream.
  void set_rotation(Rotation rotation) noexcept;
  Rotation rotation() const noexcept { return rotation_; }
  /// The spread of point azimuths around their block azimuth over every channel and firing loop,
  /// at the spin rate and rotation of the last decode() or survey() (all zero before the first):
  /// what a FrameAssembler needs to know how far behind or ahead of a block its points can land.
  AzimuthSpread beam_spread() const noexcept { return spin_.spread; }

  /// QT128: the channel configuration (parse_channel_config_csv) that maps the units of packets
  /// with customised channels (flags bit 6) to channels. Without one such packets are
  /// Error::channel_config_required; with one whose LaserNum is not the packet's laser num,
  /// Error::channel_config_mismatch. A one-loop configuration maps the blocks of both firing
  /// sequences. Errors (and no change): invalid_argument for another model, a LaserNum outside
  /// 1..128, a loop count outside 1..2, or a channel outside 1..128 or listed twice in a loop;
  /// channel_config_mismatch for a BlockNum other than the QT128's 2.
  Error set_channel_config(const ChannelConfig& config) noexcept;
  /// Forgets the channel configuration.
  void clear_channel_config() noexcept { custom_lasers_ = 0; }

  /// What Point::intensity holds (raw by default). The packets do not say which mapping a
  /// Pandar64 is set to. Error::invalid_argument (and no change) for `nonlinear` on any other
  /// model: no other manual here gives a mapping.
  Error set_reflectivity(Reflectivity mapping) noexcept;

  /// Verifies QT128 signatures with this 32-byte session key (see hesai_session_key()).
  /// Error::unsupported_feature (and no key) in a core built with HESAI_SIGNATURE 0.
  [[nodiscard]] Error set_session_key(const std::uint8_t key[32]) noexcept;
  void clear_session_key() noexcept;
  /// With a key: accept packets that carry no signature instead of rejecting them
  /// (Error::signature_missing). Off by default.
  void set_allow_unsigned(bool allow) noexcept { allow_unsigned_ = allow; }

  /// Pandar40: takes the date and hour from a GPS packet for the packets that follow.
  void update_gps(const GpsPacket& gps) noexcept;

  /// Runs every check (length, header, flags, CRCs, signature, fields) and fills `info`. QT128:
  /// the units of the channels that rest in a block's firing sequence must be all zero (manual
  /// 3.1.2, "If a channel does not fire in the current firing sequence, its corresponding four
  /// bytes are filled with 0"); otherwise Error::resting_channel_data, and no point of the packet.
  [[nodiscard]] Error validate(ByteView payload, PacketInfo& info) noexcept;
  /// validate(), then the points: distance 0 yields no point. On error out.count is 0. `path`: the
  /// vector code the CPU has, or the portable scalar code (see DecodePath).
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, PacketPoints& out,
                             DecodePath path = DecodePath::best) noexcept;
  /// decode(), and the packet's units scanned into `scan` (blockage markers, repeated returns, distances
  /// beyond the rated range): a read of each unit's distance more. `scan` is reset first; left reset on error.
  /// With Returns::distinct the repeated second returns make no point (out.count is less by
  /// scan.duplicate_returns); the others keep their order.
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, PacketPoints& out, UnitScan& scan,
                             Returns returns = Returns::all, DecodePath path = DecodePath::best) noexcept;
  /// The same, and how each unit compares with the other returns of its firing into `compare`
  /// (reset first; left reset on error): what a nebula ReturnType needs. A pass over the units more.
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, PacketPoints& out, UnitScan& scan,
                             ReturnComparison& compare, Returns returns = Returns::all,
                             DecodePath path = DecodePath::best) noexcept;
  /// The same into caller-owned storage for `capacity` points (as the Point* form of decode()).
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, Point* points, std::size_t capacity, std::size_t& count,
                             UnitScan& scan, Returns returns = Returns::all,
                             DecodePath path = DecodePath::best) noexcept;
  /// decode() into caller-owned storage for `capacity` points, sized for this decoder's model
  /// (max_points(model()): 400, 384 or 256). Error::buffer_too_small, before the packet is read,
  /// when capacity is below that. `count` gets the number of points, 0 on error; the entries from
  /// `count` up to max_points(model()) may be overwritten too.
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, Point* points, std::size_t capacity, std::size_t& count,
                             DecodePath path = DecodePath::best) noexcept;
  /// decode() into columns (point.h): the same points, in the same order, as the Point forms.
  /// Error::buffer_too_small when out.capacity is below max_points(model()), Error::invalid_argument
  /// when a column is null; both before the packet is read. `count` gets the number of points, 0 on
  /// error. `path`: the vector code the CPU has, or the portable scalar code (see DecodePath).
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, const PointColumns& out, std::size_t& count,
                             DecodePath path = DecodePath::best) noexcept;
  /// decode() into columns, and the packet's units scanned into `scan` (as the Points form with a
  /// UnitScan; Returns::distinct is not offered for columns: every unit's point is written).
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, const PointColumns& out, std::size_t& count,
                             UnitScan& scan, DecodePath path = DecodePath::best) noexcept;
  /// What a packet gives besides its points, without making them: validate() (`info`, with the
  /// block azimuths), the unit scan as decode() fills it, `points` the number of points decode()
  /// with Returns::all makes of it, and beam_spread() at its spin rate: all a caller needs to
  /// count a packet and follow its frames (FrameAssembler::block) when it keeps none of its
  /// points, such as one outside a range of packets. Leaves the decoder as decode() would (the
  /// points of later packets are the same bits). Cost: validate(), a read of each unit's
  /// distance, the scan; no per-point arithmetic, no point stored; at a new spin rate the spread
  /// (on x86-64 with vector code, without the per-rate arrays, which the next decode() builds).
  /// On error `points` is 0 and `scan` reset.
  [[nodiscard]] Error survey(ByteView payload, PacketInfo& info, UnitScan& scan, std::size_t& points,
                             DecodePath path = DecodePath::best) noexcept;
  /// decode() into columns with their own storage (N >= max_points(model())).
  template <std::size_t N>
  [[nodiscard]] Error decode(ByteView payload, PacketInfo& info, PacketColumns<N>& out,
                             DecodePath path = DecodePath::best) noexcept {
    return decode(payload, info, out.columns(), out.count, path);
  }

 private:
  // Per-channel geometry from the tables or calibration files, one array per quantity.
  // (sin_el, elevation_deg and fire_ns in this order: the ARMv7E-M loops reach each from one pointer,
  // kernels/armv7m_loops.h.)
  struct Geometry {
    std::array<float, kMaxChannels> sin_el{};
    std::array<float, kMaxChannels> elevation_deg{};
    std::array<std::array<std::int32_t, kMaxChannels>, 2> fire_ns{};  // firing time offset, ns, [loop][channel]
    std::array<float, kMaxChannels> cos_el_cos_az{};  // cos(elevation) cos(azimuth offset)
    std::array<float, kMaxChannels> cos_el_sin_az{};  // cos(elevation) sin(azimuth offset)
    std::array<float, kMaxChannels> azimuth_deg{};                   // azimuth offset
  };
  // The part of each point that depends only on the channel, the firing loop and the spin rate,
  // computed once per rate: the beam direction b (azimuth offset + firing-time correction) as
  // cos(e) cos(b), cos(e) sin(b) and b in degrees, loop[firing loop].<array>[channel] (a loop's
  // arrays side by side: the ARMv7E-M loops reach dir_sin from the dir_cos pointer). A firing
  // loop's arrays are rebuilt when a packet first uses them at the rate (a dual-return QT128 packet
  // uses one loop).
  struct SpinCache {
    static constexpr std::uint16_t kStale = 0xFFFF;  // above any accepted rpm
    struct Beams {
      std::array<float, kMaxChannels> dir_cos{}, dir_sin{}, azimuth_deg{};
    };
    std::uint16_t rpm = kStale;  // the spin rate the spread holds (0: no firing-time correction)
    std::uint8_t stale_loops = 0;  // bit l: loop l's arrays are not yet at rpm (its spread is)
    std::array<Beams, 2> loop{};
    AzimuthSpread spread;        // of every loop's azimuth_deg, folded into (-180, 180]
  };

  // The sensors' code (core/src/sensors/, one file each, listed in registry.cpp) reads and sets
  // the state below: SensorBase holds what every sensor shares, each sensor's functions are the
  // members of its SensorCode<tag> (sensors/sensor.h).
  friend struct SensorBase;
  friend struct DecodeOutput;  // holds a UnitPass
  template <class Tag>
  friend struct SensorCode;

  void set_channel_angle(std::size_t ch, double elevation_deg, double azimuth_deg) noexcept;
  void set_channel_firetime(std::size_t ch, double loop1_us, double loop2_us) noexcept;
  // Sets resting_first_ and resting_count_ from resting_.
  void find_resting_runs() noexcept;
  // Brings spin_ to `rpm` for the firing loops in `loops` (bit l: loop l) by the code of `path`
  // (every path gives the same bits): at a new rate the spread of every loop, the arrays of those
  // in `loops` (the others' arrays when a later packet uses them). Const: SensorBase::emit_blocks
  // calls it, which sees the decoder const; spin_ is a cache of the geometry.
  void update_spin(std::uint16_t rpm, unsigned loops, DecodePath path) const noexcept;
  // A pass over a validated packet's raw units that only one caller asks for (sensors/decoder.cpp):
  // compare_returns fills a ReturnComparison (the decode() form that takes one), survey_units
  // scans the units and counts the points survey() does not make. Each is handed down by address, so that a program
  // that never calls its form links none of its code (the Cortex-M0+ image's 48 KiB of flash,
  // tests/firmware). SensorBase::emit_blocks runs it first, and makes the points of the blocks it
  // returns: block_count, or 0. `into`: its output (a ReturnComparison, survey()'s).
  // (No member initializers: a default argument below value-initializes it, both null.)
  struct UnitPass {
    void* into;
    std::size_t (*run)(const kernels::BlockRef* blocks, std::size_t block_count, std::size_t unit_count,
                std::size_t unit_bytes, const PacketInfo& info, void* into) noexcept;
  };
  // Every decode() form: the capacity check, validate(), the sensor's walk into `points` (when not
  // null) or `columns`; count 0 on error. (The form with a ReturnComparison has its own copy.)
  [[nodiscard]] Error decode_into(ByteView payload, PacketInfo& info, Point* points, const PointColumns* columns,
                                  std::size_t capacity, std::size_t& count, DecodePath path,
                                  UnitScan* scan = nullptr) noexcept;

  Model model_;
  bool firetime_correction_ = true;
  Rotation rotation_ = Rotation::clockwise;
  bool has_key_ = false;
  bool allow_unsigned_ = false;
  bool has_gps_ = false;
  Reflectivity reflectivity_ = Reflectivity::raw;
  std::uint8_t custom_lasers_ = 0;  // QT128 channel configuration: units per block (0: none set)
  DateTime gps_time_;            // Pandar40: last GPS date-time
  Geometry geo_;
  mutable SpinCache spin_;  // filled on demand by update_spin()
  // QT128 channel configuration: the 0-based channel of each unit, [loop][unit] (256 bytes).
  std::array<std::array<std::uint8_t, kMaxChannels>, 2> custom_channel_{};
  // QT128: the channels that rest in each firing sequence, bit (ch % 8) of byte ch / 8 for the
  // 0-based channel ch, [loop] (32 bytes): the manual's bank rule, or the firetime file's. When
  // they are one run of channels (the manual's banks), validate() reads that run of units at
  // once: its first channel and length, [loop]; length kRestingScattered when they are not.
  static constexpr std::uint8_t kRestingScattered = 0xFF;
  std::array<std::array<std::uint8_t, kMaxChannels / 8>, 2> resting_{};
  std::array<std::uint8_t, 2> resting_first_{}, resting_count_{};
#if HESAI_SIGNATURE
  HmacSha256Key key_;
#endif
};

// The budget for a decoder context: what a firmware image can afford per sensor.
static_assert(sizeof(Decoder) <= 8 * 1024, "decoder state must stay within 8 KiB");

}  // namespace hesai
