// The live chain (daq/live/acquisition.h) as a Python iterator: a virtual rig, a replay or a
// network listener → blocks of samples in SI and the live EDC, computed exactly as offline.
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "analysis/common/input_error.h"
#include "analysis/model/model.h"
#include "bindings.h"
#include "daq/live/acquisition.h"
#include "daq/live/source_factory.h"
#include "daq/network/net_source.h"
#include "daq/recording/sidecar.h"
#include "daq/sources/replay_source.h"
#include "daq/sources/rig_source.h"
#include "python_types.h"

namespace oscilab::python {
namespace {

constexpr auto kSignalPoll = std::chrono::milliseconds(20);

struct LiveSession {
  std::unique_ptr<daq::Acquisition> acquisition;
  daq::RigSource* rig = nullptr;
  daq::ReplaySource* replay = nullptr;
  daq::NetSource* net = nullptr;
  std::optional<double> duration_s;
  double poll_s = 0.1;
  bool blocks = true;
  std::string record_to;
  bool started = false;
  bool ended = false;
  double traced_to_s = 0.0;
  std::size_t cycles_seen = 0, levels_seen = 0, events_seen = 0;

  ~LiveSession() {
    if (acquisition && started && !ended) acquisition->stop();
  }

  void start() {
    if (started) return;
    if (!record_to.empty()) acquisition->start_recording(record_to);
    acquisition->start();
    started = true;
  }

  void stop() {
    if (!started || ended) return;
    py::gil_scoped_release release;
    acquisition->stop();
    ended = true;
  }
};

py::dict status_dict(const daq::AcquisitionStatus& s) {
  py::dict d;
  d["source"] = s.source;
  d["running"] = s.running;
  d["finished"] = s.finished;
  d["layout_known"] = s.layout_known;
  d["sample_rate_hz"] = s.sample_rate_hz;
  d["stream_time_s"] = s.stream_time_s;
  d["samples"] = s.samples;
  d["blocks"] = s.blocks;
  d["gaps"] = s.gaps;
  d["gap_samples"] = s.gap_samples;
  d["lost_blocks"] = s.lost_blocks;
  d["duplicates"] = s.duplicates;
  d["reordered"] = s.reordered;
  d["late"] = s.late;
  d["discontinuities"] = s.discontinuities;
  d["non_finite_samples"] = s.non_finite_samples;
  d["saturated_samples"] = s.saturated_samples;
  d["overflowed_blocks"] = s.overflowed_blocks;
  d["malformed_frames"] = s.network.malformed_frames;
  d["layout_mismatches"] = s.network.layout_mismatches;
  d["connections"] = s.network.connections;
  d["queue_fill"] = s.queue_fill;
  d["queue_capacity"] = s.queue_capacity;
  d["recording"] = s.recording;
  d["recording_path"] = s.recording_path;
  d["recorded_samples"] = s.recorded_samples;
  d["recorder_error"] = s.recorder_error;
  d["cycles"] = s.cycles;
  d["excluded_cycles"] = s.excluded_cycles;
  d["levels"] = s.levels;
  d["edc_message"] = s.edc_message;
  d["edc_latency_s"] = s.edc_latency_s;
  d["edc_latency_median_s"] = s.edc_latency_median_s;
  d["edc_latency_max_s"] = s.edc_latency_max_s;
  d["alarms"] = s.alarms;
  return d;
}

// What arrived since the last update: new samples (SI), cycles, finished levels, events.
py::dict collect(LiveSession& session, bool final_update) {
  daq::Acquisition& a = *session.acquisition;
  const daq::AcquisitionStatus status = a.status();
  py::dict update;
  update["t_s"] = status.stream_time_s;
  update["final"] = final_update;
  update["status"] = status_dict(status);
  if (session.blocks) {
    daq::TraceHistory traces;
    const double rate = status.sample_rate_hz;
    const double to_s = status.stream_time_s + (rate > 0 ? 1.0 / rate : 0.0);
    if (to_s > session.traced_to_s) {
      // One bucket per sample: the samples themselves, not an envelope.
      const double span = (to_s - session.traced_to_s) * std::max(rate, 1.0) + 2.0;
      const int buckets =
          static_cast<int>(std::min(span, static_cast<double>(std::numeric_limits<int>::max())));
      a.history(session.traced_to_s, to_s, buckets, traces);
      // Next time from the sample after the last one (a quarter sample in: floor() lands on it).
      if (!traces.t_s.empty()) {
        session.traced_to_s = (std::round(traces.t_s.back() * rate) + 1.25) / rate;
      }
    }
    py::dict block;
    block["t_s"] = to_array(traces.t_s);
    block["base"] = to_array(traces.base);
    block["mass"] = to_array(traces.mass);
    block["force_n"] = to_array(traces.force_n);
    update["block"] = block;
  }
  const std::vector<analysis::CycleFit> cycles = a.cycles_since(session.cycles_seen);
  update["cycles"] = cycle_table(cycles);
  const std::vector<analysis::LevelResult> levels = a.levels();
  const std::vector<analysis::LevelResult> fresh(
      levels.begin() + static_cast<std::ptrdiff_t>(std::min(session.levels_seen, levels.size())),
      levels.end());
  session.levels_seen = levels.size();
  update["levels"] = level_table(fresh);
  const auto current = a.current_level();
  if (current) {
    py::dict c = level_table(std::vector<analysis::LevelResult>{*current});
    py::dict one;
    for (const auto& [key, value] : c) one[key] = value[py::int_(0)];
    update["current_level"] = one;
  } else {
    update["current_level"] = py::none();
  }
  py::list events;
  for (const daq::StreamEvent& e : a.events_since(session.events_seen)) {
    events.append(to_python(e.to_json()));
    ++session.events_seen;
  }
  update["events"] = events;
  return update;
}

py::dict next_update(LiveSession& session) {
  if (session.ended) throw py::stop_iteration();
  session.start();
  const std::chrono::steady_clock::time_point deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                             std::chrono::duration<double>(session.poll_s));
  bool end = false;
  for (;;) {
    {
      py::gil_scoped_release release;
      std::this_thread::sleep_for(std::min<std::chrono::steady_clock::duration>(
          kSignalPoll, std::max<std::chrono::steady_clock::duration>(
                           deadline - std::chrono::steady_clock::now(),
                           std::chrono::steady_clock::duration::zero())));
    }
    if (PyErr_CheckSignals() != 0) {
      py::error_already_set interrupt;
      session.stop();
      throw interrupt;
    }
    const daq::AcquisitionStatus status = session.acquisition->status();
    end = session.acquisition->finished() || !status.recorder_error.empty() ||
          (session.duration_s && status.stream_time_s >= *session.duration_s);
    if (end || std::chrono::steady_clock::now() >= deadline) break;
  }
  if (end) session.stop();
  py::dict update = collect(session, end);
  if (end) {
    const std::string error = session.acquisition->status().recorder_error;
    if (!error.empty()) throw InputError(error);
  }
  return update;
}

}  // namespace

