// The registry of sensors: one line per sensor file, in the order identify() asks them (their
// headers do not overlap, so the order changes no answer; the GPS check comes first in
// identify()). See sensor.h for what a descriptor holds.
#include "sensor.h"

namespace hesai {

extern const SensorDescriptor kPandar40Sensor;  // pandar40.cpp: Pandar40, Pandar40P
extern const SensorDescriptor kPandar64Sensor;  // pandar64.cpp
extern const SensorDescriptor kQt128Sensor;     // qt128.cpp: QT128C2X
extern const SensorDescriptor kQt64Sensor;      // qt64.cpp: PandarQT64
extern const SensorDescriptor kXtSensor;        // xt.cpp: PandarXT16, XT32, XT32M2X

namespace {
constexpr const SensorDescriptor* kSensors[] = {&kPandar40Sensor, &kPandar64Sensor, &kQt128Sensor, &kQt64Sensor,
                                                &kXtSensor};
}  // namespace

const SensorDescriptor* sensor_of(Model model) noexcept {
  for (const SensorDescriptor* s : kSensors)
    for (std::size_t i = 0; i < s->model_count; ++i)
      if (s->models[i] == model) return s;
  return nullptr;
}

const SensorDescriptor* sensor_claiming(ByteView p) noexcept {
  for (const SensorDescriptor* s : kSensors)
    if (s->claims(p)) return s;
  return nullptr;
}

Error write_udp_sequence(std::uint8_t* payload, std::size_t size, std::uint32_t sequence) noexcept {
  const ByteView p{payload, size};
  Model model = Model::unknown;
  PacketKind kind = PacketKind::point_cloud;
  if (const Error e = identify(p, model, kind); e != Error::ok) return e;
  const SensorDescriptor* s = kind == PacketKind::point_cloud ? sensor_of(model) : nullptr;
  const std::size_t at = s != nullptr ? s->sequence_at(p) : 0;
  if (at == 0) return Error::unsupported_section;
  store_le32(payload + at, sequence);
  return s->seal != nullptr ? s->seal(payload, size) : Error::ok;
}

}  // namespace hesai
