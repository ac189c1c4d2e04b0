#include "daq/live/acquisition.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "analysis/common/input_error.h"
#include "analysis/common/quantile.h"
#include "analysis/pipeline/derived_signals.h"
#include "daq/live/live_edc.h"
#include "daq/live/live_recorder.h"
#include "daq/live/sample_checker.h"
#include "daq/live/stream_calibration.h"
#include "daq/live/stream_monitor.h"

namespace oscilab::daq {
namespace {

constexpr auto kIdleWait = std::chrono::milliseconds(2);  // queue empty: look again after this
// The most memory the history ring takes: 600 s of 7 traces at 80 kHz (17 MB at 512 Hz).
constexpr std::size_t kMaxHistoryBytes = std::size_t{256} << 20;
// The fastest stream the live analysis (EDC, derived traces) follows. Its zero-phase filters
// span a fixed time, so their cost per sample grows with the rate: on a 2-core laptop the chain
// follows 4 kHz seven times faster than real time and falls behind from about 8 kHz, when a
// network sender is held back and its blocks lost. Faster streams are recorded whole, with the
// live analysis off, and analysed offline.
constexpr double kMaxLiveAnalysisRateHz = 4096.0;

}  // namespace

struct Acquisition::Impl {
  AcquisitionOptions options;
  SampleSource* source = nullptr;
  std::unique_ptr<BlockQueue> queue;
  std::thread thread;
  std::atomic<bool> stop{false};

  // --- owned by the acquisition thread ---
  Sidecar layout;
  double rate_hz = 0.0;
  StreamCalibration calibration;
  StreamCalibration::Rows calibrated;  // one block
  std::unique_ptr<StreamMonitor> monitor;
  SampleChecker checker;
  std::vector<std::string> setup_warnings;  // logged once the chain starts
  std::unique_ptr<analysis::DerivedSignals> derived;
  analysis::DerivedSignals::Block derived_block;
  AlarmMonitor alarms;
  std::uint64_t next_sample = 0;
  // What a block found, published with it (capacity kept: no allocation on a clean block).
  std::vector<SampleChecker::Run> closed_runs;
  std::vector<AlarmMonitor::Alarm> raised_alarms;
  std::vector<StreamEvent> pending_events;
  std::atomic<bool> marks_waiting{false};
  // The history ring, made once the layout is known; readers reach it without the mutex.
  std::unique_ptr<HistoryRing> history_ring;
  std::atomic<const HistoryRing*> history{nullptr};

  // --- shared, under mutex ---
  mutable std::mutex mutex;
  AcquisitionStatus status;
  std::optional<Sidecar> layout_copy;
  std::uint64_t published_end = 0;  // one past the newest sample published
  LiveEdc edc;                      // its pipelines owned by the acquisition thread
  std::vector<StreamEvent> events;
  std::unique_ptr<LiveRecorder> recorder;
  std::string pending_recording;  // start once the layout is known
  bool pending_stop_recording = false;
  std::vector<std::string> pending_marks;
  std::optional<StreamEvent> last_level;  // the excitation now, for a recording started later

