#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "daq/recording/recording.h"
#include "daq/recording/sidecar.h"
#include "daq/sources/rig_source.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

/// What a source description leaves to options: the rig's model and schedule, the replay's
/// speed, the layout a network receiver expects, the JACK server and calibration. One set for
/// every kind; each kind reads the fields it needs.
struct SourceOptions {
  // Virtual rig.
  std::string model = "paper";               // paper | illustrative | MODEL.json
  std::optional<analysis::Model> rig_model;  // a model given as a value: used instead of `model`
  bool positive_well = true;
  double frequency_hz = 9.0;             // ν until changed
  std::vector<ExcitationStep> schedule;  // an unattended stepped sine (empty: at rest)
  std::optional<double> duration_s;      // the rig ends there
  std::uint64_t seed = 1;                // the rig's sensor noise and creep
  // Virtual rig and replay.
  double speed = 1.0;  // × real time; 0: as fast as possible
  bool loop = false;   // replay: start again at the end
  // Network receiver: the layout to expect (senders that differ are refused).
  std::optional<Sidecar> expected;
  // JACK.
  std::string jack_server;                 // empty: the default server ($JACK_DEFAULT_SERVER)
  std::string jack_client = "oscilab";     // the client name asked for
  std::optional<Sidecar> calibration;      // required: one channel per port, in port order
  std::optional<double> analysis_rate_hz;  // none: the calibration's sample_rate_hz
  /// The word option messages name ("--source" on the command line, "source" in the app).
  std::string what = "--source";
};

/// The kinds of source a description names.
enum class SourceKind { Rig, Replay, Network, Jack };

/// The kind `spec` names: "rig"; "net:HOST:PORT"; "jack:PORT,PORT[,...]"; "file:REC" or a bare
/// REC path (replay).
SourceKind source_kind(const std::string& spec);

/// Makes the source `spec` names (see source_kind):
/// - "rig": the virtual rig in real time (options: model, well, frequency, schedule, duration,
///   speed);
/// - "file:REC" or REC: a replay of the recording (speed, loop);
/// - "net:HOST:PORT": a receiver of the stream protocol listening there (expected); PORT 0:
///   any free port (NetSource::port() tells which);
/// - "jack:PORT_BASE,PORT_MASS[,...]": the JACK capture ports, one per channel of the
///   calibration sidecar, in its order (jack_server, jack_client, calibration,
///   analysis_rate_hz).
/// Throws InputError naming the option, the file or the port.
std::unique_ptr<SampleSource> make_source(const std::string& spec, const SourceOptions& options);

/// A replay of a recording already read (speed, loop), as make_source makes one of a file.
std::unique_ptr<SampleSource> make_source(Recording recording, const SourceOptions& options);

}  // namespace oscilab::daq
