/* The sensor models, listed once for C++ and C: model.h makes hesai::Model and its name, channel
 * and block counts of this list, hesai.h the C enum hesai_model (HESAI_MODEL_<id>). Values count
 * from 1 in the order below; 0 is `unknown`. A new sensor adds a line at the end (every earlier
 * model keeps its value), its file in core/src/sensors/ and its tests (docs/DESIGN.md).
 *
 * A C header as well as a C++ one: only the preprocessor, no includes. */
#ifndef HESAI_MODEL_LIST_H
#define HESAI_MODEL_LIST_H

/* X(id, display name, laser channels, blocks per packet, firings per rotation at 600 rpm, PTC
 * product number), once per model in value order.
 * - Firings per rotation: 360 degrees over the azimuth step at 10 Hz: 0.2 degrees (Pandar40 and
 *   Pandar64 manuals, "Horizontal resolution"), 0.4 (QT128C2X manual, "Resolution (Horizontal)");
 *   0.6 (PandarQT64) and 0.18 (XT family) as the bundled captures' block azimuths step.
 * - PTC product number: the model byte of the PTC inventory (PTC 0x07; tier4/nebula
 *   hesai_hw_interface.cpp nebula_model_to_hesai_model_no); 255 for the Pandar40, which has no PTC. */
#define HESAI_MODEL_LIST(X)                                                                                        \
  X(pandar40, "Pandar40", 40, 10, 1800, 255)        /* older firmware: 1256-byte packets, 16-byte tail, no date */ \
  X(pandar40p, "Pandar40P", 40, 10, 1800, 0)        /* 1262 bytes, 1266 with UDP sequence */                       \
  X(pandar64, "Pandar64", 64, 6, 1800, 2)           /* 1194 bytes, 1198 with UDP sequence */                       \
  X(qt128c2x, "QT128C2X", 128, 2, 900, 32)          /* point cloud protocol 3.2, up to 1127 bytes */               \
  X(pandar_qt64, "PandarQT64", 64, 4, 600, 15)      /* point cloud protocol 3.1 */                                 \
  X(pandar_xt16, "PandarXT16", 16, 8, 2000, 26)     /* point cloud protocol 6.1 */                                 \
  X(pandar_xt32, "PandarXT32", 32, 8, 2000, 25)     /* point cloud protocol 6.1 */                                 \
  X(pandar_xt32m2x, "PandarXT32M2X", 32, 6, 2000, 38) /* point cloud protocol 6.1 */

/* X(id, spin rates, spin rate over HTTP, FOV over PTC, return-mode codes, status temperatures):
 * what PTC may set on each model and how its answers read, once per model in value order (the
 * core's ptc/ asks this list; no other file names the models for it). The sources are cited in
 * hesai/ptc_settings.h and hesai/ptc.h.
 * - Spin rates: a bit per rate, 1 = 300 rpm, 2 = 600 rpm, 4 = 1200 rpm.
 * - Spin rate over HTTP: 1 where nebula sets it over the unit's HTTP API, not PTC 0x17.
 * - FOV over PTC: 1 where the unit takes a FOV (0x22).
 * - Return-mode codes: one character per PTC code from 0, the index of its name in
 *   "last", "strongest", "last_strongest", "first", "last_first", "first_strongest"; '-' for a
 *   code the model does not list.
 * - Status temperatures: how many the status (0x09) holds. */
#define HESAI_MODEL_PTC_LIST(X)                  \
  X(pandar40, 2 | 4, 1, 0, "012", 8)             \
  X(pandar40p, 2 | 4, 1, 1, "012", 8)            \
  X(pandar64, 2 | 4, 1, 0, "012", 8)             \
  X(qt128c2x, 2 | 4, 0, 1, "012345", 9)          \
  X(pandar_qt64, 1 | 2 | 4, 1, 1, "0-43", 8)     \
  X(pandar_xt16, 1 | 2 | 4, 0, 1, "012345", 8)   \
  X(pandar_xt32, 1 | 2 | 4, 0, 1, "012345", 8)   \
  X(pandar_xt32m2x, 1 | 2 | 4, 0, 1, "012345", 8)

#endif /* HESAI_MODEL_LIST_H */