  void run(Acquisition& owner);
  bool setup_layout();
  void finish_pipeline();
  void handle_events();
  void handle_event(StreamEvent event);
  void log(StreamEvent event);  // queued; published with the block (publish_events)
  void on_block(const RawBlock& block, std::uint64_t first_sample);
  void on_gap(std::uint64_t first_sample, std::uint64_t samples);
  void recording_failed();  // under `mutex`
  void on_anomaly(EventKind kind, std::uint64_t sequence, std::uint64_t first_sample);
  void log_closed_runs();  // mutex held
  void exclude_samples(std::uint64_t from, std::uint64_t to);
  void raise_alarms(std::uint64_t first_sample, int rows);
  void add_derived(HistoryRing::BlockWrite& write) const;  // the derived block, for the ring
  void log_alarms();                                       // mutex held
  void publish_events();                                   // mutex held
  void publish_recorder_state();                           // mutex held
  void apply_recording_requests();
  void open_pending_recording();  // a recording asked for before the layout was known
  void copy_monitor_counters();   // mutex held
  double time_of(std::uint64_t sample) const { return static_cast<double>(sample) / rate_hz; }
};

Acquisition::Acquisition(std::unique_ptr<SampleSource> source, AcquisitionOptions options)
    : impl_(std::make_unique<Impl>()), source_(std::move(source)) {
  if (!source_) throw InputError("acquisition: no source");
  if (!(options.history_s > 0) || options.reorder_window_blocks < 1 || options.queue_blocks < 2) {
    throw InputError("acquisition: history, reorder window and queue must be positive");
  }
  impl_->options = options;
  impl_->source = source_.get();
  impl_->status.source = source_->describe();
  impl_->closed_runs.reserve(64);
  impl_->raised_alarms.reserve(8);
  impl_->pending_events.reserve(64);
}

Acquisition::~Acquisition() { stop(); }

void Acquisition::start() {
  if (impl_->thread.joinable()) return;
  impl_->queue = std::make_unique<BlockQueue>(impl_->options.queue_blocks,
                                              source_->max_block_rows(), source_->max_channels());
  impl_->stop.store(false);
  finished_.store(false);
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->status.running = true;
    impl_->status.queue_capacity = impl_->queue->capacity();
  }
  source_->start(*impl_->queue);
  impl_->thread = std::thread([this] { impl_->run(*this); });
}

void Acquisition::stop() {
  if (!impl_->thread.joinable()) return;
  source_->stop();
  impl_->stop.store(true);
  impl_->thread.join();
}

void Acquisition::start_recording(const std::string& path) {
  const std::lock_guard lock(impl_->mutex);
  // Before start() the source's own layout serves (rig, replay): recording from sample 0.
  const std::optional<Sidecar> layout = impl_->layout_copy ? impl_->layout_copy : source_->layout();
  if (!layout) {
    // A network source before its first sender: record from the first sample once the layout
    // is known. What can be checked now is (the container); the rest shows in the status.
    LiveRecorder::check_path(path);
    impl_->pending_recording = path;
    impl_->status.recording_path = path;
    return;
  }
  // Opened now so that a bad path fails here, in the caller's thread, with its message. The
  // acquisition thread writes a block to it under this mutex, so it starts with the next one.
  impl_->recorder = std::make_unique<LiveRecorder>(path, *layout, impl_->published_end,
                                                   impl_->options.recorder_sync_interval);
  if (impl_->last_level) {  // the level running now, from where the recording starts
    const StreamEvent& level = *impl_->last_level;
    const double layout_freq_hz =
        layout->excitation ? layout->excitation->frequency_hz.value_or(0.0) : 0.0;
    impl_->recorder->add_level(
        level.data.value("f0_n", 0.0), level.data.value("frequency_hz", layout_freq_hz), level.t_s,
        level.data.value("steady_from_s", level.t_s),
        level.data.value("steady_to_s", std::numeric_limits<double>::infinity()));
  }
  impl_->status.recording = true;
  impl_->status.recording_path = path;
  impl_->status.recorder_error.clear();
  impl_->events.emplace_back(
      static_cast<double>(impl_->published_end) / std::max(layout->sample_rate_hz, 1.0),
      EventKind::RecordingStarted, path);
  impl_->events.back().wall = utc_now_iso8601();
  impl_->recorder->log(impl_->events.back());
}

void Acquisition::stop_recording() {
  const std::lock_guard lock(impl_->mutex);
  impl_->pending_stop_recording = true;
}

void Acquisition::mark(const std::string& text) {
  const std::lock_guard lock(impl_->mutex);
  impl_->pending_marks.push_back(text);
  impl_->marks_waiting.store(true, std::memory_order_release);
}

AcquisitionStatus Acquisition::status() const {
  AcquisitionStatus s;
  std::vector<double> latencies;
  {
    const std::lock_guard lock(impl_->mutex);
    s = impl_->status;
    latencies = impl_->edc.latencies_s();
  }
  s.queue_fill = impl_->queue ? impl_->queue->size() : 0;
  const SourceCounters c = source_->counters();
  s.overflowed_blocks = c.blocks_overflowed;
  s.network = c.network;
  s.jack = c.jack;
  s.finished = finished();
  if (!latencies.empty()) s.edc_latency_median_s = median(std::move(latencies));
  return s;
}

