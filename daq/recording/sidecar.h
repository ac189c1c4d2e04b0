#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace oscilab::daq {

/// What a channel measures, contract §1 `role`.
enum class ChannelRole { Base, Mass, Relative, Force };
/// Physical quantity of a channel, contract §1 `quantity`.
enum class Quantity { Acceleration, Velocity, Displacement, Force };

std::string to_string(ChannelRole role);
std::string to_string(Quantity quantity);
/// The SI unit a reader converts `quantity` to: "m/s^2", "m/s", "m" or "N".
std::string si_unit(Quantity quantity);

/// The value of the sidecar's "format" key this code reads and writes.
inline constexpr const char* kSidecarFormat = "oscilab-recording/1";

/// One channel of a recording as the sidecar describes it. Physical value in `unit` is
/// scale × stored + offset; the readers then convert `unit` to SI. In the sidecar, "scale" is
/// required (a calibration is never guessed) and "offset" defaults to 0. For integer containers
/// (16/24/32-bit PCM, FLAC) "stored" is the integer count, not a value normalised to ±1.
struct ChannelInfo {
  std::string name;
  ChannelRole role = ChannelRole::Base;
  Quantity quantity = Quantity::Acceleration;
  std::string unit = "m/s^2";
  double scale = 1.0;
  double offset = 0.0;
  std::string sensor;
  /// Files that hold named signals (TDMS, MATLAB, HDF5, UFF 58): the signal this channel reads,
  /// as `oscilab-cli info` lists it ("group/channel", a variable, a dataset path, ...); empty:
  /// the signal named like the channel.
  std::string source;
  /// 0-based column: of a CSV file (-1: matched by name in the header), or of the 2-D matrix or
  /// dataset `source` names (-1: the signal is a vector).
  int column = -1;
  /// The sensor's or the ADC's full scale in `unit` (sidecar "range": [min, max]); a sample at
  /// or beyond either end is saturated. Unknown: no saturation check.
  std::optional<std::pair<double, double>> range;
  /// The corner of the first-order high-pass an AC-coupled input puts in front of the samples
  /// (sidecar "ac_coupling_hz", Hz, below the Nyquist frequency): a sound card's input
  /// capacitor. The analysis undoes its phase and gain (analysis/signal/ac_coupling.h). None:
  /// a DC-coupled input.
  std::optional<double> ac_coupling_hz;
  /// Volts at the full scale of a sound-card input (sidecar "full_scale_v"): a JACK source
  /// stores sample × full_scale_v, so that with unit "V" `scale` is the sensor's sensitivity.
  /// None: the stored value is the fraction of full scale the interface gives.
  std::optional<double> full_scale_v;
  nlohmann::json extra = nlohmann::json::object();  // other keys, kept as they are
};

/// One stepped-sine level: forcing amplitude and the steady part of its hold.
struct ExcitationLevel {
  double f0_n = 0.0;
  double start_s = 0.0;
  double end_s = 0.0;
  nlohmann::json extra = nlohmann::json::object();  // other keys, kept as they are
};

/// Excitation metadata (optional and possibly partial, contract §1).
struct Excitation {
  std::string type;                                 // "stepped-sine", "random", ...
  std::optional<double> frequency_hz;               // stepped sine
  std::vector<ExcitationLevel> levels;              // stepped sine
  nlohmann::json extra = nlohmann::json::object();  // other keys, kept as they are
};

/// A stretch of a recording whose samples must not be trusted (sidecar "invalid_intervals"): a
/// gap in a live stream (filled with NaN), non-finite or saturated samples. Readers accept
/// non-finite samples inside such an interval; the analysis leaves out every cycle that touches
/// one and the restoring-force samples near it. A zero-length interval marks a discontinuity.
struct InvalidInterval {
  double start_s = 0.0;
  double end_s = 0.0;
  std::string reason;  // "gap", "non-finite", "saturated", "discontinuity", ...
};

/// How a CSV file is laid out (sidecar key "csv"). With `header` false every channel names its
/// `column`. A delimiter ' ' splits on runs of spaces and tabs.
struct CsvLayout {
  bool header = true;
  char delimiter = ',';
  int skip_lines = 0;    // lines skipped before the header (or the data): an instrument's preamble
  int time_column = -1;  // 0-based column of the time in s, checked against the rate; -1: none
                         // (with a header, a column named "t_s" is the time column)
};

/// Where a file that holds named signals keeps its time axis in s (sidecar key "time"), checked
/// against the sidecar's rate: a time vector, or a column of a matrix (often the first).
struct SignalTime {
  std::string source;
  int column = -1;  // -1: `source` is a vector
};

/// The JSON sidecar of a recording, contract §1. Unknown keys are kept in `extra` and written
/// back, so a round trip loses nothing.
struct Sidecar {
  double sample_rate_hz = 0.0;
  std::optional<double> mass_kg;
  std::vector<ChannelInfo> channels;
  std::optional<Excitation> excitation;
  std::string notes;
  std::optional<CsvLayout> csv;
  std::optional<SignalTime> time;                  // named-signal files only
  std::vector<InvalidInterval> invalid_intervals;  // in time order
  nlohmann::json extra = nlohmann::json::object();
};

/// Parses and validates a sidecar. `file_name` prefixes every error message, e.g.
/// `run1.json: channels[1].unit: unknown unit "mps"`. Throws oscilab::InputError.
Sidecar parse_sidecar(const nlohmann::json& json, const std::string& file_name);
nlohmann::json sidecar_to_json(const Sidecar& sidecar);

/// The sidecar path of a recording: same stem, `.json`.
std::string sidecar_path_for(const std::string& recording_path);
Sidecar read_sidecar(const std::string& sidecar_path);
void write_sidecar(const Sidecar& sidecar, const std::string& sidecar_path);

/// Factor that turns a value in `unit` into SI for `quantity` (e.g. "mm" → 1e-3, "g" → 9.80665).
/// "V" is accepted for every quantity with factor 1: the channel's scale is then the sensor
/// sensitivity in SI units per volt. Throws InputError naming `where` for an unknown unit or one
/// that does not fit the quantity.
double unit_to_si(const std::string& unit, Quantity quantity, const std::string& where);

/// The quantity a unit the sidecar knows measures ("mm/s" → velocity), or nothing for "V" and
/// unknown units.
std::optional<Quantity> unit_quantity(const std::string& unit);

}  // namespace oscilab::daq
