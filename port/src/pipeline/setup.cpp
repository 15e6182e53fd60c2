// The engine's set-up: the calibration files (--calibration, --firetimes, --channel-config, or
// those a sensor gave), parsed when the first packet of a model shows their channel count, and
// each new source's decoder configured as the options say (pipeline.h, Pipeline::load_files,
// use_downloaded, configure_decoder).
#include <string>

#include "hesai/calibration.h"
#include "hesai_port/base/files.h"
#include "hesai_port/pipeline/pipeline.h"

namespace hesai::port {

namespace {
ByteView text_view(const std::string& s) { return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}; }

// "FILE: line N: error_name (why)": the line when the parser gave one, the reason when there is one.
std::string calibration_error(const std::string& path, std::uint32_t line, Error e, const std::string& why = "") {
  return path + ": " + (line != 0 ? "line " + std::to_string(line) + ": " : "") + error_name(e) +
         (why.empty() ? "" : " (" + why + ")");
}
}  // namespace

Status Pipeline::load_files() {
  if (!options_.calibration_path.empty())
    if (Status s = read_text_file(options_.calibration_path, angles_text_); !s.ok()) return s;
  if (!options_.firetimes_path.empty())
    if (Status s = read_text_file(options_.firetimes_path, firetimes_text_); !s.ok()) return s;
  if (!options_.channel_config_path.empty()) {
    std::string text;
    if (Status s = read_text_file(options_.channel_config_path, text); !s.ok()) return s;
    return parse_channel_config(text);
  }
  return {};
}

Status Pipeline::parse_channel_config(const std::string& text) {
  channel_config_ = std::make_unique<ChannelConfig>();
  const ParseResult r = parse_channel_config_csv(text_view(text), *channel_config_);
  if (r.error != Error::ok) return Status::usage(calibration_error(options_.channel_config_path, r.line, r.error));
  return {};
}

Status Pipeline::use_downloaded(const std::string& origin, const std::string& angles, const std::string& firetimes,
                                const std::string& channel_config) {
  if (options_.calibration_path.empty() && !angles.empty()) {
    angles_text_ = angles;
    options_.calibration_path = "the calibration from " + origin;
  }
  if (options_.firetimes_path.empty() && !firetimes.empty()) {
    firetimes_text_ = firetimes;
    options_.firetimes_path = "the firing times from " + origin;
  }
  if (options_.channel_config_path.empty() && !channel_config.empty()) {
    options_.channel_config_path = "the channel configuration from " + origin;
    return parse_channel_config(channel_config);
  }
  return {};
}

bool Pipeline::configure_decoder(Decoder& d) {
  const Model model = d.model();
  const std::size_t channels = channel_count(model);
  const std::string fits = "the capture holds " + std::string(model_name(model)) + " packets, " +
                           std::to_string(channels) + " channels";
  if (!angles_text_.empty()) {
    AngleCorrection a;
    const ParseResult r = parse_angle_csv(text_view(angles_text_), channels, a);
    const Error e = r.error != Error::ok ? r.error : d.set_angles(a);
    if (e != Error::ok) {
      error_ = calibration_error(options_.calibration_path, r.line, e,
                                 e == Error::invalid_argument
                                     ? "an elevation outside [-90, 90] degrees or an azimuth offset outside [-360, 360] degrees"
                                     : fits);
      return false;
    }
  }
  if (!firetimes_text_.empty()) {
    FiretimeCorrection f;
    const ParseResult r = parse_firetime_csv(text_view(firetimes_text_), channels, f);
    const Error e = r.error != Error::ok ? r.error : d.set_firetimes(f);
    if (e != Error::ok) {
      error_ = calibration_error(options_.firetimes_path, r.line, e,
                                 e == Error::invalid_argument ? "a firing time outside [-1000, 1000] us" : fits);
      return false;
    }
  }
  if (channel_config_) {
    const Error e = d.set_channel_config(*channel_config_);
    if (e != Error::ok) {
      error_ = calibration_error(options_.channel_config_path, 0, e,
                                 model == Model::qt128c2x ? "BlockNum must be the QT128C2X's 2"
                                                          : "a QT128C2X channel configuration; " + fits);
      return false;
    }
  }
  if (d.set_reflectivity(options_.reflectivity) != Error::ok) {
    error_ = std::string("--reflectivity nonlinear: only the Pandar64 manual gives that mapping (the capture holds ") +
             model_name(model) + " packets)";
    return false;
  }
  d.set_firetime_correction(options_.firetime_azimuth);
  if (options_.has_key) {
    if (const Error e = d.set_session_key(options_.session_key.data()); e != Error::ok) {
      error_ = std::string("--session-key: ") + error_name(e);
      return false;
    }
  }
  d.set_allow_unsigned(options_.allow_unsigned);
  if (have_gps_) d.update_gps(last_gps_);
  d.set_rotation(options_.rotation);
  return true;
}

}  // namespace hesai::port