std::optional<Sidecar> Acquisition::layout() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->layout_copy;
}

std::vector<analysis::LevelResult> Acquisition::levels() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->edc.levels();
}

std::optional<analysis::LevelResult> Acquisition::current_level() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->edc.current_level();
}

std::vector<analysis::CycleFit> Acquisition::cycles_since(std::size_t& next) const {
  const std::lock_guard lock(impl_->mutex);
  const std::deque<analysis::CycleFit>& kept = impl_->edc.cycles();
  const std::size_t count = impl_->edc.cycle_count();
  const std::size_t oldest = count - kept.size();  // index of kept.front()
  const std::size_t from = std::max(next, oldest);
  next = count;
  if (from >= count) return {};
  return {kept.begin() + static_cast<std::ptrdiff_t>(from - oldest), kept.end()};
}

std::vector<StreamEvent> Acquisition::events_since(std::size_t first) const {
  const std::lock_guard lock(impl_->mutex);
  if (first >= impl_->events.size()) return {};
  return {impl_->events.begin() + static_cast<std::ptrdiff_t>(first), impl_->events.end()};
}

void Acquisition::history(double from_s, double to_s, int buckets, TraceHistory& out) const {
  const HistoryRing* ring = impl_->history.load(std::memory_order_acquire);
  if (ring == nullptr) {
    out.clear();
    return;
  }
  ring->read(from_s, to_s, buckets, out);
}

// --- the acquisition thread -----------------------------------------------------------------

bool Acquisition::Impl::setup_layout() {
  const std::optional<Sidecar> known = source->layout();
  if (!known) return false;
  layout = *known;
  rate_hz = layout.sample_rate_hz;
  const int channels = static_cast<int>(layout.channels.size());
  calibration = StreamCalibration(layout);
  const int max_rows = queue->max_rows();
  std::vector<SampleChecker::Channel> checked;
  for (const ChannelInfo& channel : layout.channels) {
    checked.push_back({channel.name, channel.scale, channel.offset, channel.range});
  }
  checker = SampleChecker(std::move(checked), max_rows);
  calibrated = calibration.make_rows(max_rows);
  alarms = AlarmMonitor(options.alarms, rate_hz);
  monitor = std::make_unique<StreamMonitor>(
      options.reorder_window_blocks, max_rows, channels,
      StreamMonitor::Output{[this](const RawBlock& b, std::uint64_t first) { on_block(b, first); },
                            [this](std::uint64_t first, std::uint64_t n) { on_gap(first, n); },
                            [this](EventKind kind, std::uint64_t seq, std::uint64_t first) {
                              on_anomaly(kind, seq, first);
                            }});

  std::string edc_message;
  if (calibration.analysed() && rate_hz > kMaxLiveAnalysisRateHz) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "live analysis off: the stream's %g Hz is above the %g Hz it runs at (the "
                  "recording is analysed offline)",
                  rate_hz, kMaxLiveAnalysisRateHz);
    edc_message = text;
  } else if (calibration.analysed()) {
    // The excitation frequency (0: not known), the option's before the stream's.
    double freq_hz = 0.0;
    if (options.excitation_freq_hz) {
      freq_hz = *options.excitation_freq_hz;
    } else if (layout.excitation && layout.excitation->frequency_hz) {
      freq_hz = *layout.excitation->frequency_hz;
    }
    setup_warnings = calibration.ac_coupling_warnings(freq_hz);
    analysis::StreamSetup stream;
    stream.sample_rate_hz = rate_hz;
    stream.mass_kg = calibration.mass_kg();
    stream.base_quantity = calibration.base().quantity;
    stream.mass_quantity = calibration.mass().quantity;
    stream.mass_is_relative = calibration.mass_relative();
    edc.configure(options.settings, stream, layout.excitation);
    if (freq_hz > 0) {
      edc.start(freq_hz, 0.0);
    } else {
      edc_message = "live EDC off: the stream does not say the excitation frequency";
    }
    if (options.derived_signals) {
      analysis::DerivedSignals::Options o;
      o.sample_rate_hz = rate_hz;
      o.mass_kg = calibration.mass_kg();
      o.base_quantity = calibration.base().quantity;
      o.mass_quantity = calibration.mass().quantity;
      o.mass_is_relative = calibration.mass_relative();
      o.integration_highpass_hz = options.settings.integration_highpass_hz;
      o.derivative_lowpass_hz = options.settings.derivative_lowpass_hz;
      o.latency_s = options.derived_latency_s;
      o.max_rows = max_rows;
      derived = std::make_unique<analysis::DerivedSignals>(o);
      derived_block = derived->make_block();
    }
  } else {
    edc_message =
        "live analysis off: the stream needs a base and a mass (or relative) motion "
        "channel";
  }
  // history_s at the stream's rate, within kMaxHistoryBytes: a stream at 1 MHz (which a sidecar
  // may declare) keeps its last 4.8 s instead of asking for 34 GB.
  const std::size_t history_samples = std::max<std::size_t>(
      16, static_cast<std::size_t>(std::min(
              std::ceil(options.history_s * rate_hz),
              static_cast<double>(kMaxHistoryBytes / (HistoryRing::kTraces * sizeof(double))))));
  history_ring = std::make_unique<HistoryRing>(history_samples, rate_hz);
  history.store(history_ring.get(), std::memory_order_release);

  const std::lock_guard lock(mutex);
  layout_copy = layout;
  status.layout_known = true;
  status.sample_rate_hz = rate_hz;
  status.edc_message = edc_message;
  return true;
}

