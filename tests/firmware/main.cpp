// The bare-metal test image: the core's known answers and one real packet of each sensor, decoded
// on a Cortex-M under qemu-system-arm. Reports through semihosting; exit status 0 when all pass.
//
// What it shows:
// - CRC-32/MPEG-2, SHA-256, HMAC-SHA256 and HKDF give the published answers on the target.
// - One real packet per sensor (fuzz/seed_packets.inc, from data/*.pcap) decodes to the points
//   derived by hand from the manuals (tests/firmware/derive_points.py prints them), and does so at
//   every byte offset 0..3. In the ARMv6-M (Cortex-M0+) image a wire field read through a cast
//   would fault at an odd address: the startup code arms the alignment trap, checked below.
// - The C path (c_path.c, C99 through hesai.h) decodes the QT128 packet to the same points as
//   hesai::Decoder, and gives the errors hesai.h names for a damaged packet and a short array.
// - The stack each entry point used, measured by painting the stack, and sizeof(Decoder).
// - Under qemu-system-arm -icount shift=7 (report.py runs it so): the instructions per packet of
//   validate() and decode() for each sensor, of decode() when the spin rate changed, of the
//   stream health, of the frame assembly (Cortex-M4F only), and of the QT128 signature check,
//   exact (see "Instructions per packet").
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

#include "hesai/calibration.h"
#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/detail/kernel_calls.h"
#include "hesai/frame.h"
#include "hesai/health.h"
#include "hesai/hkdf.h"
#include "hesai/hmac.h"
#include "hesai/detail/pandar40_packet.h"
#include "hesai/detail/pandar64_packet.h"
#include "hesai/detail/qt128_packet.h"
#include "hesai/detail/qt64_packet.h"
#include "hesai/sha256.h"
#include "hesai/detail/xt_packet.h"
#include "alt_hooks.h"
#include "c_path.h"
#include "semihost.h"

#include "../../fuzz/seed_packets.inc"

extern "C" {
extern std::uint32_t __stack_limit[];
extern volatile std::uint32_t firmware_expect_fault;
extern volatile std::uint32_t firmware_faults_seen;
}

