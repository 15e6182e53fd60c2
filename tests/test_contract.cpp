// The memory figures the headers state (decoder.h "Memory", and each header's contract), held to
// the types by static_assert: changing a type's size fails the build until its documentation is
// updated. Checked on every CI target (x86-64, aarch64, armhf, s390x); the firmware image checks
// sizeof(Decoder) on Cortex-M.
#include <gtest/gtest.h>

#include "hesai/calibration.h"
#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/frame.h"
#include "hesai/gps.h"
#include "hesai/hmac.h"
#include "hesai/safety.h"
#include "hesai/sequence.h"
#include "hesai/sha256.h"

namespace {

using namespace hesai;

static_assert(sizeof(Decoder) == (HESAI_SIGNATURE ? 7208 : 6980), "decoder.h: Memory");
static_assert(sizeof(PacketPoints) == 16008 && sizeof(Point) == 40, "decoder.h: Memory");
static_assert(sizeof(PacketColumns<256>) == 19 * 256 + sizeof(std::size_t) && sizeof(PacketColumns<400>) == 19 * 400 + sizeof(std::size_t), "point.h: PacketColumns");
static_assert(sizeof(PacketInfo) == 88, "decoder.h: Memory");
static_assert(sizeof(AngleCorrection) == 2056 && sizeof(FiretimeCorrection) == 2312, "decoder.h, calibration.h");
static_assert(sizeof(ChannelConfig) == 326, "calibration.h: Contract");
static_assert(sizeof(HmacSha256Key) == 224 && sizeof(HmacSha256) == 120, "hmac.h: Contract");
static_assert(sizeof(Sha256) == 112, "sha256.h: Contract");
static_assert(sizeof(Crc32Mpeg2) == 4, "crc32.h: Contract");
static_assert(sizeof(FrameAssembler) == 400, "frame.h: Contract");
static_assert(sizeof(SequenceTracker) == 576, "sequence.h: Contract");
static_assert(sizeof(GpsPacket) == 112, "gps.h");
static_assert(sizeof(SafetyMonitor) == 136, "safety.h: Cost");

// The per-packet bound of decoder.h: every sensor's blocks x channels fit kMaxPointsPerPacket.
static_assert(kMaxPointsPerPacket == 400 && kMaxChannels == 128, "decoder.h: Worst-case cost");

TEST(Contract, DocumentedSizesHold) {
  // The static_asserts above are the test; this records the sizes in the test log.
  RecordProperty("sizeof_Decoder", static_cast<int>(sizeof(Decoder)));
  EXPECT_LE(sizeof(Decoder), 8u * 1024u);
}

}  // namespace