void Acquisition::Impl::finish_pipeline() {
  if (!edc.running()) return;
  edc.finish();
  const std::lock_guard lock(mutex);
  edc.publish_finished(status);
}

void Acquisition::Impl::log(StreamEvent event) {
  if (event.wall.empty()) event.wall = utc_now_iso8601();
  pending_events.push_back(std::move(event));
}

void Acquisition::Impl::publish_events() {
  for (StreamEvent& event : pending_events) {
    if (recorder) recorder->log(event);
    events.push_back(std::move(event));
  }
  pending_events.clear();
}

void Acquisition::Impl::handle_event(StreamEvent event) {
  const std::lock_guard lock(mutex);  // events are rare: each is published as it comes
  // Whatever the source: an event the analysis cannot trust (a level beyond Nyquist, a time
  // beyond any clock) is logged with why, and neither analysed nor written to the sidecar.
  if (const std::string problem = rate_hz > 0.0 ? stream_event_problem(event, rate_hz) : "";
      !problem.empty()) {
    log({event.t_s, EventKind::Warning, "ignored: " + problem, event.data});
    publish_events();
    return;
  }
  if (event.kind == EventKind::Level && edc.running()) {
    const double f0 = event.data.value("f0_n", 0.0);
    const double freq = event.data.value("frequency_hz", edc.freq_hz());
    const double change_s = event.t_s;
    const double from_s = event.data.value("steady_from_s", change_s);
    const double to_s = event.data.value("steady_to_s", std::numeric_limits<double>::infinity());
    edc.apply_level(f0, freq, change_s, from_s, to_s, status);
    last_level = event;
    if (recorder) recorder->add_level(f0, freq, change_s, from_s, to_s);
  } else if (event.kind == EventKind::Invalid || event.kind == EventKind::Clipped) {
    // A replayed recording's own invalid stretch, or input a source saw clipped before it
    // resampled it: the same treatment as a fault seen here.
    const double from_s = event.data.value("from_s", event.t_s);
    const double to_s = event.data.value("to_s", event.t_s);
    edc.exclude(from_s, to_s);
    if (recorder) {
      recorder->mark_invalid(
          static_cast<std::uint64_t>(std::max(0.0, std::floor(from_s * rate_hz))),
          static_cast<std::uint64_t>(std::max(0.0, std::ceil(to_s * rate_hz))),
          event.kind == EventKind::Clipped ? "clipped" : "replayed");
    }
  } else if (event.kind == EventKind::Discontinuity && std::isfinite(event.t_s)) {
    // The samples on either side of the jump do not belong to one motion.
    const auto at = static_cast<std::uint64_t>(std::max(0.0, std::round(event.t_s * rate_hz)));
    exclude_samples(at > 0 ? at - 1 : 0, at);
    ++status.discontinuities;
  }
  log(std::move(event));
  publish_events();
}

