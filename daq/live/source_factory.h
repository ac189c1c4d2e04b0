#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/edc/well.h"
#include "daq/recording/recording.h"
#include "daq/recording/sidecar.h"
#include "daq/sources/rig_source.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

/// What a source description leaves to options, one part per kind of source (each kind reads
/// its own), and the word its messages name.
struct SourceOptions {
  /// The virtual rig ("rig").
  struct Rig {
    std::string model = "paper";                     // paper | illustrative | MODEL.json
    std::optional<analysis::Model> model_value;      // a model given as a value: used instead
    analysis::Well well = analysis::Well::Positive;  // where it starts: positive or negative
    double frequency_hz = 9.0;                       // ν until changed
    std::vector<ExcitationStep> schedule;            // an unattended stepped sine (empty: at rest)
    std::optional<double> duration_s;                // the rig ends there
    std::uint64_t seed = 1;                          // the rig's sensor noise and creep
    double speed = 1.0;                              // × real time; 0: as fast as possible
  };
  /// A replay ("file:REC" or REC).
  struct Replay {
    double speed = 1.0;  // × real time; 0: as fast as possible
    bool loop = false;   // start again at the end
  };
  /// A network receiver ("net:HOST:PORT").
  struct Network {
    std::optional<Sidecar> expected;  // the layout to expect (senders that differ are refused)
  };
  /// A sound card through JACK ("jack:PORT,PORT[,...]").
  struct Jack {
    std::string server;                      // empty: the default server ($JACK_DEFAULT_SERVER)
    std::string client = "oscilab";          // the client name asked for
    std::optional<Sidecar> calibration;      // required: one channel per port, in port order
    std::optional<double> analysis_rate_hz;  // none: the calibration's sample_rate_hz
  };
  Rig rig;
  Replay replay;
  Network network;
  Jack jack;
  /// The word option messages name ("--source" on the command line, "source" in the app).
  std::string what = "--source";
};

/// The kinds of source a description names.
enum class SourceKind { Rig, Replay, Network, Jack };

/// The kind `spec` names: "rig"; "net:HOST:PORT"; "jack:PORT,PORT[,...]"; "file:REC" or a bare
/// REC path (replay).
SourceKind source_kind(const std::string& spec);

/// Makes the source `spec` names (see source_kind):
/// - "rig": the virtual rig in real time (options.rig);
/// - "file:REC" or REC: a replay of the recording (options.replay);
/// - "net:HOST:PORT": a receiver of the stream protocol listening there (options.network); PORT
///   0: any free port (NetSource::port() tells which);
/// - "jack:PORT_BASE,PORT_MASS[,...]": the JACK capture ports, one per channel of the
///   calibration sidecar, in its order (options.jack).
/// Throws InputError naming the option, the file or the port.
std::unique_ptr<SampleSource> make_source(const std::string& spec, const SourceOptions& options);

/// A replay of a recording already read (options.replay), as make_source makes one of a file.
std::unique_ptr<SampleSource> make_source(Recording recording, const SourceOptions& options);

}  // namespace oscilab::daq