namespace {

// The LiveSession class: a running acquisition read block by block.
void bind_live_session(py::module_& m) {
  py::class_<LiveSession>(m, "LiveSession", R"doc(
A live source running through the acquisition chain (the CLI's `record`): iterate it for updates,
each a dict: t_s (stream time [s]), block (the samples since the last update in SI: t_s, base,
mass, force_n = −m b̈), cycles (new fitted cycles, columns as Analysis.cycles), levels (levels
finished since the last update, columns as the EDC table without `record`), current_level (the
level being filled, or None), events (gaps, faults, marks ... as dicts), status (counters), and
final (True on the last update). It ends when the source ends, at duration_s of stream time,
or on stop(); Ctrl-C stops it and raises KeyboardInterrupt. Use it as a context manager to stop
it on leaving. Made by oscilab.live().
)doc")
      .def("__iter__", [](LiveSession& s) -> LiveSession& { return s; })
      .def("__next__", &next_update)
      .def("__enter__", [](LiveSession& s) -> LiveSession& { return s; })
      .def("__exit__", [](LiveSession& s, const py::args&) { s.stop(); })
      .def("start", &LiveSession::start, "Starts the source (the first iteration does it too).")
      .def("stop", &LiveSession::stop,
           "Stops the source, processes what it delivered, closes the levels and the recording.")
      .def(
          "levels", [](const LiveSession& s) { return level_table(s.acquisition->levels()); },
          "Every finished level so far: the live EDC table (well, f0_n, edc_mean_j, edc_std_j, "
          "cycles, ... flags), what `record --edc` writes.")
      .def(
          "status", [](const LiveSession& s) { return status_dict(s.acquisition->status()); },
          "The acquisition's counters now (samples, gaps, duplicates, NaN, saturation, queue, "
          "cycles, levels, EDC latency ...).")
      .def(
          "mark", [](LiveSession& s, const std::string& text) { s.acquisition->mark(text); },
          py::arg("text"), "An operator's mark in the event log at the current stream time.")
      .def(
          "set_excitation",
          [](LiveSession& s, double f0_n, double frequency_hz) {
            if (!s.rig) throw InputError("set_excitation: only the virtual rig is operated");
            s.rig->set_excitation(f0_n, frequency_hz);
          },
          py::arg("f0_n"), py::arg("frequency_hz") = 9.0,
          "Virtual rig: ramp to f0_n [N] at frequency_hz [Hz] from the next block on.")
      .def_property_readonly(
          "port",
          [](const LiveSession& s) -> py::object {
            return s.net ? py::object(py::int_(s.net->port())) : py::object(py::none());
          },
          "Network source: the TCP port it listens on (useful with port 0).")
      .def_property_readonly(
          "layout",
          [](const LiveSession& s) -> py::object {
            const auto layout = s.acquisition->layout();
            return layout ? to_python(daq::sidecar_to_json(*layout)) : py::none();
          },
          "The stream's sidecar (dict) once known, else None.");
}

// live(): a live session on a source.
void bind_live_function(py::module_& m) {
  m.def(
      "live",
      [](const py::object& source, const py::object& duration_s, double speed,
         const py::object& model, const std::string& well, double freq_hz,
         const py::object& levels_n, double hold_s, double lead_in_s, std::uint64_t seed,
         const py::object& expected_sidecar, const py::object& record_to, double poll_s,
         bool blocks, const py::object& excitation_freq_hz, const py::object& calibration,
         const std::string& jack_server) {
        auto session = std::make_unique<LiveSession>();
        if (!duration_s.is_none()) session->duration_s = number_argument(duration_s, "duration_s");
        if (!(poll_s > 0.0)) throw InputError("poll_s: must be positive");
        session->poll_s = poll_s;
        session->blocks = blocks;
        if (!record_to.is_none()) session->record_to = path_string(record_to);
        // One factory for every front-end (the CLI's record and stream, the app's Live tab):
        // Python adds only a Recording object as a source and a Model object as the rig's model.
        daq::SourceOptions options;
        options.what = "source";
        options.rig.speed = options.replay.speed = speed;
        std::unique_ptr<daq::SampleSource> src;
        if (py::isinstance<daq::Recording>(source)) {
          src = daq::make_source(source.cast<daq::Recording>(), options);
        } else {
          const std::string spec = path_string(source);
          if (daq::source_kind(spec) == daq::SourceKind::Rig) {
            options.rig.model_value = model_argument(model);
            options.rig.well = well_argument(well);
            options.rig.seed = seed;
            options.rig.frequency_hz = freq_hz;
            options.rig.duration_s = session->duration_s;
            if (!levels_n.is_none()) {
              options.rig.schedule =
                  daq::rig_schedule(levels_argument(levels_n), hold_s, lead_in_s, freq_hz);
            }
          }
          const auto sidecar_argument = [](const py::object& value, const char* name) {
            return py::isinstance<py::dict>(value)
                       ? daq::parse_sidecar(json_argument(value, name), name)
                       : daq::read_sidecar(path_string(value));
          };
          if (!expected_sidecar.is_none()) {
            options.network.expected = sidecar_argument(expected_sidecar, "expected_sidecar");
          }
          if (!calibration.is_none())
            options.jack.calibration = sidecar_argument(calibration, "calibration");
          options.jack.server = jack_server;
          py::gil_scoped_release release;  // a replay reads its whole file here
          src = daq::make_source(spec, options);
        }
        session->rig = dynamic_cast<daq::RigSource*>(src.get());
        session->replay = dynamic_cast<daq::ReplaySource*>(src.get());
        session->net = dynamic_cast<daq::NetSource*>(src.get());
        daq::AcquisitionOptions acquisition;
        if (!excitation_freq_hz.is_none()) {
          acquisition.excitation_freq_hz =
              number_argument(excitation_freq_hz, "excitation_freq_hz");
        }
        session->acquisition = std::make_unique<daq::Acquisition>(std::move(src), acquisition);
        return session;
      },
      py::arg("source"), py::kw_only(), py::arg("duration_s") = py::none(), py::arg("speed") = 1.0,
      py::arg("model") = "paper", py::arg("well") = "positive", py::arg("freq_hz") = 9.0,
      py::arg("levels_n") = py::none(), py::arg("hold_s") = 10.0, py::arg("lead_in_s") = 2.5,
      py::arg("seed") = 1, py::arg("expected_sidecar") = py::none(),
      py::arg("record_to") = py::none(), py::arg("poll_s") = 0.1, py::arg("blocks") = true,
      py::arg("excitation_freq_hz") = py::none(), py::arg("calibration") = py::none(),
      py::arg("jack_server") = "",
      R"doc(A live source through the acquisition chain, as an iterator of updates (LiveSession).

source: 'rig' (the virtual rig in real time: model, well, freq_hz [Hz], seed, and levels_n —
amplitudes [N] as a sequence or 'A:STEP:B' — held hold_s [s] each after lead_in_s [s] for an
unattended stepped sine; without it the rig rests until set_excitation()), a recording path or
'file:PATH' or a Recording read from a file (replay), or 'net:HOST:PORT' (listen for a sender of
the stream protocol; port 0 picks a free one, see .port; expected_sidecar: a dict or path of the
layout to accept), or 'jack:PORT_BASE,PORT_MASS[,...]' (JACK capture ports, one per channel of
the calibration sidecar, a dict or path, in its order; jack_server: the server's name, empty for
the default; the signals are brought to the calibration's sample_rate_hz). speed: × real time for rig and replay (0: as fast as the chain takes it).
duration_s: stop at this stream time [s]. record_to: also record to this path (.wav .w64 .rf64)
with sidecar and event log. poll_s: seconds between updates. blocks: include the samples.
excitation_freq_hz: override the layout's frequency for the live EDC [Hz].)doc");
}

}  // namespace

void bind_live(py::module_& m) {
  bind_live_session(m);
  bind_live_function(m);
}

}  // namespace oscilab::python