void Acquisition::Impl::handle_events() {
  for (StreamEvent& event : source->take_events()) handle_event(std::move(event));
  if (!marks_waiting.load(std::memory_order_acquire)) return;
  const std::lock_guard lock(mutex);
  for (const std::string& text : pending_marks) log({time_of(next_sample), EventKind::Mark, text});
  pending_marks.clear();
  marks_waiting.store(false, std::memory_order_relaxed);
  publish_events();
}

void Acquisition::Impl::exclude_samples(std::uint64_t from, std::uint64_t to) {
  edc.exclude(time_of(from), time_of(to));
  if (derived) derived->exclude(from, to);
}

void Acquisition::Impl::log_closed_runs() {
  for (const SampleChecker::Run& run : closed_runs) {
    const std::string& name = checker.channels()[static_cast<std::size_t>(run.channel)].name;
    if (recorder) recorder->mark_invalid(run.from, run.to, to_string(run.kind));
    log({time_of(run.from),
         run.kind == BadSampleKind::NonFinite ? EventKind::NonFinite : EventKind::Saturated,
         std::to_string(run.count) + " sample(s) of \"" + name + "\"",
         {{"channel", name},
          {"samples", run.count},
          {"from_s", time_of(run.from)},
          {"to_s", time_of(run.to)}}});
  }
  closed_runs.clear();
}

void Acquisition::Impl::log_alarms() {
  for (AlarmMonitor::Alarm& alarm : raised_alarms) {
    ++status.alarms;
    log({time_of(alarm.sample), EventKind::Alarm, std::move(alarm.text)});
  }
  raised_alarms.clear();
}

void Acquisition::Impl::on_anomaly(EventKind kind, std::uint64_t sequence,
                                   std::uint64_t first_sample) {
  const bool discontinuity = kind == EventKind::Discontinuity;
  if (discontinuity) exclude_samples(first_sample > 0 ? first_sample - 1 : 0, first_sample);
  const std::lock_guard lock(mutex);
  if (discontinuity) ++status.discontinuities;
  log({time_of(first_sample), kind, "block " + std::to_string(sequence), {{"sequence", sequence}}});
  publish_events();
}

void Acquisition::Impl::on_gap(std::uint64_t first_sample, std::uint64_t samples) {
  exclude_samples(first_sample, first_sample + samples - 1);
  // The derived filters run on through the gap on zeros; their output there is left out.
  if (derived) {
    std::vector<double>& base_si = calibrated.base_si;
    std::vector<double>& mass_si = calibrated.mass_si;
    std::fill(base_si.begin(), base_si.end(), 0.0);
    std::fill(mass_si.begin(), mass_si.end(), 0.0);
    const auto max_rows = static_cast<std::uint64_t>(base_si.size());
    for (std::uint64_t s = first_sample; s < first_sample + samples; s += max_rows) {
      const int rows = static_cast<int>(std::min(max_rows, first_sample + samples - s));
      derived->push(s, base_si.data(), mass_si.data(), rows, derived_block);
      HistoryRing::BlockWrite write;
      add_derived(write);
      history_ring->write(write);
    }
  }
  history_ring->write_gap(first_sample, samples);
  next_sample = first_sample + samples;
  const std::lock_guard lock(mutex);
  if (recorder && !recorder->write_gap(samples)) recording_failed();
  published_end = next_sample;
  log({time_of(first_sample),
       EventKind::Gap,
       std::to_string(samples) + " sample(s) never arrived",
       {{"samples", samples},
        {"from_s", time_of(first_sample)},
        {"to_s", time_of(first_sample + samples - 1)}}});
  publish_events();
}

