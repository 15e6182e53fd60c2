// One real packet of each model (fuzz/seed_packets.inc, written by make_corpus.py), for harnesses
// that apply a parsed calibration file and then decode a real packet.
#pragma once

#include "hesai/bytes.h"
#include "hesai/model.h"
#include "seed_packets.inc"

namespace hesai_fuzz {

/// A real packet of `model` (the Pandar40P one for the 40-channel models and any other).
inline hesai::ByteView seed_packet(hesai::Model model) {
  switch (model) {
    case hesai::Model::pandar64: return {kPandar64, sizeof kPandar64};
    case hesai::Model::qt128c2x: return {kQt128, sizeof kQt128};
    case hesai::Model::pandar_qt64: return {kQt64, sizeof kQt64};
    case hesai::Model::pandar_xt16: return {kXt16, sizeof kXt16};
    case hesai::Model::pandar_xt32: return {kXt32, sizeof kXt32};
    case hesai::Model::pandar_xt32m2x: return {kXt32m2x, sizeof kXt32m2x};
    default: return {kPandar40P, sizeof kPandar40P};
  }
}

}  // namespace hesai_fuzz
