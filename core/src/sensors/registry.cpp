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

/// Whether a payload of at least 4 bytes starts with the sensor's header.
bool has_header(const SensorDescriptor& s, ByteView p) noexcept {
  // The first four bytes as one word, the ones not compared masked off (one load and compare a
  // sensor, where a byte loop took several times as many instructions per packet on Cortex-M).
  const std::uint32_t mask = s.header_bytes >= 4 ? 0xFFFFFFFFu : (1u << (8 * s.header_bytes)) - 1;
  return ((load_le32(p.data) ^ load_le32(s.header)) & mask) == 0;
}

// One line per sensor file: its descriptor and the models it decodes.
struct Entry {
  const SensorDescriptor* sensor;
  Model models[3];  // Model::unknown after the last
};
constexpr Entry kSensors[] = {
    {&kPandar40Sensor, {Model::pandar40, Model::pandar40p}},
    {&kPandar64Sensor, {Model::pandar64}},
    {&kQt128Sensor, {Model::qt128c2x}},
    {&kQt64Sensor, {Model::pandar_qt64}},
    {&kXtSensor, {Model::pandar_xt16, Model::pandar_xt32, Model::pandar_xt32m2x}},
};

// The same by model, for a lookup in one step; every model of model_list.h has exactly one sensor.
struct ByModel {
  const SensorDescriptor* sensor[kModelCount] = {};
  std::size_t claimed[kModelCount] = {};
};
constexpr ByModel by_model() {
  ByModel t;
  for (const Entry& e : kSensors)
    for (const Model m : e.models)
      if (m != Model::unknown) {
        t.sensor[static_cast<std::size_t>(m)] = e.sensor;
        ++t.claimed[static_cast<std::size_t>(m)];
      }
  return t;
}
constexpr ByModel kByModel = by_model();
constexpr bool every_model_has_one_sensor() {
  for (std::size_t m = 1; m < kModelCount; ++m)
    if (kByModel.claimed[m] != 1) return false;
  return kByModel.claimed[0] == 0;
}
static_assert(every_model_has_one_sensor(), "registry.cpp: every model of model_list.h needs one line's sensor");

}  // namespace

const SensorDescriptor* sensor_of(Model model) noexcept {
  const auto i = static_cast<std::size_t>(model);
  return i < kModelCount ? kByModel.sensor[i] : nullptr;
}

const SensorDescriptor* sensor_claiming(ByteView p) noexcept {
  for (const Entry& e : kSensors)
    if (has_header(*e.sensor, p)) return e.sensor;
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
