// The engine: datagrams in (from a capture or a socket), decoded and accounted, points and frames
// out to a sink. The hesai program's commands (port/src/cli/) and the C library for bindings
// (port/src/capi/) both run it.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/frame.h"
#include "hesai/health.h"
#include "hesai/held_packets.h"
#include "hesai/replay.h"
#include "hesai/rotation.h"
#include "hesai/safety.h"
#include "hesai/sequence.h"
#include "hesai/stats.h"
#include "hesai_port/base/status.h"
#include "hesai_port/capture/capture.h"
#include "hesai_port/formats/pointcloud2.h"

namespace hesai::port {

/// Options shared by decode, stats and listen.
struct DecodeOptions {
  std::string calibration_path;     ///< --calibration: angle-correction CSV
  std::string firetimes_path;       ///< --firetimes
  std::string channel_config_path;  ///< --channel-config (QT128)
  Reflectivity reflectivity = Reflectivity::raw;  ///< --reflectivity (nonlinear: Pandar64 only)
  Returns returns = Returns::all;   ///< --returns: distinct leaves out the repeated second returns
  bool firetime_azimuth = true;     ///< off with --no-firetime-azimuth
  bool detect_rotation = true;      ///< --rotation auto (default): per sensor, by a RotationDetector
  Rotation rotation = Rotation::clockwise;  ///< --rotation cw|ccw; with auto, the direction assumed for packets released undecided
  std::uint64_t first_packet = 0;   ///< --packets FIRST:END, point-cloud packet indices
  std::uint64_t end_packet = UINT64_MAX;
  FrameAssembler frames;            ///< --cut-angle and --fov set; each source starts from a copy
  float min_range = 0;              ///< --min-range, metres
  float max_range = 1e9f;           ///< --max-range, metres
  bool has_key = false;             ///< --session-key, or --secret with the two randoms
  std::array<std::uint8_t, 32> session_key{};
  bool allow_unsigned = false;      ///< --allow-unsigned
  /// listen --sensor: a secret without randoms is kept here for a signature session (the randoms
  /// come from the sensor) instead of being refused.
  bool session_secret_allowed = false;
  std::string session_secret;
};

/// Consecutive kept points of one packet that belong to one frame, for Sink::points: the points
/// as the decoder made them (read in place where the packet keeps every point; where --min-range,
/// --max-range or --fov leave some out, the kept ones gathered once). Valid during the call only.
struct PointRun {
  const Point* points = nullptr;
  /// nebula's ReturnType of each point, for the MCAP's return_type (from the packet's return mode
  /// and the other returns of the point's firing: nebula_return_type); null unless the sink
  /// wants_return_types().
  const NebulaReturnType* return_types = nullptr;
  std::size_t count = 0;
  std::uint64_t frame = 0;   ///< frame id (1-based) within its sensor's frames
  std::uint64_t packet = 0;  ///< 0-based index of the point-cloud packet in the input
  std::uint32_t sensor = 0;  ///< its sensor, as Sink::sensor_added named it
};

/// Receives what the pipeline produces. A sensor is one source (an address and port, or a bag
/// topic): sensor_added() names it before its first point. Each sensor's frames close in order;
/// every point of a frame is given to points() before its frame_closed(). Points come in packet
/// order, as runs (PointRun): a run is a packet's consecutive kept points of one frame, so a
/// packet whose points all fall in one frame is one call, not one per point. Near a cut a packet
/// gives points to two frames, and there its points can alternate between them (channels' azimuth
/// offsets): each change of frame starts a new run, and a frame that closes inside the packet
/// ends the run under way. The points of several sensors interleave as their packets do.
class Sink {
 public:
  virtual ~Sink() = default;
  /// A new sensor: `sensor` (0, 1, ... in the order they first sent a point-cloud packet) and its
  /// label ("192.168.1.201:2368", a bag's topic, or "source N").
  virtual void sensor_added(std::uint32_t sensor, const std::string& label) = 0;
  /// The receive time (ns since 1970) of the datagram now being fed: the capture's record time, or
  /// the kernel's for a live socket. Frames that close while it is processed closed at this time.
  virtual void receive_time(std::uint64_t ns) = 0;
  virtual void points(const PointRun& run) = 0;
  virtual void frame_closed(const FrameInfo& frame, std::uint32_t sensor) = 0;
  /// Whether PointRun::return_types are wanted (the MCAP's return_type): it costs the decoder a
  /// pass more over each packet's units, so they are left out otherwise.
  virtual bool wants_return_types() const { return false; }
};

/// The columns mode's receiver (Pipeline::set_columns): each point-cloud packet is decoded
/// straight into room() by the core's columnar decode; kept() then says that the points last
/// decoded there are the next ones of the output. A packet decoded but not kept (held until its
/// sensor's direction is known, outside --packets, refused as replayed) is written over by the
/// next decode: room() may be asked for again without a kept() in between.
class ColumnSink {
 public:
  virtual ~ColumnSink() = default;
  /// Room for kMaxPointsPerPacket points, where the next packet's points go (time_ns relative to
  /// the packet's time, PacketInfo::time_ns).
  virtual PointColumns room() = 0;
  /// The `count` points last decoded into room() are kept: from point-cloud packet `index` (as
  /// PointRun::packet) of `sensor` (as Sink::sensor_added numbered it), whose time is info.time_ns.
  virtual void kept(std::size_t count, std::uint64_t index, std::uint32_t sensor, const PacketInfo& info) = 0;
};

/// One sensor's stream health, for the per-sensor report (`sensors` in stats --json).
struct SensorReport {
  std::string source;             ///< "192.168.1.201:10000" (label_source), or "source N"
  Model model = Model::unknown;
  std::uint64_t packets = 0;      ///< its point-cloud packets decoded
  std::uint64_t lost = 0;         ///< by its UDP sequence, or by azimuth and time when its packets carry none
  LostBy lost_by = LostBy::none;
  HealthCounts health;            ///< its monitor's counters (its lost, reordered, duplicates: by azimuth and time)
};

/// Decodes datagrams. One decoder, sequence tracker, stream-health monitor, frame assembler and
/// functional-safety monitor per source (the sensor's address and port), created on its first
/// packet. A packet with a UDP sequence counts its losses by the sequence; one without, by the
/// health monitor's block azimuth and packet time (Stats::lost_by says which).
///
/// With --rotation auto, a source's point-cloud packets are held (up to kHeldPackets) until its
/// RotationDetector knows the direction, then decoded in it, in their order and with the indices
/// they came with: the points and frames of the first packets are those of a stream whose
/// direction was set. A source whose direction is still unknown when kHeldPackets are held
/// releases its oldest packet decoded in the assumed direction (a stationary motor); so does
/// finish(). A Pandar40 GPS packet that comes while packets are held sets their time base too.
class Pipeline {
 public:
  Pipeline(const DecodeOptions& options, Sink* sink);
  /// Wipes the session key (the pipeline's copy and its decoders').
  ~Pipeline();
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  /// Loads the calibration files (the angle and firing-time files are parsed and applied when the
  /// first packet of a model shows their channel count; feed() then fails with the file's error;
  /// the channel configuration is parsed at once, and applied to each QT128 decoder).
  /// Status::input for a missing or unreadable file, Status::usage for a channel configuration
  /// that does not parse.
  Status load_files();
  /// Files downloaded from a sensor (listen --sensor), used where no file was given (an explicit
  /// file wins); `origin` names them in messages. Status::usage for a channel configuration that
  /// does not parse.
  Status use_downloaded(const std::string& origin, const std::string& angles, const std::string& firetimes,
                        const std::string& channel_config);
  /// Verifies signatures under `key` from now on (a live signature session, or one restarted with
  /// a new key), in every decoder and those created later. Every packet fed from now on must carry
  /// a valid signature: an unsigned one is rejected (unsigned_rejected) unless it is fed with
  /// `pre_session` (received before the session's key was agreed; unsigned_accepted) or
  /// --allow-unsigned was given. Each sensor's replay guard starts anew (a new key).
  ///
  /// Under any key (this one, or --session-key), a validly signed packet that is not new for its
  /// sensor (hesai/replay.h: its UDP sequence, or its time, does not move forward past the replay
  /// window) is refused and counted as replayed: none of its points is kept, and it counts in
  /// neither signature_valid nor the losses.
  void start_session(const std::uint8_t key[32]);
  /// listen --sensor: the sensor's model, from its inventory. A point-cloud packet of another
  /// model is rejected and counted (foreign_model_packets): it never ends the run and never
  /// replaces the sensor's decoder, calibration or session.
  void fix_model(Model model) { fixed_model_ = model; }
  std::uint64_t foreign_model_packets() const { return foreign_model_packets_; }

