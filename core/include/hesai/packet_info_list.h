/* The members of the C interface's packet-level structs, listed once: hesai.h declares
 * hesai_date_time, hesai_functional_safety and hesai_packet_info from these lists, capi/hesai_c.cpp
 * copies each member from the hesai::PacketInfo member of the same name (converted to the C type:
 * enums and bools to their values) and checks its offset, and the C interface's test compares
 * each. A member added here is declared, copied and compared; none can be left out of one of them.
 *
 * FIELD(type, name): a member; ARRAY(type, name, count): an array member; NESTED(type, name,
 * list): a struct member whose own members are `list`. In declaration order.
 *
 * A C header as well as a C++ one: only the preprocessor, no includes. */
#ifndef HESAI_PACKET_INFO_LIST_H
#define HESAI_PACKET_INFO_LIST_H

/* hesai_date_time: a tail's date-time, UTC (hesai::DateTime). */
#define HESAI_DATE_TIME_LIST(FIELD)                                             \
  FIELD(int32_t, year)   /* full year, e.g. 2024 */                             \
  FIELD(uint8_t, month)  /* 1..12 */                                            \
  FIELD(uint8_t, day)    /* 1..days in month */                                 \
  FIELD(uint8_t, hour)   /* 0..23 */                                            \
  FIELD(uint8_t, minute) /* 0..59 */                                            \
  FIELD(uint8_t, second) /* 0..59 */

/* hesai_functional_safety: the QT128 functional-safety section, header flags bit 2
 * (hesai::FunctionalSafety). */
#define HESAI_FUNCTIONAL_SAFETY_LIST(FIELD)                                                        \
  FIELD(uint8_t, present)           /* 1 when the packet has the section */                        \
  FIELD(uint8_t, version)           /* FS version (0x01) */                                        \
  FIELD(uint8_t, lidar_state)       /* 0 init, 1 normal, 2 report fault, 3 pre-degradation, */     \
                                    /* 4 degradation, 5 pre-shutdown, 6 shutdown, 7 standby */     \
  FIELD(uint8_t, fault_code_type)   /* 1 current fault, 2 past fault */                            \
  FIELD(uint8_t, rolling_counter)   /* 0..7 */                                                     \
  FIELD(uint8_t, total_fault_codes) /* 0..15 */                                                    \
  FIELD(uint8_t, fault_code_id)     /* 0..15 */                                                    \
  FIELD(uint16_t, fault_code)       /* outgoing fault code */

/* hesai_packet_info: packet-level fields, filled by validate and decode (hesai::PacketInfo). */
#define HESAI_PACKET_INFO_LIST(FIELD, ARRAY, NESTED)                                                          \
  FIELD(int64_t, time_ns)                     /* packet time t0 = date-time + timestamp, ns */                \
  NESTED(hesai_date_time, date_time, HESAI_DATE_TIME_LIST) /* the tail's date-time (Pandar40: from the */    \
                                                           /* last GPS packet) */                             \
  FIELD(uint32_t, timestamp_us)               /* the tail's timestamp field as sent */                        \
  FIELD(uint32_t, sequence)                   /* UDP sequence, when has_sequence */                           \
  FIELD(uint16_t, motor_rpm)                  /* spin rate as sent */                                         \
  ARRAY(uint16_t, block_azimuth, 10)          /* per block, 0.01 degree */                                    \
  FIELD(uint8_t, model)                       /* a hesai_model */                                             \
  FIELD(uint8_t, return_mode)                 /* the return-mode byte (0x37 strongest, 0x38 last, ...) */     \
  FIELD(uint8_t, returns)                     /* 1 single return, 2 dual return, 3 triple return */           \
  FIELD(uint8_t, blocks)                      /* blocks in the packet */                                      \
  FIELD(uint8_t, dis_unit_mm)                 /* distance step, mm */                                         \
  FIELD(uint8_t, time_reference)              /* HESAI_TIME_utc or HESAI_TIME_hour_relative */                \
  FIELD(uint8_t, has_sequence)                /* 1 when the packet carries a UDP sequence */                  \
  FIELD(uint8_t, high_temperature)            /* Pandar40/40P/64 shutdown flag */                             \
  FIELD(uint8_t, factory_info)                /* factory byte as sent */                                      \
  FIELD(uint8_t, flags)                       /* QT128 header flags */                                        \
  FIELD(uint8_t, mode_flag)                   /* QT128 tail mode flag */                                      \
  FIELD(uint8_t, signature)                   /* a HESAI_SIGNATURE_ value */                                  \
  NESTED(hesai_functional_safety, safety, HESAI_FUNCTIONAL_SAFETY_LIST) /* QT128 only */

#endif
