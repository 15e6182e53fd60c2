// PandarQT64 (point cloud protocol 3.1): identification, validation and the walk over its blocks.
// TODO(#15): not implemented yet; every 3.1 packet is unsupported_version, as before.
#include "hesai/decoder.h"
#include "block_points.h"
#include "sensor_rules.h"

namespace hesai {

Error detail::identify_qt64(ByteView, Model&) noexcept { return Error::unsupported_version; }

Error Decoder::validate_qt64(ByteView, PacketInfo&) noexcept { return Error::unsupported_version; }

void Decoder::decode_qt64(const std::uint8_t*, const PacketInfo&, Output&) const noexcept {}

}  // namespace hesai