  /// One UDP payload; `source` identifies the sender (address and port); `pre_session`: during a
  /// live session, the kernel received it before the session's key was agreed, so it may be
  /// unsigned. Returns false on a fatal configuration error: a calibration file that does not
  /// parse, does not fit the model or holds a value the decoder refuses (message in error(),
  /// naming the file and the Error).
  bool feed(ByteView payload, std::uint64_t source, bool pre_session = false);
  /// The receive time of the datagrams fed from now on (ns since 1970), for the sink.
  void set_receive_time(std::uint64_t ns) {
    if (sink_) sink_->receive_time(ns);
  }
  /// Decodes the packets still held and closes the open frames at the end of the input.
  void finish();

  /// The columns mode (set before the first feed()): every point-cloud packet is decoded into
  /// `columns` (ColumnSink) instead of into Points, then held, selected by --packets and accounted
  /// per packet as in the points mode, with two costs left out, both per point or per unit: no
  /// frames are assembled (the columns carry no azimuth; the Sink gets sensor_added() and
  /// receive_time(), never points() or frame_closed()) and the units are not scanned. So
  /// Stats::frames and what the scan counts (blockage, repeated returns, beyond rated range) stay
  /// 0: a caller of this mode reports no counts. Every decoded point is kept: the options must
  /// leave none out (no --fov, ranges or --returns distinct; the caller checks).
  void set_columns(ColumnSink* columns) {
    columns_ = columns;
    scan_ = UnitScan{};  // what process() reads of it: nothing
  }

