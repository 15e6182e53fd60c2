/* The core's error codes, listed once for C++ and C: error.h makes hesai::Error of this list,
 * hesai.h the C enum hesai_error (HESAI_ERROR_<name>), and error.cpp the names. Values count from
 * 0 in the order below; the name is the stable string error_name() gives for logs and JSON. Add a
 * code by adding a line: C++, C and the names follow.
 *
 * A C header as well as a C++ one: only the preprocessor, no includes. */
#ifndef HESAI_ERROR_LIST_H
#define HESAI_ERROR_LIST_H

/* X(name) once per code, in value order. */
#define HESAI_ERROR_LIST(X)                                                                                    \
  X(ok)                       /* success */                                                                    \
  /* Byte reading. */                                                                                          \
  X(truncated)                /* a read would pass the end of the input */                                     \
  /* Packet recognition. */                                                                                    \
  X(bad_length)               /* the length fits no supported layout */                                        \
  X(bad_magic)                /* start bytes or block preamble are not the manual's */                         \
  X(unsupported_version)      /* a Hesai header with a protocol version we do not implement */                 \
  X(unsupported_model)        /* a Hesai header whose laser/block counts match no supported sensor */          \
                              /* (QT128: a laser num other than 128 without channel customisation) */          \
  X(unsupported_section)      /* a section whose layout the manual does not give (QT128 IMU) */                \
  X(flags_length_mismatch)    /* header flags announce sections that do not add up to the length */            \
  X(bad_header)               /* a header field out of its documented range (distance unit 0, return count) */ \
                              /* (and a customised QT128 laser num of 0 or above 128) */                       \
  /* Field validation. */                                                                                      \
  X(bad_azimuth)              /* block azimuth >= 360.00 degrees */                                            \
  X(bad_return_mode)          /* return-mode byte not listed in the manual */                                  \
  X(bad_date_time)            /* tail date-time outside the calendar */                                        \
  X(bad_timestamp)            /* microsecond field beyond its manual's range (999 999; QT128 1 000 000) */     \
  X(bad_motor_speed)          /* motor speed above 1500 rpm (the sensors spin at 600 or 1200) */               \
  X(dual_block_mismatch)      /* the two blocks of one dual-return firing disagree in azimuth */               \
  /* Integrity. */                                                                                             \
  X(crc_body)                 /* QT128 CRC1 (body) does not match */                                           \
  X(crc_functional_safety)    /* QT128 CRC2 (functional safety) does not match */                              \
  X(crc_tail)                 /* QT128 CRC3 (tail) does not match */                                           \
  X(signature_missing)        /* a key is configured but the packet carries no signature */                    \
  X(signature_invalid)        /* the HMAC-SHA256 signature does not match */                                   \
  /* Decoder use. */                                                                                           \
  X(model_mismatch)           /* the packet is of another model than the decoder's calibration */              \
  X(invalid_argument)         /* a parameter outside its documented range */                                   \
  X(buffer_too_small)         /* the caller's point storage holds fewer than max_points(model) */              \
  X(unsupported_feature)      /* the feature is configured out of this build (config.h: HESAI_SIGNATURE 0) */  \
  X(channel_config_required)  /* QT128 customised channels (flags bit 6) and no channel configuration set */   \
  X(channel_config_mismatch)  /* the channel configuration's LaserNum or BlockNum is not the packet's */       \
  /* GPS packets. */                                                                                           \
  X(bad_gps_field)            /* a GPS date/time digit or status byte outside its range */                     \
  /* Calibration files. */                                                                                     \
  X(calib_bad_header)         /* the header row is not one the manuals give */                                 \
  X(calib_bad_row)            /* a row has the wrong number of fields */                                       \
  X(calib_bad_number)         /* a field is not a decimal number */                                            \
  X(calib_bad_channel)        /* a channel number outside 1..N, or repeated */                                 \
  X(calib_channel_count)      /* the file has another number of channels than the model */                     \
  /* PTC (Pandar TCP Commands) responses. */                                                                   \
  X(ptc_bad_magic)            /* a response header that does not start with 47 74 */                           \
  X(ptc_command_mismatch)     /* the response echoes another command than the request's */                     \
  X(ptc_length_exceeds_bound) /* the announced payload length is above the caller's bound for the command */   \
  X(ptc_sensor_error)         /* the sensor answered with a non-zero return code */                            \
  X(ptc_payload_length)       /* a payload shorter than its command's layout, or not the size it fixes */      \
  /* Field validation, added after the rest: every code keeps its value. */                                    \
  X(resting_channel_data)     /* QT128: a channel that rests in its block's firing sequence has non-zero */    \
                              /* bytes (manual 3.1.2: a resting channel's four bytes are 0) */

#endif /* HESAI_ERROR_LIST_H */