void Acquisition::Impl::on_block(const RawBlock& block, std::uint64_t first_sample) {
  const int rows = block.rows;
  const auto end_sample = first_sample + static_cast<std::uint64_t>(rows);
  // 1. Every sample checked: non-finite and saturated runs per channel, left out everywhere.
  const SampleChecker::Counts bad = checker.check(block, first_sample, closed_runs);
  if (bad.non_finite + bad.saturated > 0) {
    for (int r = 0; r < rows; ++r) {
      if (checker.bad_row(r)) {
        const std::uint64_t sample = first_sample + static_cast<std::uint64_t>(r);
        exclude_samples(sample, sample);
      }
    }
  }
  // 2. Calibrated and analysed.
  const bool analysed = calibration.analysed();
  if (analysed) {
    // Bad samples are excluded above; the calibrated rows hold zeros for them (the display a
    // hole).
    calibration.calibrate(block, calibrated);
    edc.note_arrival(first_sample, end_sample, block.delivered);
    edc.push(first_sample, calibrated.base_si.data(), calibrated.mass_si.data(), rows);
    if (derived) {
      derived->push(first_sample, calibrated.base_si.data(), calibrated.mass_si.data(), rows,
                    derived_block);
    }
    raise_alarms(first_sample, rows);
  }
  next_sample = end_sample;
  // 3. Published once: counts, the recording (exactly as delivered), faults, cycles.
  {
    const std::lock_guard lock(mutex);
    status.non_finite_samples += bad.non_finite;
    status.saturated_samples += bad.saturated;
    if (recorder && !recorder->write(block)) recording_failed();
    log_closed_runs();
    log_alarms();
    status.samples += static_cast<std::uint64_t>(rows);
    ++status.blocks;
    status.stream_time_s = time_of(end_sample);
    published_end = end_sample;
    edc.publish(std::chrono::steady_clock::now(), status);
    copy_monitor_counters();
    publish_recorder_state();
    publish_events();
  }
  // 4. Traces for display, under the ring's own lock.
  HistoryRing::BlockWrite write;
  write.measured_first = first_sample;
  write.measured_count = rows;
  if (analysed) {
    write.base = calibrated.base_shown.data();
    write.mass = calibrated.mass_shown.data();
    write.force_n = calibrated.force_n.data();
  }
  if (analysed && derived) add_derived(write);
  history_ring->write(write);
}

void Acquisition::Impl::add_derived(HistoryRing::BlockWrite& write) const {
  write.derived_first = derived_block.first_sample;
  write.derived_count = derived_block.count;
  write.b_m = derived_block.b_m.data();
  write.z_m = derived_block.z_m.data();
  write.z_dot_m_s = derived_block.z_dot_m_s.data();
  write.restoring_force_n = derived_block.restoring_force_n.data();
}

void Acquisition::Impl::raise_alarms(std::uint64_t first_sample, int rows) {
  // f as it arrives; z and b a filter latency later, with the derived block.
  if (alarms.watches(AlarmQuantity::Force)) {
    for (int r = 0; r < rows; ++r) {
      alarms.check(AlarmQuantity::Force, first_sample + static_cast<std::uint64_t>(r),
                   calibrated.force_n[static_cast<std::size_t>(r)], raised_alarms);
    }
  }
  if (derived) {
    for (int r = 0; r < derived_block.count; ++r) {
      const std::uint64_t at = derived_block.first_sample + static_cast<std::uint64_t>(r);
      const auto i = static_cast<std::size_t>(r);
      alarms.check(AlarmQuantity::RelativeDisplacement, at, derived_block.z_m[i], raised_alarms);
      alarms.check(AlarmQuantity::BaseDisplacement, at, derived_block.b_m[i], raised_alarms);
    }
  }
}