  /// Sets up a fresh decoder as the pipeline sets up each source's: the calibration files (parsed
  /// for its model's channels), the channel configuration, reflectivity, firing-time correction,
  /// session key, the last GPS packet and the --rotation given. False with a message in error()
  /// when a file or setting does not fit the model (feed() fails the same way).
  bool configure_decoder(Decoder& decoder);

  const Stats& stats() const { return stats_; }
  /// Names the sender `key` in the per-sensor report (once; later calls for the key change nothing).
  void label_source(std::uint64_t key, const std::string& label) { labels_.emplace(key, label); }
  bool has_label(std::uint64_t key) const { return labels_.count(key) != 0; }
  /// Every sensor that sent point-cloud packets, in the order they first did.
  std::vector<SensorReport> sensors() const;
  /// The IP fragments the capture reader skipped (they are not reassembled), for the report.
  void set_ip_fragments(std::uint64_t n) { stats_.ip_fragments = n; }
  const std::string& error() const { return error_; }
  /// Packets per Error code that rejected them (for the text summary).
  const std::map<Error, std::uint64_t>& rejections() const { return rejections_; }
  /// The rotation of the sensor that sent the last point-cloud packet and how it was chosen:
  /// "clockwise (set)", "counterclockwise (detected)", "clockwise (assumed: not detected)"; empty
  /// before any point-cloud packet.
  std::string rotation_text() const;

 /// Packets held per source while its direction is not known. A dual-return QT128C2X, whose
  /// packets show no direction by themselves, holds two; the other bundled captures none.
  static constexpr std::size_t kHeldPackets = 8;

