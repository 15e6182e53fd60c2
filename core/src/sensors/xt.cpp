// PandarXT16, XT32 and XT32M2X (point cloud protocol 6.1): identification, validation and the
// walk over their blocks.
// TODO(#15): not implemented yet; every 6.1 packet is unsupported_version, as before.
#include "hesai/decoder.h"
#include "block_points.h"
#include "sensor_rules.h"

namespace hesai {

Error detail::identify_xt(ByteView, Model&) noexcept { return Error::unsupported_version; }

Error Decoder::validate_xt(ByteView, PacketInfo&) noexcept { return Error::unsupported_version; }

void Decoder::decode_xt(const std::uint8_t*, const PacketInfo&, Output&) const noexcept {}

}  // namespace hesai