void Acquisition::Impl::copy_monitor_counters() {
  if (!monitor) return;
  const StreamMonitor::Counters& c = monitor->counters();
  status.gaps = c.gaps;
  status.gap_samples = c.gap_samples;
  status.lost_blocks = c.lost_blocks;
  status.duplicates = c.duplicates;
  status.reordered = c.reordered;
  status.late = c.late;
}

void Acquisition::Impl::open_pending_recording() {
  const std::lock_guard lock(mutex);
  if (pending_recording.empty() || !layout_copy) return;
  const std::string path = std::exchange(pending_recording, std::string());
  try {
    recorder = std::make_unique<LiveRecorder>(path, *layout_copy, published_end,
                                              options.recorder_sync_interval);
    status.recording = true;
    StreamEvent started(time_of(published_end), EventKind::RecordingStarted, path);
    started.wall = utc_now_iso8601();
    recorder->log(started);
    events.push_back(started);
  } catch (const InputError& error) {
    status.recorder_error = error.what();
    StreamEvent failed(time_of(published_end), EventKind::Error, error.what());
    failed.wall = utc_now_iso8601();
    events.push_back(failed);
  }
}

void Acquisition::Impl::recording_failed() {
  // The recording stops there (a full disk, a failing write); the stream goes on. Said once, as
  // an error event, and the recording closed at once with what was written whole.
  if (!status.recorder_error.empty()) return;
  status.recorder_error = recorder->error();
  log({time_of(next_sample), EventKind::Error, "recording stopped: " + recorder->error()});
  publish_events();  // into the event log too, while it is open (a few hundred bytes may fit)
  pending_stop_recording = true;
}

void Acquisition::Impl::publish_recorder_state() {
  if (recorder) recorder->maybe_write_sidecar();
  if (pending_stop_recording) {
    pending_stop_recording = false;
    if (recorder) {
      StreamEvent stopped(time_of(next_sample), EventKind::RecordingStopped, recorder->path());
      stopped.wall = utc_now_iso8601();
      recorder->log(stopped);
      recorder->close();
      if (!recorder->error().empty()) status.recorder_error = recorder->error();
      status.recorded_samples = recorder->samples_written();
      events.push_back(stopped);
      recorder.reset();
      status.recording = false;
    }
  }
  if (recorder) status.recorded_samples = recorder->samples_written();
}

void Acquisition::Impl::apply_recording_requests() {
  const std::lock_guard lock(mutex);
  publish_recorder_state();
}

void Acquisition::Impl::run(Acquisition& owner) {
  // Events wait in the source until the layout is set up: a network sender's first levels come
  // right after its HELLO and must reach the pipeline and the recording.
  while (!stop.load() && !setup_layout()) {
    if (source->finished()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  open_pending_recording();
  bool layout_known = false;
  {
    const std::lock_guard lock(mutex);
    layout_known = status.layout_known;
    log({0.0, EventKind::Start, source->describe()});
    for (const std::string& warning : setup_warnings) log({0.0, EventKind::Warning, warning});
    publish_events();
  }
  bool source_done = false;
  while (layout_known) {
    // The block first, then the events: a source posts an event before it publishes the block
    // that reaches the event's time, so every event up to this block's end is visible now.
    RawBlock* block = queue->front();
    handle_events();
    if (block == nullptr) {
      if (source_done) break;
      if (source->finished() || stop.load()) {
        source_done = true;  // one more look: the source may have delivered before ending
        handle_events();
        continue;
      }
      apply_recording_requests();
      std::this_thread::sleep_for(kIdleWait);
      continue;
    }
    monitor->push(*block);  // on_block, on_gap, on_anomaly: each publishes what it found
    queue->pop();
  }
  if (monitor) monitor->flush();
  checker.finish(closed_runs);
  handle_events();
  finish_pipeline();
  const std::lock_guard lock(mutex);
  log_closed_runs();
  log({time_of(next_sample), EventKind::Stop, source->describe()});
  copy_monitor_counters();
  pending_stop_recording = true;
  publish_events();
  publish_recorder_state();
  status.running = false;
  owner.finished_.store(true, std::memory_order_release);
}

}  // namespace oscilab::daq