namespace {

using hesai::ByteView;
using hesai::Error;
using hesai::Model;

int failures = 0;

// The figure decoder.h states ("Memory"), on the target.
static_assert(sizeof(hesai::Decoder) == (HESAI_SIGNATURE ? 7208 : 6980), "decoder.h: Memory");

// ---- Output ---------------------------------------------------------------------------------

void print(const char* s) { semihost_write(s); }

void print_int(std::int64_t v) {
  char text[24];
  char* p = text + sizeof text;
  *--p = 0;
  const bool negative = v < 0;
  std::uint64_t u = negative ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
  do {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u != 0);
  if (negative) *--p = '-';
  print(p);
}

// v with 4 decimals (enough for metres to 0.1 mm).
void print_fixed4(float v) {
  const std::int64_t tenths_of_mm = static_cast<std::int64_t>(v * 10000.0f + (v < 0 ? -0.5f : 0.5f));
  if (tenths_of_mm < 0) print("-");
  const std::int64_t a = tenths_of_mm < 0 ? -tenths_of_mm : tenths_of_mm;
  print_int(a / 10000);
  char frac[6] = {'.', static_cast<char>('0' + a / 1000 % 10), static_cast<char>('0' + a / 100 % 10),
                  static_cast<char>('0' + a / 10 % 10), static_cast<char>('0' + a % 10), 0};
  print(frac);
}

void check(bool ok, const char* what) {
  if (!ok) {
    ++failures;
    print("FAIL: ");
    print(what);
    print("\n");
  }
}

// ---- Known answers ----------------------------------------------------------------------------

[[maybe_unused]] bool equal_hex(const std::uint8_t* got, const char* hex, std::size_t n) {  // crypto answers
  auto nibble = [](char c) { return c <= '9' ? c - '0' : c - 'a' + 10; };
  for (std::size_t i = 0; i < n; ++i) {
    const int want = nibble(hex[2 * i]) * 16 + nibble(hex[2 * i + 1]);
    if (got[i] != want) return false;
  }
  return true;
}

ByteView text(const char* s) { return {reinterpret_cast<const std::uint8_t*>(s), std::strlen(s)}; }

void known_answers() {
  // CRC-32/MPEG-2 check value (poly 0x04C11DB7, init 0xFFFFFFFF, no reflection, no xorout).
  const ByteView digits = text("123456789");
  for (const auto path : {hesai::CrcPath::bitwise, hesai::CrcPath::table, hesai::CrcPath::slicing, hesai::CrcPath::hardware})
    check(hesai::crc32_mpeg2_update(path, hesai::kCrc32Mpeg2Init, digits) == 0x0376E6E7u, "CRC-32/MPEG-2 of 123456789");

#if HESAI_SIGNATURE
  std::uint8_t out[64];
  // FIPS 180-4 examples (one block, two blocks).
  hesai::sha256(text("abc"), out);
  check(equal_hex(out, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad", 32), "SHA-256 abc");
  hesai::sha256(text("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"), out);
  check(equal_hex(out, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1", 32), "SHA-256 448 bits");

  // RFC 4231 test cases 1 and 2.
  std::uint8_t key[131];
  std::memset(key, 0x0b, 20);
  hesai::hmac_sha256({key, 20}, text("Hi There"), out);
  check(equal_hex(out, "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7", 32), "HMAC-SHA256 RFC 4231 case 1");
  hesai::hmac_sha256(text("Jefe"), text("what do ya want for nothing?"), out);
  check(equal_hex(out, "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843", 32), "HMAC-SHA256 RFC 4231 case 2");
  // RFC 4231 case 6: a 131-byte key, longer than a block, is hashed first.
  std::memset(key, 0xaa, 131);
  hesai::hmac_sha256({key, 131}, text("Test Using Larger Than Block-Size Key - Hash Key First"), out);
  check(equal_hex(out, "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54", 32), "HMAC-SHA256 RFC 4231 case 6");

  // RFC 5869 test case 1.
  std::uint8_t ikm[22], salt[13], info[10];
  std::memset(ikm, 0x0b, sizeof ikm);
  for (std::uint8_t i = 0; i < 13; ++i) salt[i] = i;
  for (std::uint8_t i = 0; i < 10; ++i) info[i] = static_cast<std::uint8_t>(0xf0 + i);
  check(hesai::hkdf_sha256({salt, 13}, {ikm, 22}, {info, 10}, out, 42) == Error::ok, "HKDF-SHA256 status");
  check(equal_hex(out, "3cb25f25faacd57a90434f64d0362f2a2d2d0a90cf1a5a4c5db02d56ecc4c5bf34007208d5b887185865", 42),
        "HKDF-SHA256 RFC 5869 case 1");
#endif
}

// ---- Real packets -------------------------------------------------------------------------------

// A point derived by hand from the manuals (tests/firmware/derive_points.py has every input).
struct Expected {
  std::uint8_t block;  // 0-based
  std::uint8_t channel;
  std::uint8_t intensity;
  float x, y, z, azimuth_deg;
  std::int64_t time_ns;
};

// One packet's points, or (for the columnar form's instruction count) its columns in the same RAM.
struct ColumnArrays {
  float x[hesai::kMaxPointsPerPacket], y[hesai::kMaxPointsPerPacket], z[hesai::kMaxPointsPerPacket];
  std::int32_t time_ns[hesai::kMaxPointsPerPacket];
  std::uint8_t intensity[hesai::kMaxPointsPerPacket], channel[hesai::kMaxPointsPerPacket], ret[hesai::kMaxPointsPerPacket];
};
// Also a unit's angle file, while it is handed to Decoder::set_angles (which keeps what it needs).
union PointStorage {
  PointStorage() : points() {}
  hesai::PacketPoints points;
  ColumnArrays columns;
  hesai::AngleCorrection angles;
};
static_assert(sizeof(hesai::AngleCorrection) <= sizeof(hesai::PacketPoints), "the angles take no RAM of their own");
PointStorage storage;
hesai::PacketPoints& points = storage.points;
hesai::PointColumns column_view() {
  ColumnArrays& c = storage.columns;
  hesai::PointColumns v;
  v.x = c.x;
  v.y = c.y;
  v.z = c.z;
  v.time_ns = c.time_ns;
  v.intensity = c.intensity;
  v.channel = c.channel;
  v.return_index = c.ret;
  v.capacity = hesai::kMaxPointsPerPacket;
  return v;
}
const hesai::PointColumns columns = column_view();
std::size_t column_count = 0;
// Four decoders fit the 64 KiB RAM region beside the points and the stack. The PandarQT64 and
// PandarXT models borrow the Pandar40's (decoders[0]), rebuilt in place for each: guest().
hesai::Decoder decoders[] = {hesai::Decoder(Model::pandar40), hesai::Decoder(Model::pandar40p),
                             hesai::Decoder(Model::pandar64), hesai::Decoder(Model::qt128c2x)};
hesai::Decoder& guest(Model m) {
  decoders[0].~Decoder();
  return *::new (&decoders[0]) hesai::Decoder(m);
}
// The packet copied to an offset 0..3 from a 4-byte boundary.
alignas(8) std::uint8_t shifted[1300];

float absf(float v) { return v < 0 ? -v : v; }

std::size_t nonzero_distances(ByteView p, std::size_t first, std::size_t block_bytes, std::size_t blocks,
                              std::size_t channels, std::size_t point_bytes, unsigned min_distance) {
  std::size_t n = 0;
  for (std::size_t b = 0; b < blocks; ++b)
    for (std::size_t c = 0; c < channels; ++c) {
      const std::uint8_t* q = p.data + first + b * block_bytes + c * point_bytes;
      if (static_cast<unsigned>(q[0] | q[1] << 8) >= min_distance) ++n;
    }
  return n;
}

void check_packet(const char* name, hesai::Decoder& decoder, ByteView packet, std::size_t want_points,
                  const Expected* want, std::size_t want_count) {
  for (std::size_t shift = 0; shift < 4; ++shift) {
    std::memcpy(shifted + shift, packet.data, packet.size);
    hesai::PacketInfo info;
    const Error e = decoder.decode({shifted + shift, packet.size}, info, points);
    check(e == Error::ok, name);
    check(points.count == want_points, "point count = non-zero distances");
    for (std::size_t i = 0; i < want_count; ++i) {
      const Expected& w = want[i];
      const hesai::Point* got = nullptr;
      for (const hesai::Point& p : points)
        if (p.block == w.block && p.channel == w.channel) got = &p;
      check(got != nullptr, "hand-checked point present");
      if (got == nullptr) continue;
      const bool ok = absf(got->x - w.x) < 1e-3f && absf(got->y - w.y) < 1e-3f && absf(got->z - w.z) < 1e-3f &&
                      absf(got->azimuth_deg - w.azimuth_deg) < 1e-3f && got->time_ns == w.time_ns &&
                      got->intensity == w.intensity;
      check(ok, "hand-checked point");
      if (shift == 0) {
        print("  ");
        print(name);
        print(" block ");
        print_int(w.block);
        print(" channel ");
        print_int(w.channel);
        print(": x ");
        print_fixed4(got->x);
        print(" y ");
        print_fixed4(got->y);
        print(" z ");
        print_fixed4(got->z);
        print(" m, time ");
        print_int(got->time_ns);
        print(" ns\n");
      }
    }
  }
}

void real_packets() {
  using namespace hesai;
  // Values from tests/firmware/derive_points.py (the manuals' tables and formulas, the packet bytes).
  static const Expected p40p[] = {{0, 1, 6, 0.5722f, 4.4881f, 1.2123f, 7.2660f, 1504714786883218960},
                                  {0, 2, 13, 0.6065f, 4.7241f, 0.9258f, 7.3155f, 1504714786883232710}};
  static const Expected p40[] = {{0, 1, 6, 0.5722f, 4.4881f, 1.2123f, 7.2660f, 883218960}};
  // Pandar64 year byte 120 = 2020 (the vendor SDK's rule). These times were 2120 by the manual's
  // year - 2000: 2020-06-25 to 2120-06-25 is 100 x 365 days + the leap days 2024, 2028, ..., 2120
  // (25 years divisible by 4) less 2100 (a century not divisible by 400) = 36500 + 24 = 36524 days
  // = 36524 x 86400 s = 3 155 673 600 s; 4748760129978331120 - 3155673600000000000 =
  // 1593086529978331120, and 4748760129978336336 - 3155673600000000000 = 1593086529978336336
  // (2020-06-25 12:02:09 UTC is 1593086529 s: 18438 days x 86400 + 43329 s).
  static const Expected p64[] = {{0, 1, 44, 0.1420f, 2.1408f, 0.5702f, 3.7947f, 1593086529978331120},
                                 {0, 5, 8, 0.1427f, 2.1402f, 0.1139f, 3.8134f, 1593086529978336336}};
  static const Expected qt[] = {{0, 35, 1, 0.0432f, 0.3306f, -0.0996f, 7.4513f, 1602245009403807312},
                                {0, 38, 15, 0.0417f, 0.3154f, -0.0799f, 7.5397f, 1602245009403810480}};
  // PandarQT64 (no manual here: the vendor SDK's layout and files, named in derive_points.py).
  static const Expected qt64[] = {{2, 10, 202, 0.0258f, 0.0854f, -0.0609f, 16.8304f, 1504708282820634600},
                                  {2, 54, 30, 0.3568f, 4.1823f, 2.6872f, 4.8758f, 1504708282820728870}};

  // The Pandar40: the real Pandar40P packet's blocks with the Pandar40's 16-byte tail (its first
  // 1256 bytes); no Pandar40 capture is at hand.
  const ByteView b40{kPandar40P, 1256}, b40p{kPandar40P, sizeof kPandar40P};
  const ByteView b64{kPandar64, sizeof kPandar64}, bqt{kQt128, sizeof kQt128};
  check_packet("Pandar40", decoders[0], b40, nonzero_distances(b40, 4, 124, 10, 40, 3, 1), p40, 1);
  check_packet("Pandar40P", decoders[1], b40p, nonzero_distances(b40p, 4, 124, 10, 40, 3, 1), p40p, 2);
  check_packet("Pandar64", decoders[2], b64, nonzero_distances(b64, 8 + 2, 194, 6, 64, 3, 1), p64, 2);
  // QT128: distance 1 is a marker, not a point.
  check_packet("QT128C2X", decoders[3], bqt, nonzero_distances(bqt, 12 + 2, 514, 2, 128, 4, 2), qt, 2);
  const ByteView bqt64{kQt64, sizeof kQt64};
  check_packet("PandarQT64", guest(Model::pandar_qt64), bqt64, nonzero_distances(bqt64, 12 + 2, 258, 4, 64, 4, 1), qt64, 2);

  // PandarXT16, XT32, XT32M2X (protocol 6.1, no CRC): each with its design tables, 4-byte units
  // after a 2-byte block azimuth, 12-byte header.
  static const Expected xt16[] = {{0, 1, 48, -0.8857f, 0.0728f, 0.2381f, 274.7016f, 1564027949276045000},
                                  {7, 16, 1, -1.0347f, 0.0979f, -0.2785f, 275.4049f, 1564027949276240360}};
  static const Expected xt32[] = {{0, 2, 52, 0.2365f, 2.1957f, 0.5506f, 6.1470f, 1564024769620422512},
                                  {7, 32, 0, 0.0229f, 0.1909f, -0.0551f, 6.8500f, 1564024769620617872}};
  static const Expected xt32m2x[] = {{0, 2, 86, 0.2083f, 2.6279f, 0.8667f, 4.5319f, 1564037176851061888},
                                     {5, 1, 81, 0.2250f, 2.6345f, 0.9363f, 4.8816f, 1564037176851159000}};
  struct XtCase {
    const char* name;
    Model model;
    ByteView packet;
    std::size_t blocks, channels;
    const Expected* want;
  };
  const XtCase xts[] = {{"PandarXT16", Model::pandar_xt16, {kXt16, sizeof kXt16}, 8, 16, xt16},
                        {"PandarXT32", Model::pandar_xt32, {kXt32, sizeof kXt32}, 8, 32, xt32},
                        {"PandarXT32M2X", Model::pandar_xt32m2x, {kXt32m2x, sizeof kXt32m2x}, 6, 32, xt32m2x}};
  for (const XtCase& c : xts) {
    check_packet(c.name, guest(c.model), c.packet,
                 nonzero_distances(c.packet, 12 + 2, 2 + 4 * c.channels, c.blocks, c.channels, 4, 1), c.want, 2);
  }

  // Integrity on the target: a flipped body byte fails CRC1; a session key with an unsigned packet
  // fails as signature_missing (without signature support: no key, a signed packet is unverified).
  std::memcpy(shifted, kQt128, sizeof kQt128);
  shifted[100] ^= 0x01;
  PacketInfo info;
  check(decoders[3].decode({shifted, sizeof kQt128}, info, points) == Error::crc_body && points.count == 0,
        "QT128 flipped body byte -> crc_body");
  std::uint8_t key[32] = {};
#if HESAI_SIGNATURE
  check(decoders[3].set_session_key(key) == Error::ok, "QT128 session key");
  check(decoders[3].decode(bqt, info, points) == Error::signature_missing, "QT128 unsigned packet with a key");
#if HESAI_CRC32_ALT && HESAI_SHA256_ALT
  // The platform hooks: a signed packet validates through them, three CRCs (body, functional
  // safety, tail) and 19 SHA-256 compressions (the inner hash of the 1 095 signed bytes after the
  // precomputed key block, 18; the outer one, 1).
  std::memcpy(shifted, kQt128, sizeof kQt128);
  check(hesai::qt128::sign(shifted, sizeof kQt128, key) == Error::ok, "QT128 signed by the hooks");
  const std::size_t crc_before = firmware_crc_hook_calls, sha_before = firmware_sha_hook_blocks;
  check(decoders[3].validate({shifted, sizeof kQt128}, info) == Error::ok &&
            info.signature == hesai::SignatureStatus::valid,
        "QT128 signature valid through the hooks");
  check(firmware_crc_hook_calls - crc_before == 3, "three CRCs through the CRC hook");
  check(firmware_sha_hook_blocks - sha_before == 19, "19 compressions through the SHA-256 hook");
#endif
  decoders[3].clear_session_key();
#else
  check(decoders[3].set_session_key(key) == Error::unsupported_feature, "no session key without HESAI_SIGNATURE");
  std::memcpy(shifted, kQt128, sizeof kQt128);
  shifted[sizeof kQt128 - 1] = 0x5A;  // a signature byte: the last 32 bytes, after CRC3, which does not cover them
  check(decoders[3].decode({shifted, sizeof kQt128}, info, points) == Error::ok &&
            info.signature == hesai::SignatureStatus::unverified,
        "QT128 signed packet without signature support -> unverified");
#endif
}

// ---- The C path ---------------------------------------------------------------------------------

// Every member of every point, folded into one CRC: two arrays of points with the same digest
// hold the same values (the RAM holds one packet's points, not two).
template <class P>
std::uint32_t digest(const P* pts, std::size_t count) {
  std::uint32_t crc = hesai::kCrc32Mpeg2Init;
  auto add = [&crc](const auto& v) {
    std::uint8_t bytes[sizeof v];
    std::memcpy(bytes, &v, sizeof v);
    crc = hesai::crc32_mpeg2_update(hesai::CrcPath::table, crc, {bytes, sizeof bytes});
  };
  for (std::size_t i = 0; i < count; ++i) {
    const P& p = pts[i];
    add(p.x), add(p.y), add(p.z), add(p.distance_m), add(p.azimuth_deg), add(p.elevation_deg), add(p.time_ns);
    add(p.intensity), add(p.channel), add(p.return_index), add(p.confidence), add(p.block);
  }
  return crc;
}

// The caller's array of the C path: the storage of `points`, as C sees it (hesai_point has
// hesai::Point's layout).
hesai_point* c_points() { return reinterpret_cast<hesai_point*>(points.points.data()); }

void c_path() {
  const ByteView bqt{kQt128, sizeof kQt128};
  hesai::PacketInfo info;
  check(decoders[3].decode(bqt, info, points) == Error::ok, "QT128C2X packet");
  const std::size_t want_count = points.count;
  const std::uint32_t want = digest(points.points.data(), points.count);

  failures += firmware_c_path_checks(kQt128, sizeof kQt128, c_points(), 256, shifted, sizeof shifted);
  std::size_t count = 0;
  check(firmware_c_decode(kQt128, sizeof kQt128, c_points(), 256, &count) == HESAI_ERROR_ok, "C path: QT128C2X packet");
  check(count == want_count && count == nonzero_distances(bqt, 12 + 2, 514, 2, 128, 4, 2), "C path: point count");
  check(digest(c_points(), count) == want, "C path: the same points as hesai::Decoder");
  // The hand-checked point of real_packets(): block 0, channel 35.
  bool found = false;
  for (std::size_t i = 0; i < count; ++i) {
    const hesai_point& p = c_points()[i];
    if (p.block != 0 || p.channel != 35) continue;
    found = absf(p.x - 0.0432f) < 1e-3f && absf(p.y - 0.3306f) < 1e-3f && absf(p.z - -0.0996f) < 1e-3f &&
            p.time_ns == 1602245009403807312;
  }
  check(found, "C path: hand-checked point");
  print("C path (hesai.h, c_path.c): QT128C2X packet, ");
  print_int(static_cast<std::int64_t>(count));
  print(" points, the same as hesai::Decoder's\n");
}

// ---- The alignment trap -------------------------------------------------------------------------

#if defined(__ARM_ARCH_6M__)
void alignment_trap_armed() {
  alignas(4) static volatile std::uint8_t bytes[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  firmware_expect_fault = 1;
  const std::uint32_t before = firmware_faults_seen;
  // A 16-bit LDR from an odd address: faults with CCR.UNALIGN_TRP set (always on ARMv6-M).
  __asm volatile("ldr r2, [%0]" : : "l"(bytes + 1) : "r2", "memory");
  check(firmware_faults_seen == before + 1, "an unaligned load faults (alignment trap armed)");
  firmware_expect_fault = 0;
}
#else
void alignment_trap_armed() {}
#endif

// ---- Stack use ----------------------------------------------------------------------------------

constexpr std::uint32_t kPaint = 0xC5C5C5C5u;

std::uintptr_t stack_pointer() {
  std::uintptr_t sp;
  __asm volatile("mov %0, sp" : "=r"(sp));
  return sp;
}

// Bytes of stack below the caller's frame that f touched.
template <class F>
__attribute__((noinline)) std::uint32_t stack_used(F f) {
  const std::uintptr_t top = stack_pointer();
  volatile std::uint32_t* const limit = __stack_limit;
  for (volatile std::uint32_t* p = limit; reinterpret_cast<std::uintptr_t>(p) < top - 64; ++p) *p = kPaint;
  f();
  volatile std::uint32_t* p = limit;
  while (reinterpret_cast<std::uintptr_t>(p) < top && *p == kPaint) ++p;
  return static_cast<std::uint32_t>(top - reinterpret_cast<std::uintptr_t>(p));
}

// The Error of the call stack_used() measures, checked (then reset) by report_stack().
Error measured = Error::ok;

void report_stack(const char* name, std::uint32_t bytes) {
  print("  ");
  print(name);
  print(": ");
  print_int(bytes);
  print(" bytes\n");
#if HESAI_CRC32_ALT && HESAI_SHA256_ALT
  // The platform hooks' own frames are counted too: here software ones (alt_hooks.cpp, up to 192
  // bytes more on the Cortex-M0+), where a platform's would drive its hardware. No budget.
#else
  check(bytes <= 1024, "stack per call <= 1 KiB");
#endif
  check(measured == Error::ok, name);
  measured = Error::ok;
}

void stack_use() {
  using namespace hesai;
  static const std::uint8_t data[1095] = {1, 2, 3};
  [[maybe_unused]] static std::uint8_t out[42];  // the crypto calls (HESAI_SIGNATURE 1)
  static PacketInfo info;
  const ByteView bqt{kQt128, sizeof kQt128};
  print("stack used per call (painted stack):\n");
  report_stack("Decoder::decode Pandar40P", stack_used([] { measured = decoders[1].decode({kPandar40P, sizeof kPandar40P}, info, points); }));
  report_stack("Decoder::decode Pandar64", stack_used([] { measured = decoders[2].decode({kPandar64, sizeof kPandar64}, info, points); }));
  report_stack("Decoder::decode QT128C2X", stack_used([&] { measured = decoders[3].decode(bqt, info, points); }));
  guest(Model::pandar_qt64);
  report_stack("Decoder::decode PandarQT64", stack_used([] { measured = decoders[0].decode({kQt64, sizeof kQt64}, info, points); }));
  report_stack("Decoder::validate QT128C2X", stack_used([&] { measured = decoders[3].validate(bqt, info); }));
  guest(Model::pandar_xt32m2x);
  report_stack("Decoder::decode PandarXT32M2X", stack_used([] { measured = decoders[0].decode({kXt32m2x, sizeof kXt32m2x}, info, points); }));
  report_stack("crc32_mpeg2 (1095 B)", stack_used([] { (void)crc32_mpeg2({data, sizeof data}); }));
#if HESAI_SIGNATURE
  report_stack("sha256 (1095 B)", stack_used([] { sha256({data, sizeof data}, out); }));
  report_stack("hmac_sha256 (1095 B)", stack_used([] { hmac_sha256({data, 32}, {data, sizeof data}, out); }));
  report_stack("hkdf_sha256 (42 B)", stack_used([] { measured = hkdf_sha256({data, 13}, {data, 22}, {data, 10}, out, 42); }));
  report_stack("hesai_session_key", stack_used([] { measured = hesai_session_key({data, 32}, data, data + 32, out); }));
#endif
  report_stack("hesai_decoder_decode (C) QT128C2X", stack_used([] {
    std::size_t count = 0;
    measured = static_cast<Error>(firmware_c_decode(kQt128, sizeof kQt128, c_points(), 256, &count));  // hesai_error: the same values
  }));
  // The constructor, rebuilding the QT128 decoder in place (no fifth decoder in RAM for it).
  decoders[3].~Decoder();
  report_stack("Decoder::Decoder QT128C2X", stack_used([] { ::new (&decoders[3]) Decoder(Model::qt128c2x); }));
}

// ---- Instructions per packet --------------------------------------------------------------------
//
// qemu models no cycles, but with -icount shift=7 it advances its virtual clock by exactly 2^7 =
// 128 ns per instruction executed, and SysTick, on the board's 25 MHz processor clock, counts that
// clock down every 40 ns: n instructions move it by 3.2 n ticks, less than one tick off at either
// end (the reading rounds the time to the next tick). So n = round(ticks / 3.2) exactly: the error,
// under 1 / 3.2 instruction, is below one half. The count runs from one SysTick read to the next, so
// the same span around an empty function is subtracted; what is left is the callee's instructions,
// call and return included. Checked on functions of exactly 1 and 1 000 instructions beside the
// empty one (a nop each); without -icount (the plain ctest run) the check fails and no count is
// printed. The 24-bit counter allows 5.2 million instructions per count (COUNTFLAG: over).

volatile std::uint32_t& syst_csr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E010u);
volatile std::uint32_t& syst_rvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E014u);
volatile std::uint32_t& syst_cvr = *reinterpret_cast<volatile std::uint32_t*>(0xE000E018u);
constexpr std::uint32_t kCountFlag = 1u << 16;

// SysTick ticks from just before f() to just after it; ~0u when the counter wrapped.
__attribute__((noinline)) std::uint32_t ticks_of(void (*f)()) {
  syst_csr = 0;
  syst_rvr = 0xFFFFFFu;
  syst_cvr = 0;            // any write clears it: reloads on the next tick
  syst_csr = 5;            // enabled, processor clock, no interrupt
  while (syst_cvr == 0) {}
  [[maybe_unused]] const std::uint32_t clear = syst_csr;  // a read clears COUNTFLAG
  const std::uint32_t start = syst_cvr;
  f();
  const std::uint32_t end = syst_cvr;
  const bool wrapped = (syst_csr & kCountFlag) != 0;
  syst_csr = 0;
  return wrapped ? ~0u : start - end;
}

std::uint32_t span_of(void (*f)()) {
  const std::uint32_t t = ticks_of(f);
  return t == ~0u ? ~0u : (t * 10 + 16) / 32;  // round(t / 3.2)
}

__attribute__((noinline)) void nothing() { __asm volatile(""); }
__attribute__((noinline)) void one_nop() { __asm volatile("nop"); }
__attribute__((noinline)) void thousand_nops() { __asm volatile(".rept 1000\n\tnop\n\t.endr"); }

// Instructions f() executes (call and return included); ~0u when too long to count.
std::uint32_t instructions(void (*f)()) {
  const std::uint32_t n = span_of(f), empty = span_of(nothing);
  return n == ~0u ? ~0u : n - empty + 1;  // + 1: the empty function's own return
}

// What the measured calls work on (captureless lambdas, so plain function pointers).
hesai::Decoder* subject = nullptr;
ByteView packet;
hesai::PacketInfo subject_info;
Error subject_error = Error::ok;

// Stream health (issue #32): the monitor primed with a packet, the next packet in order (one
// packet's time and azimuth step on), and the unit scan of the packet's decode.
hesai::HealthMonitor health_monitor;
hesai::PacketInfo next_info;
hesai::UnitScan subject_scan;

// Frame assembly (issue #43), where the image has room for it: on the Cortex-M4F, not in the
// Cortex-M0+ image, whose flash report.py holds to 48 KiB (nothing here calls FrameAssembler
// there, so the linker leaves it out).
#if defined(__ARM_ARCH_7EM__) && defined(__ARM_FP)
#define HESAI_FIRMWARE_FRAMES 1
#else
#define HESAI_FIRMWARE_FRAMES 0
#endif
#if HESAI_FIRMWARE_FRAMES
// A stream under way (one block a degree before the packet's first), the cut half a turn from the
// packet so that no block straddles it, no point across 0 from its block: the common case. The measured calls then take the packet
// decoded into `points` (frames_info its blocks) as hesai's Pipeline does: begin_packet(), block()
// per block with the closed frames taken, and the block's points by points() or point by point.
hesai::FrameAssembler frame_assembler;
hesai::PacketInfo frames_info;
std::size_t frames_split = 0;  // blocks whose points points() gave to more than one frame

void prime_frames() {
  frame_assembler.reset();
  const std::uint32_t first = frames_info.block_azimuth[0];
  check(frame_assembler.set_cut_deg(static_cast<float>((first + 18000u) % 36000u) / 100.0f) == Error::ok, "frames: cut");
  check(frame_assembler.set_beam_spread(subject->beam_spread()) == Error::ok, "frames: beam spread");
  frame_assembler.begin_packet(0, 0);
  (void)frame_assembler.block(static_cast<std::uint16_t>((first + 36000u - 100u) % 36000u));
  frames_split = 0;
}

template <bool kByBlock>
void assign_frames() {
  frame_assembler.begin_packet(1, 0);
  std::size_t next = 0;
  for (std::size_t b = 0; b < frames_info.blocks; ++b) {
    if (frame_assembler.block(frames_info.block_azimuth[b]))
      for (hesai::FrameInfo f; frame_assembler.pop_closed(f);) {}
    const std::size_t first = next;
    while (next < points.count && points.points[next].block == b) ++next;
    if (kByBlock) {
      // No ids: in one frame, the id returned is every point's (ids_out only for a split block).
      if (next > first && frame_assembler.points(&points.points[first].azimuth_deg, next - first,
                                                 sizeof(hesai::Point), nullptr) == 0)
        ++frames_split;
    } else {
      for (std::size_t k = first; k < next; ++k) (void)frame_assembler.point(points.points[k].azimuth_deg);
    }
  }
}
#endif

void count(const char* sensor, const char* what, void (*f)()) {
  subject_error = Error::ok;
  const std::uint32_t n = instructions(f);
  check(subject_error == Error::ok, what);
  check(n != ~0u, "instruction count within the 24-bit counter");
  print("instructions: ");
  print(sensor);
  print(" ");
  print(what);
  print(" ");
  print_int(n);
  print("\n");
}

// The packet `p` of `n` bytes copied to `into` with its motor speed set to `rpm` (CRCs re-sealed).
ByteView with_rpm(Model m, const std::uint8_t* p, std::size_t n, std::uint16_t rpm, std::uint8_t* into) {
  std::memcpy(into, p, n);
  std::size_t at = 0;
  if (m == Model::pandar64) at = hesai::pandar64::kMotorSpeed;
  else if (m == Model::qt128c2x) at = hesai::qt128::Layout::from_header(p[hesai::qt128::kLaserNum], p[hesai::qt128::kFlags]).tail + hesai::qt128::kTailMotorSpeed;
  else if (m == Model::pandar_qt64) at = hesai::qt64::kTail + hesai::qt64::kTailMotorSpeed;
  else if (m == Model::pandar_xt16 || m == Model::pandar_xt32 || m == Model::pandar_xt32m2x)
    at = n - hesai::xt::kTailBytes + hesai::xt::kTailMotorSpeed;
  else at = hesai::pandar40::kMotorSpeed;
  hesai::store_le16(into + at, rpm);
  if (m == Model::qt128c2x) check(hesai::qt128::seal(into, n) == Error::ok, "re-seal");
  return {into, n};
}

// One real packet of each sensor (the Pandar40's: the Pandar40P packet with the Pandar40's tail).
struct Subject {
  const char* name;
  Model model;
  ByteView packet;
};
const Subject kSubjects[] = {{"Pandar40", Model::pandar40, {kPandar40P, 1256}},
                             {"Pandar40P", Model::pandar40p, {kPandar40P, sizeof kPandar40P}},
                             {"Pandar64", Model::pandar64, {kPandar64, sizeof kPandar64}},
                             {"QT128C2X", Model::qt128c2x, {kQt128, sizeof kQt128}},
                             {"PandarQT64", Model::pandar_qt64, {kQt64, sizeof kQt64}},
                             {"PandarXT16", Model::pandar_xt16, {kXt16, sizeof kXt16}},
                             {"PandarXT32", Model::pandar_xt32, {kXt32, sizeof kXt32}},
                             {"PandarXT32M2X", Model::pandar_xt32m2x, {kXt32m2x, sizeof kXt32m2x}}};
// decoders[1..3] are the Pandar40P, Pandar64 and QT128's own; every other model borrows decoders[0].
hesai::Decoder& decoder_for(Model m) {
  return m == Model::pandar40p ? decoders[1] : m == Model::pandar64 ? decoders[2] : m == Model::qt128c2x ? decoders[3] : guest(m);
}

// ---- Every decode path gives the same bits --------------------------------------------------------

// The columns' every member, as digest() folds a Point's.
std::uint32_t column_digest(std::size_t count) {
  std::uint32_t crc = hesai::kCrc32Mpeg2Init;
  auto add = [&crc](const void* data, std::size_t bytes) {
    crc = hesai::crc32_mpeg2_update(hesai::CrcPath::table, crc, {static_cast<const std::uint8_t*>(data), bytes});
  };
  add(columns.x, count * 4), add(columns.y, count * 4), add(columns.z, count * 4), add(columns.time_ns, count * 4);
  add(columns.intensity, count), add(columns.channel, count), add(columns.return_index, count);
  return crc;
}

// decode() by `path` into the cleared storage: the digest of what it wrote and how many.
struct PathResult {
  std::uint32_t points_digest, columns_digest;
  std::size_t points, columns;
};
PathResult decode_by(hesai::Decoder& decoder, ByteView bytes, hesai::DecodePath path) {
  PathResult r{};
  hesai::PacketInfo info;
  std::memset(&storage, 0xA5, sizeof storage);
  check(decoder.decode(bytes, info, points, path) == Error::ok, "decode by one path");
  r.points = points.count;
  r.points_digest = digest(points.points.data(), points.count);
  std::memset(&storage, 0x5A, sizeof storage);
  check(decoder.decode(bytes, info, columns, r.columns, path) == Error::ok, "columns by one path");
  r.columns_digest = column_digest(r.columns);
  return r;
}

void same_on_every_path(const char* name, hesai::Decoder& decoder, ByteView bytes) {
#if HESAI_KERNEL_COUNTERS && defined(__ARM_ARCH_7EM__) && defined(__ARM_FP)
  // The image whose core counts kernel calls (hesai_core_alt): DecodePath::best took the packet
  // through the assembly loops once as Points and once as columns, DecodePath::portable never.
  using hesai::detail::Kernel;
  hesai::detail::reset_kernel_calls();
  const PathResult best = decode_by(decoder, bytes, hesai::DecodePath::best);
  check(hesai::detail::kernel_calls(Kernel::armv7m_points) == 1 && hesai::detail::kernel_calls(Kernel::armv7m_columns) == 1,
        "DecodePath::best ran the ARMv7E-M loops (kernel counters)");
  hesai::detail::reset_kernel_calls();
  const PathResult portable = decode_by(decoder, bytes, hesai::DecodePath::portable);
  check(hesai::detail::kernel_calls(Kernel::armv7m_points) == 0 && hesai::detail::kernel_calls(Kernel::armv7m_columns) == 0,
        "DecodePath::portable ran the C loops (kernel counters)");
#else
  const PathResult best = decode_by(decoder, bytes, hesai::DecodePath::best);
  const PathResult portable = decode_by(decoder, bytes, hesai::DecodePath::portable);
#endif
  const bool same = best.points == portable.points && best.columns == portable.columns && best.points == best.columns &&
                    best.points_digest == portable.points_digest && best.columns_digest == portable.columns_digest;
  check(same, name);
}

// Where DecodePath::best is not the C loops (the Cortex-M4F and M7: the ARMv7E-M assembly). On
// the M0+ the comparisons below would be of the C loops with themselves, and would link
// Decoder::set_angles into the image whose flash report.py holds to 48 KiB.
#if defined(__ARM_ARCH_7EM__) && defined(__ARM_FP)
#define HESAI_FIRMWARE_TWO_PATHS 1
#else
#define HESAI_FIRMWARE_TWO_PATHS 0
#endif
#if HESAI_FIRMWARE_TWO_PATHS
// Where a model's block azimuths lie (as tests/packet_builder.h's block_layout): the first at
// `first`, then one every `stride` bytes. Pandar40/40P, Pandar64 and QT128C2X manuals Section
// 3.1.2; PandarQT64 protocol 3.1 and PandarXT protocol 6.1 (the SDK's layouts).
struct BlockLayout {
  std::size_t first, stride, blocks;
};
BlockLayout block_layout(Model m) {
  switch (m) {
    case Model::pandar64: return {8, 194, 6};
    case Model::qt128c2x: return {12, 514, 2};
    case Model::pandar_qt64: return {12, 258, 4};
    case Model::pandar_xt16: return {12, 66, 8};
    case Model::pandar_xt32: return {12, 130, 8};
    case Model::pandar_xt32m2x: return {12, 130, 6};
    default: return {2, 124, 10};  // Pandar40, Pandar40P
  }
}

// The packet copied into `shifted` with each block's azimuth a replaced by azimuth(a, f), f the
// block's firing: 0 for the first block, one more at each block whose azimuth differs from the
// block's before (the blocks of one firing, the returns, share an azimuth: validate() checks).
// The QT128's CRCs sealed again.
template <typename F>
ByteView with_azimuths(Model m, ByteView original, F azimuth) {
  std::memcpy(shifted, original.data, original.size);
  const BlockLayout l = block_layout(m);
  std::size_t firing = 0;
  for (std::size_t b = 0; b < l.blocks; ++b) {
    const std::uint8_t* was = original.data + l.first + b * l.stride;
    if (b > 0 && hesai::load_le16(was) != hesai::load_le16(was - l.stride)) ++firing;
    hesai::store_le16(shifted + l.first + b * l.stride, azimuth(hesai::load_le16(was), firing));
  }
  if (m == Model::qt128c2x) check(hesai::qt128::seal(shifted, original.size) == Error::ok, "re-seal");
  return {shifted, original.size};
}

// The model's decoder slot (decoder_for's), built afresh: design angles, clockwise.
hesai::Decoder& fresh_decoder(Model m) {
  hesai::Decoder* d = m == Model::pandar40p  ? &decoders[1]
                      : m == Model::pandar64 ? &decoders[2]
                      : m == Model::qt128c2x ? &decoders[3]
                                             : &decoders[0];
  d->~Decoder();
  return *::new (d) hesai::Decoder(m);
}

// The paths agree where the real packets do not go: a counter-clockwise unit (each block azimuth a
// sent as 36000 - a, the decoder set to Rotation::counterclockwise), a unit's angle file whose
// azimuth offsets span -359.5..+351.7 degrees (every beam azimuth wraps past 0 or 360 on some
// block) and whose elevations are not the design's, and firings' block azimuths across 0: 359.98,
// 359.99, 0, 0.01... clockwise, 0.02, 0.01, 0, 359.99... counter-clockwise. Each sensor, each
// combination.
void rotations_offsets_and_wraps() {
  print("decode paths: counter-clockwise, calibration offsets, block azimuths across 0, every sensor\n");
  for (const Subject& s : kSubjects) {
    for (const bool offsets : {false, true}) {
      for (const bool ccw : {false, true}) {
        hesai::Decoder& decoder = fresh_decoder(s.model);
        if (offsets) {
          hesai::AngleCorrection& a = storage.angles;
          a = hesai::AngleCorrection{};
          a.channels = static_cast<std::uint16_t>(hesai::channel_count(s.model));
          for (std::size_t ch = 0; ch < a.channels; ++ch) {
            a.azimuth_deg[ch] = -359.5 + 5.6 * static_cast<double>(ch % 128);
            a.elevation_deg[ch] = -25.0 + 0.375 * static_cast<double>(ch);
          }
          check(decoder.set_angles(a) == Error::ok, "set_angles: a unit's offsets");
        }
        decoder.set_rotation(ccw ? hesai::Rotation::counterclockwise : hesai::Rotation::clockwise);
        const char* what = offsets ? (ccw ? "counter-clockwise, with offsets" : "clockwise, with offsets")
                                   : (ccw ? "counter-clockwise" : "clockwise");
        print("  ");
        print(s.name);
        print(" ");
        print(what);
        print("\n");
        if (ccw) {
          same_on_every_path(s.name, decoder, with_azimuths(s.model, s.packet, [](std::uint16_t a, std::size_t) {
                               return static_cast<std::uint16_t>((36000u - a) % 36000u);
                             }));
        } else if (offsets) {
          same_on_every_path(s.name, decoder, s.packet);
        }
        same_on_every_path(s.name, decoder, with_azimuths(s.model, s.packet, [ccw](std::uint16_t, std::size_t firing) {
                             const auto step = static_cast<std::uint32_t>(firing);
                             return static_cast<std::uint16_t>(ccw ? (36002u - step) % 36000u : (35998u + step) % 36000u);
                           }));
      }
    }
  }
  // Every decoder as paths_agree() left it, for the counts below: design angles, clockwise.
  for (const Model m : {Model::pandar40p, Model::pandar64, Model::qt128c2x}) fresh_decoder(m);
}

// The unit scan (issue #43): on the M4F DecodePath::best folds it into the assembly loops (the
// _scan and _repeat loops, and the exact count in C of a packet that set Q), DecodePath::portable
// runs the reference scan_units after the C loops. The same UnitScan byte for byte (each filled
// with 0xA5 first: the reset too), and the same points with Returns::all and Returns::distinct.
void same_scan_on_every_path(const char* name, hesai::Decoder& decoder, ByteView bytes) {
  static hesai::UnitScan scans[2];
  std::uint32_t digests[2][2] = {};
  std::size_t counts[2][2] = {};
  const hesai::DecodePath paths[2] = {hesai::DecodePath::best, hesai::DecodePath::portable};
  for (std::size_t p = 0; p < 2; ++p) {
    for (std::size_t distinct = 0; distinct < 2; ++distinct) {
      hesai::PacketInfo info;
      std::memset(&storage, 0xA5, sizeof storage);
      std::memset(&scans[p], 0xA5, sizeof scans[p]);
      check(decoder.decode(bytes, info, points, scans[p], distinct != 0 ? hesai::Returns::distinct : hesai::Returns::all,
                           paths[p]) == Error::ok,
            name);
      digests[p][distinct] = digest(points.points.data(), points.count);
      counts[p][distinct] = points.count;
    }
  }
  check(std::memcmp(&scans[0], &scans[1], sizeof scans[0]) == 0 && digests[0][0] == digests[1][0] &&
            digests[0][1] == digests[1][1] && counts[0][0] == counts[1][0] && counts[0][1] == counts[1][1],
        name);
}

// xorshift32 (Marsaglia 2003): the same packets on every run.
std::uint32_t next_random(std::uint32_t& state) {
  state ^= state << 13;
  state ^= state >> 17;
  state ^= state << 5;
  return state;
}

// Every sensor's packet with its units rewritten at random, 40 packets each, on both paths: distances
// 0, 1 (the QT128's blockage marker), 2, at and about the rated ranges' limits (12 500 raw for
// the QT128's 50 m at 4 mm, 50 000 for the Pandars' 200 m; in odd rounds none beyond), 65 535 and
// any, and second returns
// that repeat their first return, or repeat only its distance or only its reflectivity. A QT128
// unit that is all zero (a resting channel: validate() checks) stays so; the CRCs are sealed again.
void scans_agree() {
  print("unit scan: assembly loops against scan_units, every sensor, real and 40 random packets each\n");
  for (const Subject& s : kSubjects) same_scan_on_every_path(s.name, decoder_for(s.model), s.packet);
  static const std::uint16_t kEdges[] = {12499, 12500, 12501, 49999, 50000, 50001, 65535};
  std::uint32_t state = 0x2545F491u;
  for (const Subject& s : kSubjects) {
    const BlockLayout l = block_layout(s.model);
    const std::size_t channels = hesai::channel_count(s.model);
    const std::size_t unit = (l.stride - 2) / channels;
    for (int round = 0; round < 40; ++round) {
      std::memcpy(shifted, s.packet.data, s.packet.size);
      for (std::size_t b = 0; b < l.blocks; ++b) {
        for (std::size_t j = 0; j < channels; ++j) {
          std::uint8_t* u = shifted + l.first + 2 + b * l.stride + j * unit;
          if (s.model == Model::qt128c2x && (u[0] | u[1] | u[2] | u[3]) == 0) continue;
          const std::uint8_t* first = u - l.stride;  // the first return's, for a second return
          const std::uint32_t r = next_random(state);
          std::uint32_t distance = hesai::load_le16(u);
          switch (r % 16) {
            case 0: distance = 0; break;
            case 1: distance = 1; break;
            case 2: distance = 2; break;
            // Odd rounds stay within every rated range (12 500 raw), so that no distance beyond it
            // hides a blockage marker the loops missed (both set Q: the packet counted in C).
            case 3: distance = round % 2 == 0 ? kEdges[(r >> 8) % 7] : kEdges[(r >> 8) % 2]; break;
            case 4: distance = round % 2 == 0 ? (r >> 8) & 0xFFFFu : (r >> 8) % 12501u; break;
            case 5: case 6: case 7: case 8:
              if (b % 2 == 1) distance = hesai::load_le16(first), u[2] = first[2];
              break;
            case 9:
              if (b % 2 == 1) distance = hesai::load_le16(first), u[2] = static_cast<std::uint8_t>(first[2] + 1);
              break;
            case 10:
              if (b % 2 == 1) u[2] = first[2];
              break;
            default: break;
          }
          hesai::store_le16(u, static_cast<std::uint16_t>(distance));
        }
      }
      if (s.model == Model::qt128c2x) check(hesai::qt128::seal(shifted, s.packet.size) == Error::ok, "re-seal");
      same_scan_on_every_path(s.name, decoder_for(s.model), {shifted, s.packet.size});
    }
  }
}
#endif  // HESAI_FIRMWARE_TWO_PATHS

// On the Cortex-M4F (and M7) DecodePath::best runs the assembly loops of kernels/armv7m_loops.h,
// DecodePath::portable the C loops: every point of every packet, Points and columns, bit for bit
// (on the M0+ both are the C loops). Also a QT128 packet with confidence bytes and distances at
// and below its smallest kept distance (2), resealed, and each packet at another spin rate.
void paths_agree() {
  print("decode paths: ");
  print(hesai::decode_simd_name());
  print(" against portable, every sensor\n");
#if defined(__ARM_ARCH_7EM__) && defined(__ARM_FP)
  // Else the comparison below would be of the C loops with themselves.
  check(std::strcmp(hesai::decode_simd_name(), "armv7m") == 0 && !hesai::decode_simd_available(),
        "DecodePath::best runs the ARMv7E-M assembly loops");
#endif
  for (const Subject& s : kSubjects) {
    hesai::Decoder& decoder = decoder_for(s.model);
    same_on_every_path(s.name, decoder, s.packet);
    hesai::PacketInfo info;
    check(decoder.validate(s.packet, info) == Error::ok, s.name);
    same_on_every_path(s.name, decoder,
                       with_rpm(s.model, s.packet.data, s.packet.size, static_cast<std::uint16_t>(info.motor_rpm + 7), shifted));
  }
  using namespace hesai::qt128;
  std::memcpy(shifted, kQt128, sizeof kQt128);
  const Layout l = Layout::from_header(kQt128[kLaserNum], kQt128[kFlags]);
  check(l.unit == 4 && l.lasers == 128, "QT128 packet with confidence bytes");
  for (std::size_t u = 0; u < kBlocks * 128; ++u) {
    std::uint8_t* q = shifted + kBody + (u / 128) * l.block + kBlockPoints + (u % 128) * l.unit;
    if ((q[0] | q[1]) == 0) continue;  // a resting channel's unit stays all zero (validate() checks)
    q[3] = static_cast<std::uint8_t>(u * 37 + 1);  // confidence
    if (u % 5 == 0) q[0] = static_cast<std::uint8_t>(u % 3), q[1] = 0;  // distances 0, 1 and 2
  }
  check(hesai::qt128::seal(shifted, sizeof kQt128) == Error::ok, "QT128 resealed");
  same_on_every_path("QT128C2X with confidence and short distances", decoders[3], {shifted, sizeof kQt128});
}

void instruction_counts() {
  const bool exact = span_of(one_nop) - span_of(nothing) == 1 && span_of(thousand_nops) - span_of(nothing) == 1000;
  if (!exact) {
    print("instructions per packet: not counted (run under qemu-system-arm -icount shift=7; report.py does)\n");
    return;
  }
  print("instructions per packet (qemu -icount shift=7 and SysTick, checked on 1 and 1000 nops):\n");
  static hesai::PacketInfo info;
  for (const Subject& s : kSubjects) {
    subject = &decoder_for(s.model);
    packet = s.packet;
    check(subject->decode(packet, info, points) == Error::ok, s.name);  // the spin-rate cache warm
    count(s.name, "validate", [] { subject_error = subject->validate(packet, subject_info); });
    count(s.name, "decode", [] { subject_error = subject->decode(packet, subject_info, points); });
    count(s.name, "decode_columns",
          [] { subject_error = subject->decode(packet, subject_info, columns, column_count); });
    // Stream health: the decode with the unit scan, then the monitor's work on the packet that
    // follows in order (HealthMonitor::observe and observe_units).
    count(s.name, "decode_scan", [] { subject_error = subject->decode(packet, subject_info, points, subject_scan); });
    health_monitor.reset();
    (void)health_monitor.observe(subject_info);
    next_info = subject_info;
    {
      const std::uint32_t firings = hesai::model_facts::of(subject_info.model).firings;
      const std::uint32_t per = static_cast<std::uint32_t>(subject_info.blocks) /
                                (subject_info.returns != 0 ? static_cast<std::uint32_t>(subject_info.returns) : 1u);
      next_info.time_ns += static_cast<std::int64_t>(per) * 100000000 / firings;
      next_info.block_azimuth[0] =
          static_cast<std::uint16_t>((subject_info.block_azimuth[0] + per * 60u * subject_info.motor_rpm / firings) % 36000u);
    }
    count(s.name, "health", [] {
      (void)health_monitor.observe(next_info);
      health_monitor.observe_units(subject_scan);
    });
    check(health_monitor.counts().lost == 0 && health_monitor.counts().time_stalls == 0, "health: the next packet in order");
#if HESAI_FIRMWARE_FRAMES
    // Frames: the packet turned half a turn, so that no point lies across 0 from its block (the
    // Pandar64's, at 4.92 degrees, has points below 0, given as 355 and more, which points() leaves
    // to point()); every point into the one open frame.
    check(subject->decode(with_azimuths(s.model, s.packet,
                                        [](std::uint16_t a, std::size_t) {
                                          return static_cast<std::uint16_t>((a + 18000u) % 36000u);
                                        }),
                          frames_info, points) == Error::ok,
          "frames: the packet half a turn on");
    for (const bool by_block : {false, true}) {
      prime_frames();
      count(s.name, by_block ? "frames" : "frames_per_point", by_block ? assign_frames<true> : assign_frames<false>);
      check(frame_assembler.current().points == points.count && frames_split == 0 &&
                frame_assembler.current().late_points == 0,
            "frames: every point of the packet in the open frame");
    }
#endif
    // The worst case: a packet at another spin rate, so the decode rebuilds the cache first.
    packet = with_rpm(subject->model(), s.packet.data, s.packet.size, static_cast<std::uint16_t>(info.motor_rpm + 2), shifted);
    count(s.name, "decode_rpm_change", [] { subject_error = subject->decode(packet, subject_info, points); });
  }
#if HESAI_SIGNATURE
  // The QT128 signature check: validate() of the packet signed under a session key.
  std::uint8_t key[32];
  for (std::size_t i = 0; i < 32; ++i) key[i] = static_cast<std::uint8_t>(i * 7 + 1);
  std::memcpy(shifted, kQt128, sizeof kQt128);
  const std::size_t at = hesai::qt128::Layout::from_header(kQt128[hesai::qt128::kLaserNum], kQt128[hesai::qt128::kFlags]).signature;
  hesai::hmac_sha256({key, 32}, {shifted, at}, shifted + at);
  subject = &decoders[3];
  packet = {shifted, sizeof kQt128};
  check(subject->set_session_key(key) == Error::ok, "QT128 session key");
  count("QT128C2X", "validate_signed", [] {
    subject_error = subject->validate(packet, subject_info);
    if (subject_error == Error::ok && subject_info.signature != hesai::SignatureStatus::valid) subject_error = Error::signature_invalid;
  });
  subject->clear_session_key();
#endif
}

}  // namespace

int main() {
  print("hesai firmware test: " HESAI_FIRMWARE_TARGET "\n");
  print("configuration: HESAI_CRC_SLICING ");
  print_int(HESAI_CRC_SLICING);
  print(", HESAI_SIGNATURE ");
  print_int(HESAI_SIGNATURE);
  print("\n");
  alignment_trap_armed();
#if defined(__ARM_ARCH_6M__)
  print("alignment trap armed: an unaligned load faults; every packet below is decoded at offsets 0..3\n");
#endif
  known_answers();
  real_packets();
  c_path();
  paths_agree();
#if HESAI_FIRMWARE_TWO_PATHS
  rotations_offsets_and_wraps();
  scans_agree();
#endif
  instruction_counts();
  stack_use();
  print("sizeof(Decoder): ");
  print_int(static_cast<std::int64_t>(sizeof(hesai::Decoder)));
  print(" bytes (budget 8192)\n");
  if (failures == 0) print("all checks passed\n");
  return failures == 0 ? 0 : 1;
}