 private:
  struct Source {
    std::unique_ptr<Decoder> decoder;
    SequenceTracker sequence;
    HealthMonitor health;
    FrameAssembler frames;
    SafetyMonitor safety;
    RotationDetector rotation;
    ReplayGuard replay;  // its validly signed packets, each accepted once in a session
    HeldPackets<kHeldPackets> held;  // decoded, not yet processed: the direction is not known;
                                     // tagged with the packet's index | kPreSessionTag
    std::uint64_t key = 0;           // the sender (feed's source)
    std::uint64_t order = 0;         // when it first sent (for the report's order)
    std::uint64_t packets = 0;       // point-cloud packets processed
    LostBy lost_by = LostBy::none;
  };
  // A held packet's tag: its index, with this bit when it was fed as pre_session.
  static constexpr std::uint64_t kPreSessionTag = std::uint64_t{1} << 63;
  // During a session, lets `src`'s decoder accept an unsigned packet only if it came pre_session.
  void allow_unsigned_for(Source& src, bool pre_session);
  Source* source_for(std::uint64_t key, Model model);
  // Parses a channel configuration (named options_.channel_config_path in messages) into
  // channel_config_. Status::usage when it does not parse.
  Status parse_channel_config(const std::string& text);
  // Decodes the oldest held packet in the decoder's direction and processes it.
  bool release_held(Source& src);
  // Whether --packets keeps the point-cloud packet of `index`.
  bool wanted(std::uint64_t index) const { return index >= options_.first_packet && index < options_.end_packet; }
  // src's decoder on the payload of the packet that is (or would be, once accepted) `index`: a
  // wanted one decoded into points_ and scan_, and compare_ when return_types_; any other
  // surveyed (Decoder::survey: scan_ and surveyed_points_, no point made).
  Error decode(Source& src, ByteView payload, std::uint64_t index, PacketInfo& info);
  // Accounts one decoded or surveyed packet and gives its blocks to the frames, and the points of a
  // wanted one (points_ holds them).
  bool process(Source& src, std::uint64_t index, const PacketInfo& info);
  // The kept points of points_[first, end) (one block) to their frames, and in runs to the sink.
  void assign_frames(Source& src, std::uint64_t index, const PacketInfo& info, std::size_t first, std::size_t end);
  void close_frames(Source& src);

  DecodeOptions options_;
  Sink* sink_;
  bool return_types_;  // the sink wants PointRun::return_types
  bool filtered_;      // --min-range, --max-range or --fov may leave points out
  std::string angles_text_, firetimes_text_;
  std::unique_ptr<ChannelConfig> channel_config_;  // --channel-config, parsed once
  std::map<std::uint64_t, Source> sources_;
  std::map<std::uint64_t, std::string> labels_;
  std::uint64_t sources_made_ = 0;
  const Source* last_source_ = nullptr;  // of the last decoded point-cloud packet
  const Source* fov_source_ = nullptr;   // the sensor whose FOV gap Stats reports (compared, never read)
  bool session_ = false;  // start_session() was called
  Model fixed_model_ = Model::unknown;  // fix_model(); unknown: any model
  std::uint64_t foreign_model_packets_ = 0;
  GpsPacket last_gps_{};
  bool have_gps_ = false;
  Stats stats_{};
  std::map<Error, std::uint64_t> rejections_;
  std::uint64_t point_packet_index_ = 0;
  std::string error_;
  // Gives the sink the run under way (before a frame closes, and at a packet's end); the gathered
  // points start over.
  void flush_points();
  // Points [points, points + count) of one frame to the sink: added to the run under way when
  // they continue it (the same frame and packet, the next points in memory), else a new run.
  void run_points(const Point* points, const NebulaReturnType* types, std::size_t count, std::uint64_t frame,
                  std::uint64_t packet, std::uint32_t sensor);

  PacketPoints points_;  // one packet's points (reused)
  UnitScan scan_;        // and what its units say beyond them
  std::size_t surveyed_points_ = 0;  // the points of a packet surveyed, not decoded (not wanted)
  ReturnComparison compare_;  // and how each of its returns compares with its firing's others
  // The nebula ReturnType of each of points_ (when return_types_), computed a block at a time
  // from the packet's table.
  std::array<NebulaReturnType, kMaxPointsPerPacket> types_;
  PacketReturnTypes type_of_;
  // A filtered packet's kept points (and their return types), gathered a block at a time:
  // gathered_n_ of them so far; reset when the sink has them (flush_points).
  std::array<Point, kMaxPointsPerPacket> gathered_;
  std::array<NebulaReturnType, kMaxPointsPerPacket> gathered_types_;
  std::size_t gathered_n_ = 0;
  // A block's frame id per point, when its points went to more than one frame.
  std::array<std::uint64_t, kMaxPointsPerPacket> ids_;
  PointRun run_;  // the run under way (count 0: none)

  ColumnSink* columns_ = nullptr;  // set_columns(): the columns mode
  std::size_t column_count_ = 0;   // the points of the last decode into columns_->room()
};

/// The source a captured datagram comes from, for Pipeline::feed: its sender's address and port.
std::uint64_t source_key(const UdpDatagram& d);

/// The sender of a captured datagram, for the per-sensor report: "192.168.1.201:10000",
/// "[fe80::1]:10000", or "mcap channel N" (MCAP packets carry no address).
std::string source_text(const UdpDatagram& d, const CaptureFile& file);

}  // namespace hesai::port
