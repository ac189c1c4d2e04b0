#include "daq/live/acquisition.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <utility>

#include "analysis/common/input_error.h"
#include "analysis/pipeline/measurement_pipeline.h"
#include "analysis/signal/ac_coupling.h"
#include "analysis/signal/streaming_integrator.h"
#include "daq/live/live_recorder.h"
#include "daq/live/stream_monitor.h"

namespace oscilab::daq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kMaxLatencies = 10000;
constexpr auto kIdleWait = std::chrono::milliseconds(2);  // queue empty: look again after this
constexpr double kAcCouplingWarnFactor = 10.0;  // warn when f < this × the AC-coupling corner

analysis::MotionQuantity motion_quantity(Quantity quantity) {
  switch (quantity) {
    case Quantity::Velocity:
      return analysis::MotionQuantity::Velocity;
    case Quantity::Acceleration:
      return analysis::MotionQuantity::Acceleration;
    default:
      return analysis::MotionQuantity::Displacement;
  }
}

// physical (SI) = (scale × stored + offset) × unit factor; saturated when scale × stored +
// offset reaches the channel's range (in its unit).
struct ChannelCalibration {
  int index = -1;
  double scale = 1.0, offset = 0.0, factor = 1.0;
  std::optional<std::pair<double, double>> range;
  analysis::MotionQuantity quantity = analysis::MotionQuantity::Acceleration;
};

ChannelCalibration calibration_of(const Sidecar& layout, int index) {
  ChannelCalibration c;
  c.index = index;
  const ChannelInfo& channel = layout.channels[static_cast<std::size_t>(index)];
  c.scale = channel.scale;
  c.offset = channel.offset;
  c.factor = unit_to_si(channel.unit, channel.quantity, "stream channel \"" + channel.name + "\"");
  c.range = channel.range;
  c.quantity = motion_quantity(channel.quantity);
  return c;
}

// Per-channel run of bad samples (non-finite or saturated) being tracked across blocks.
struct BadRun {
  bool open = false;
  std::uint64_t from = 0, to = 0, count = 0;
};

// A ring of the last minutes of traces, indexed by stream sample.
struct HistoryRing {
  std::size_t capacity = 0;
  std::uint64_t end = 0;          // one past the newest measured sample
  std::uint64_t derived_end = 0;  // one past the newest derived sample
  std::vector<double> base, mass, force, b, z, z_dot, r;
  void resize(std::size_t n) {
    capacity = n;
    for (auto* v : {&base, &mass, &force, &b, &z, &z_dot, &r}) v->assign(n, kNaN);
  }
  std::size_t slot(std::uint64_t sample) const {
    return static_cast<std::size_t>(sample % capacity);
  }
};

struct BlockArrival {
  std::uint64_t first_sample = 0, end_sample = 0;
  std::chrono::steady_clock::time_point delivered;
};

}  // namespace

void TraceHistory::clear() {
  for (auto* v : {&t_s, &base, &mass, &force_n, &b_m, &z_m, &z_dot_m_s, &restoring_force_n}) {
    v->clear();
  }
}

struct Acquisition::Impl {
  AcquisitionOptions options;
  SampleSource* source = nullptr;
  std::unique_ptr<BlockQueue> queue;
  std::thread thread;
  std::atomic<bool> stop{false};

  // --- owned by the acquisition thread ---
  Sidecar layout;
  double rate_hz = 0.0;
  double mass_kg = 1.0;
  int channels = 0;
  ChannelCalibration base_cal, mass_cal;
  bool mass_relative = false;
  std::vector<ChannelCalibration> all_cal;  // every channel, for the saturation check
  std::unique_ptr<StreamMonitor> monitor;
  std::unique_ptr<analysis::MeasurementPipeline> pipeline;
  double pipeline_freq_hz = 0.0;
  std::size_t pipeline_cycles_seen = 0;
  std::vector<double> base_si, mass_si;  // one block, calibrated
  // The AC-coupling high-pass of a channel, undone after calibration (sidecar ac_coupling_hz).
  std::optional<analysis::AcCouplingInverse> base_ac, mass_ac;
  std::vector<std::string> setup_warnings;  // logged once the chain starts
  std::vector<BadRun> non_finite_runs, saturated_runs;
  // b, ḃ, ẏ, ÿ, y from the calibrated channels; null where the channel is that quantity already.
  std::vector<std::unique_ptr<analysis::StreamingIntegrator>> filters;
  int filter_latency = 0;
  bool fault_seen = false;
  std::uint64_t last_fault = 0;  // newest sample excluded (derived traces near it are left out)
  std::deque<BlockArrival> arrivals;
  std::uint64_t next_sample = 0;
  bool alarm_armed[3] = {true, true, true};
  std::uint64_t below_limit_samples[3] = {0, 0, 0};

  // --- shared, under mutex ---
  mutable std::mutex mutex;
  AcquisitionStatus status;
  std::optional<Sidecar> layout_copy;
  std::vector<analysis::LevelResult> levels_done;  // of pipelines already finished
  std::vector<analysis::LevelResult> levels;       // levels_done + the current pipeline's
  std::optional<analysis::LevelResult> current_level;
  std::vector<analysis::CycleFit> cycles;
  std::vector<StreamEvent> events;
  HistoryRing history;
  std::unique_ptr<LiveRecorder> recorder;
  std::string pending_recording;  // start at the next block
  bool pending_stop_recording = false;
  std::vector<std::string> pending_marks;
  std::optional<StreamEvent> last_level;
  std::vector<double> latencies_s;  // per cycle, the last kMaxLatencies  // the excitation now, for
                                    // a recording started later

  void run(Acquisition& owner);
  bool setup_layout();
  void make_pipeline(double freq_hz, double t0_s);
  void finish_pipeline();
  void handle_events();
  void handle_event(StreamEvent event);
  void log(StreamEvent event);  // mutex held by caller? no: takes it
  void on_block(const RawBlock& block, std::uint64_t first_sample);
  void on_gap(std::uint64_t first_sample, std::uint64_t samples);
  void on_anomaly(const char* kind, std::uint64_t sequence, std::uint64_t first_sample);
  void close_bad_run(BadRun& run, const char* kind, int channel);
  void exclude_samples(std::uint64_t from, std::uint64_t to);
  void push_filters(const double* inputs, std::uint64_t sample);
  void derive(std::uint64_t sample, const double* filtered);
  void check_alarms(std::uint64_t sample, double z, double b, double f);
  void collect_cycles();
  void apply_recording_requests();
  void open_pending_recording();  // a recording asked for before the layout was known
  void copy_monitor_counters();   // StreamMonitor's counts into the status, per block
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
  // Open now so that a bad path fails here, in the caller's thread, with its message.
  impl_->recorder = std::make_unique<LiveRecorder>(path, *layout, impl_->history.end,
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
      static_cast<double>(impl_->history.end) / std::max(impl_->rate_hz, 1.0), "recording-started",
      path);
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
}

AcquisitionStatus Acquisition::status() const {
  const std::lock_guard lock(impl_->mutex);
  AcquisitionStatus s = impl_->status;
  s.queue_fill = impl_->queue ? impl_->queue->size() : 0;
  const SourceCounters c = source_->counters();
  s.overflowed_blocks = c.blocks_overflowed;
  s.malformed_frames = c.malformed_frames;
  s.layout_mismatches = c.layout_mismatches;
  s.connections = c.connections;
  s.xruns = c.xruns;
  s.server_losses = c.server_losses;
  s.port_disconnections = c.port_disconnections;
  s.rate_changes = c.rate_changes;
  s.dropped_frames = c.dropped_frames;
  s.clipped_samples = c.clipped_samples;
  s.reconnections = c.reconnections;
  s.finished = finished();
  if (!impl_->latencies_s.empty()) {
    std::vector<double> sorted = impl_->latencies_s;
    const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
    std::nth_element(sorted.begin(), mid, sorted.end());
    s.edc_latency_median_s = *mid;
  }
  return s;
}

std::optional<Sidecar> Acquisition::layout() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->layout_copy;
}

std::vector<analysis::LevelResult> Acquisition::levels() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->levels;
}

std::optional<analysis::LevelResult> Acquisition::current_level() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->current_level;
}

std::vector<analysis::CycleFit> Acquisition::cycles_since(std::size_t first) const {
  const std::lock_guard lock(impl_->mutex);
  if (first >= impl_->cycles.size()) return {};
  return {impl_->cycles.begin() + static_cast<std::ptrdiff_t>(first), impl_->cycles.end()};
}

std::vector<StreamEvent> Acquisition::events_since(std::size_t first) const {
  const std::lock_guard lock(impl_->mutex);
  if (first >= impl_->events.size()) return {};
  return {impl_->events.begin() + static_cast<std::ptrdiff_t>(first), impl_->events.end()};
}

void Acquisition::history(double from_s, double to_s, int buckets, TraceHistory& out) const {
  out.clear();
  const std::lock_guard lock(impl_->mutex);
  const HistoryRing& h = impl_->history;
  const double rate = impl_->rate_hz;
  if (h.capacity == 0 || h.end == 0 || !(rate > 0) || buckets < 1 || !(to_s > from_s)) return;
  const std::uint64_t oldest = h.end > h.capacity ? h.end - h.capacity : 0;
  const auto clamp_sample = [&](double t) {
    const double s = std::floor(t * rate);
    if (s <= static_cast<double>(oldest)) return oldest;
    if (s >= static_cast<double>(h.end)) return h.end;
    return static_cast<std::uint64_t>(s);
  };
  const std::uint64_t first = clamp_sample(from_s), last = clamp_sample(to_s);
  if (last <= first) return;
  const std::uint64_t span = last - first;
  const std::uint64_t per_bucket = std::max<std::uint64_t>(1, (span + buckets - 1) / buckets);
  const std::vector<double>* sources[] = {&h.base, &h.mass, &h.force, &h.b, &h.z, &h.z_dot, &h.r};
  std::vector<double>* targets[] = {&out.base, &out.mass,      &out.force_n,          &out.b_m,
                                    &out.z_m,  &out.z_dot_m_s, &out.restoring_force_n};
  for (std::uint64_t start = first; start < last; start += per_bucket) {
    const std::uint64_t end = std::min(last, start + per_bucket);
    if (per_bucket == 1) {
      out.t_s.push_back(static_cast<double>(start) / rate);
      for (int k = 0; k < 7; ++k) targets[k]->push_back((*sources[k])[h.slot(start)]);
      continue;
    }
    // Envelope: the min and the max of the bucket, in the order they occur.
    out.t_s.push_back(static_cast<double>(start) / rate);
    out.t_s.push_back(static_cast<double>(end - 1) / rate);
    for (int k = 0; k < 7; ++k) {
      double lo = kNaN, hi = kNaN;
      std::uint64_t lo_at = start, hi_at = start;
      for (std::uint64_t s = start; s < end; ++s) {
        const double v = (*sources[k])[h.slot(s)];
        if (!std::isfinite(v)) continue;
        if (!(v >= lo)) lo = v, lo_at = s;
        if (!(v <= hi)) hi = v, hi_at = s;
      }
      targets[k]->push_back(lo_at <= hi_at ? lo : hi);
      targets[k]->push_back(lo_at <= hi_at ? hi : lo);
    }
  }
}

// --- the acquisition thread -----------------------------------------------------------------

bool Acquisition::Impl::setup_layout() {
  const std::optional<Sidecar> known = source->layout();
  if (!known) return false;
  layout = *known;
  rate_hz = layout.sample_rate_hz;
  mass_kg = layout.mass_kg.value_or(1.0);
  channels = static_cast<int>(layout.channels.size());
  int base = -1, mass = -1, relative = -1;
  for (int i = 0; i < channels; ++i) {
    const ChannelRole role = layout.channels[static_cast<std::size_t>(i)].role;
    if (role == ChannelRole::Base && base < 0) base = i;
    if (role == ChannelRole::Mass && mass < 0) mass = i;
    if (role == ChannelRole::Relative && relative < 0) relative = i;
  }
  mass_relative = mass < 0;
  if (mass < 0) mass = relative;
  for (int i = 0; i < channels; ++i) all_cal.push_back(calibration_of(layout, i));
  non_finite_runs.assign(static_cast<std::size_t>(channels), {});
  saturated_runs.assign(static_cast<std::size_t>(channels), {});
  const int max_rows = queue->max_rows();
  base_si.assign(static_cast<std::size_t>(max_rows), 0.0);
  mass_si.assign(static_cast<std::size_t>(max_rows), 0.0);
  monitor = std::make_unique<StreamMonitor>(
      options.reorder_window_blocks, max_rows, channels,
      StreamMonitor::Output{[this](const RawBlock& b, std::uint64_t first) { on_block(b, first); },
                            [this](std::uint64_t first, std::uint64_t n) { on_gap(first, n); },
                            [this](const char* kind, std::uint64_t seq, std::uint64_t first) {
                              on_anomaly(kind, seq, first);
                            }});

  std::string edc_message;
  const bool motion_ok =
      base >= 0 && mass >= 0 &&
      layout.channels[static_cast<std::size_t>(base)].quantity != Quantity::Force &&
      layout.channels[static_cast<std::size_t>(mass)].quantity != Quantity::Force;
  if (motion_ok) {
    base_cal = all_cal[static_cast<std::size_t>(base)];
    mass_cal = all_cal[static_cast<std::size_t>(mass)];
    // The excitation frequency (0: not known), the option's before the stream's.
    double freq_hz = 0.0;
    if (options.excitation_freq_hz) {
      freq_hz = *options.excitation_freq_hz;
    } else if (layout.excitation && layout.excitation->frequency_hz) {
      freq_hz = *layout.excitation->frequency_hz;
    }
    for (const auto& [cal, inverse] :
         {std::pair{&base_cal, &base_ac}, std::pair{&mass_cal, &mass_ac}}) {
      const ChannelInfo& channel = layout.channels[static_cast<std::size_t>(cal->index)];
      if (!channel.ac_coupling_hz) continue;
      inverse->emplace(*channel.ac_coupling_hz, rate_hz, "stream channel \"" + channel.name + "\"");
      // A first-order high-pass leads by atan(fc / f): 0.0997 rad at f = 10 fc. Corrected, a
      // corner known to ±10 % still leaves up to 0.01 rad there, a large error in the loop's
      // area, so an excitation within 10× of the corner is worth a warning (docs/live.md).
      if (freq_hz > 0 && freq_hz < kAcCouplingWarnFactor * *channel.ac_coupling_hz) {
        setup_warnings.push_back(
            "channel \"" + channel.name + "\": the excitation " + std::to_string(freq_hz) +
            " Hz is within " + std::to_string(static_cast<int>(kAcCouplingWarnFactor)) +
            "x of its AC-coupling corner " + std::to_string(*channel.ac_coupling_hz) +
            " Hz; its phase is corrected, but the EDC now depends on how well the corner is "
            "known: a DC-coupled input is better");
      }
    }
    if (freq_hz > 0) {
      make_pipeline(freq_hz, 0.0);
    } else {
      edc_message = "live EDC off: the stream does not say the excitation frequency";
    }
    if (options.derived_signals) {
      const int d_base = analysis::derivative_order(base_cal.quantity);
      const int d_mass = analysis::derivative_order(mass_cal.quantity);
      const auto filter = [&](int order) -> std::unique_ptr<analysis::StreamingIntegrator> {
        if (order == 0) return nullptr;  // the delayed sample itself
        analysis::StreamingIntegrator::Options o;
        o.sample_rate_hz = rate_hz;
        o.order = order;
        o.highpass_hz = order < 0 ? options.settings.integration_highpass_hz : 0.0;
        o.lowpass_hz = std::min(options.settings.derivative_lowpass_hz, 0.45 * rate_hz);
        o.latency_s = options.derived_latency_s;
        return std::make_unique<analysis::StreamingIntegrator>(o);
      };
      filters.push_back(filter(-d_base));     // b
      filters.push_back(filter(1 - d_base));  // ḃ
      filters.push_back(filter(1 - d_mass));  // ẏ (or ż)
      filters.push_back(filter(2 - d_mass));  // ÿ (or z̈)
      filters.push_back(filter(-d_mass));     // y (or z)
      // Every filter has the same latency; the delayed raw samples are read that far back.
      for (const auto& f : filters) {
        if (f) filter_latency = f->latency_samples();
      }
    }
  } else {
    edc_message =
        "live analysis off: the stream needs a base and a mass (or relative) motion "
        "channel";
  }
  const std::size_t history_samples =
      std::max<std::size_t>(16, static_cast<std::size_t>(std::ceil(options.history_s * rate_hz)));

  const std::lock_guard lock(mutex);
  layout_copy = layout;
  history.resize(history_samples);
  status.layout_known = true;
  status.sample_rate_hz = rate_hz;
  status.edc_message = edc_message;
  return true;
}

void Acquisition::Impl::make_pipeline(double freq_hz, double t0_s) {
  analysis::StreamSetup setup;
  setup.sample_rate_hz = rate_hz;
  setup.mass_kg = mass_kg;
  setup.base_quantity = base_cal.quantity;
  setup.mass_quantity = mass_cal.quantity;
  setup.mass_is_relative = mass_relative;
  setup.excitation_freq_hz = freq_hz;
  setup.t0_s = t0_s;
  // An excitation built in code may leave `extra` null rather than an object.
  setup.windowed_levels = layout.excitation && layout.excitation->extra.is_object() &&
                          layout.excitation->extra.value("levels_live", false);
  if (layout.excitation) {  // levels the stream's sidecar gives up front, in stream time
    for (const ExcitationLevel& level : layout.excitation->levels) {
      if (level.end_s > t0_s)
        setup.level_windows.push_back({level.start_s, level.end_s, level.f0_n});
    }
  }
  pipeline = std::make_unique<analysis::MeasurementPipeline>(options.settings, setup);
  pipeline_freq_hz = freq_hz;
  pipeline_cycles_seen = 0;
}

void Acquisition::Impl::finish_pipeline() {
  if (!pipeline) return;
  pipeline->finish();
  collect_cycles();
  const std::lock_guard lock(mutex);
  levels_done.insert(levels_done.end(), pipeline->levels().begin(), pipeline->levels().end());
  levels = levels_done;
  current_level.reset();
}

void Acquisition::Impl::log(StreamEvent event) {
  if (event.wall.empty()) event.wall = utc_now_iso8601();
  const std::lock_guard lock(mutex);
  if (recorder) recorder->log(event);
  events.push_back(std::move(event));
}

void Acquisition::Impl::handle_event(StreamEvent event) {
  if (event.kind == "level" && pipeline) {
    const double f0 = event.data.value("f0_n", 0.0);
    const double freq = event.data.value("frequency_hz", pipeline_freq_hz);
    const double change_s = event.t_s;
    const double from_s = event.data.value("steady_from_s", change_s);
    const double to_s = event.data.value("steady_to_s", std::numeric_limits<double>::infinity());
    if (std::abs(freq - pipeline_freq_hz) > 1e-9 * pipeline_freq_hz) {
      // A new frequency: a new cycle grid, from the change on.
      finish_pipeline();
      make_pipeline(freq, change_s);
    }
    // f0 = 0 is the table at rest: it ends the level before it and starts none.
    pipeline->end_level_window(change_s);
    if (f0 > 0) pipeline->add_level_window({from_s, to_s, f0});
    const std::lock_guard lock(mutex);
    last_level = event;
    if (recorder) recorder->add_level(f0, freq, change_s, from_s, to_s);
  } else if (event.kind == "invalid" || event.kind == "clipped") {
    // A replayed recording's own invalid stretch, or input a source saw clipped before it
    // resampled it: the same treatment as a fault seen here.
    const double from_s = event.data.value("from_s", event.t_s);
    const double to_s = event.data.value("to_s", event.t_s);
    if (pipeline) pipeline->exclude(from_s, to_s);
    const std::lock_guard lock(mutex);
    if (recorder) {
      recorder->mark_invalid(
          static_cast<std::uint64_t>(std::max(0.0, std::floor(from_s * rate_hz))),
          static_cast<std::uint64_t>(std::max(0.0, std::ceil(to_s * rate_hz))),
          event.kind == "clipped" ? "clipped" : "replayed");
    }
  } else if (event.kind == "discontinuity" && std::isfinite(event.t_s)) {
    // The samples on either side of the jump do not belong to one motion.
    const auto at = static_cast<std::uint64_t>(std::max(0.0, std::round(event.t_s * rate_hz)));
    exclude_samples(at > 0 ? at - 1 : 0, at);
    const std::lock_guard lock(mutex);
    ++status.discontinuities;
  }
  log(std::move(event));
}

void Acquisition::Impl::handle_events() {
  for (StreamEvent& event : source->take_events()) handle_event(std::move(event));
  std::vector<std::string> marks;
  {
    const std::lock_guard lock(mutex);
    marks.swap(pending_marks);
  }
  for (const std::string& text : marks) log({time_of(next_sample), "mark", text});
}

void Acquisition::Impl::exclude_samples(std::uint64_t from, std::uint64_t to) {
  if (pipeline) pipeline->exclude(time_of(from), time_of(to));
  last_fault = fault_seen ? std::max(last_fault, to) : to;
  fault_seen = true;
}

void Acquisition::Impl::close_bad_run(BadRun& run, const char* kind, int channel) {
  if (!run.open) return;
  run.open = false;
  const std::string name = layout.channels[static_cast<std::size_t>(channel)].name;
  {
    const std::lock_guard lock(mutex);
    if (recorder) recorder->mark_invalid(run.from, run.to, kind);
  }
  log({time_of(run.from),
       kind,
       std::to_string(run.count) + " sample(s) of \"" + name + "\"",
       {{"channel", name},
        {"samples", run.count},
        {"from_s", time_of(run.from)},
        {"to_s", time_of(run.to)}}});
  run.count = 0;
}

void Acquisition::Impl::on_anomaly(const char* kind, std::uint64_t sequence,
                                   std::uint64_t first_sample) {
  if (std::string(kind) == "discontinuity")
    exclude_samples(first_sample > 0 ? first_sample - 1 : 0, first_sample);
  {
    const std::lock_guard lock(mutex);
    if (std::string(kind) == "discontinuity") ++status.discontinuities;
  }
  log({time_of(first_sample), kind, "block " + std::to_string(sequence), {{"sequence", sequence}}});
}

void Acquisition::Impl::on_gap(std::uint64_t first_sample, std::uint64_t samples) {
  exclude_samples(first_sample, first_sample + samples - 1);
  {
    const std::lock_guard lock(mutex);
    if (recorder && !recorder->write_gap(samples)) status.recorder_error = recorder->error();
    for (std::uint64_t s = first_sample; s < first_sample + samples; ++s) {
      if (s + history.capacity < first_sample + samples) continue;  // older than the ring
      const std::size_t i = history.slot(s);
      for (auto* v : {&history.base, &history.mass, &history.force, &history.b, &history.z,
                      &history.z_dot, &history.r}) {
        (*v)[i] = kNaN;
      }
    }
    history.end = first_sample + samples;
  }
  // The derived filters run on through the gap on zeros; their output there is left out.
  if (!filters.empty()) {
    const double zeros[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
    for (std::uint64_t s = first_sample; s < first_sample + samples; ++s) push_filters(zeros, s);
  }
  next_sample = first_sample + samples;
  log({time_of(first_sample),
       "gap",
       std::to_string(samples) + " sample(s) never arrived",
       {{"samples", samples},
        {"from_s", time_of(first_sample)},
        {"to_s", time_of(first_sample + samples - 1)}}});
}

void Acquisition::Impl::on_block(const RawBlock& block, std::uint64_t first_sample) {
  const int rows = block.rows;
  // 1. Every sample checked: non-finite and saturated runs per channel, left out everywhere.
  for (int r = 0; r < rows; ++r) {
    const std::uint64_t sample = first_sample + static_cast<std::uint64_t>(r);
    bool row_bad = false;
    for (int c = 0; c < channels; ++c) {
      const double v = block.value(r, c);
      const ChannelCalibration& cal = all_cal[static_cast<std::size_t>(c)];
      const bool finite = std::isfinite(v);
      const double physical = cal.scale * v + cal.offset;
      const bool saturated =
          finite && cal.range && (physical <= cal.range->first || physical >= cal.range->second);
      for (auto [bad, run, kind] :
           {std::tuple{!finite, &non_finite_runs[static_cast<std::size_t>(c)], "non-finite"},
            std::tuple{saturated, &saturated_runs[static_cast<std::size_t>(c)], "saturated"}}) {
        if (bad) {
          if (!run->open) run->open = true, run->from = sample;
          run->to = sample;
          ++run->count;
          row_bad = true;
        } else if (run->open) {
          close_bad_run(*run, kind, c);
        }
      }
      if (!finite || saturated) {
        const std::lock_guard lock(mutex);
        ++(finite ? status.saturated_samples : status.non_finite_samples);
      }
    }
    if (row_bad) exclude_samples(sample, sample);
  }
  // 2. Recorded exactly as delivered.
  {
    const std::lock_guard lock(mutex);
    if (recorder && !recorder->write(block)) status.recorder_error = recorder->error();
  }
  // 3. Calibrated and analysed.
  const bool analysed = base_cal.index >= 0 && mass_cal.index >= 0;
  if (analysed) {
    for (int r = 0; r < rows; ++r) {
      const double b = block.value(r, base_cal.index), y = block.value(r, mass_cal.index);
      double b_si = (base_cal.scale * b + base_cal.offset) * base_cal.factor;
      double y_si = (mass_cal.scale * y + mass_cal.offset) * mass_cal.factor;
      if (base_ac) b_si = base_ac->push(b_si);
      if (mass_ac) y_si = mass_ac->push(y_si);
      // Bad samples are excluded above; zeros keep the filters and fits finite meanwhile.
      base_si[static_cast<std::size_t>(r)] = std::isfinite(b_si) ? b_si : 0.0;
      mass_si[static_cast<std::size_t>(r)] = std::isfinite(y_si) ? y_si : 0.0;
    }
    arrivals.push_back(
        {first_sample, first_sample + static_cast<std::uint64_t>(rows), block.delivered});
    while (arrivals.size() > 512) arrivals.pop_front();
    if (pipeline) {
      pipeline->push(static_cast<std::int64_t>(first_sample), base_si.data(), mass_si.data(), rows);
      collect_cycles();
    }
  }
  // 4. Traces for display.
  {
    const std::lock_guard lock(mutex);
    for (int r = 0; r < rows; ++r) {
      const std::size_t i = history.slot(first_sample + static_cast<std::uint64_t>(r));
      const bool ok = analysed;
      const double raw_b = ok ? block.value(r, base_cal.index) : kNaN;
      const double raw_y = ok ? block.value(r, mass_cal.index) : kNaN;
      history.base[i] = ok && std::isfinite(raw_b) ? base_si[static_cast<std::size_t>(r)] : kNaN;
      history.mass[i] = ok && std::isfinite(raw_y) ? mass_si[static_cast<std::size_t>(r)] : kNaN;
      history.force[i] = base_cal.quantity == analysis::MotionQuantity::Acceleration
                             ? -mass_kg * history.base[i]
                             : kNaN;
      history.b[i] = history.z[i] = history.z_dot[i] = history.r[i] = kNaN;
    }
    history.end = first_sample + static_cast<std::uint64_t>(rows);
    status.samples += static_cast<std::uint64_t>(rows);
    ++status.blocks;
    status.stream_time_s = time_of(history.end);
  }
  if (analysed && !filters.empty()) {
    for (int r = 0; r < rows; ++r) {
      const double inputs[5] = {
          base_si[static_cast<std::size_t>(r)], base_si[static_cast<std::size_t>(r)],
          mass_si[static_cast<std::size_t>(r)], mass_si[static_cast<std::size_t>(r)],
          mass_si[static_cast<std::size_t>(r)]};
      push_filters(inputs, first_sample + static_cast<std::uint64_t>(r));
    }
  }
  next_sample = first_sample + static_cast<std::uint64_t>(rows);
}

// The derived traces at sample − latency, from the filter outputs just computed with `sample`
// (NaN for a filter the channel needs none for: its delayed sample is read from the ring).
void Acquisition::Impl::derive(std::uint64_t sample, const double* filtered) {
  const auto latency = static_cast<std::uint64_t>(filter_latency);
  if (filters.empty() || sample < latency) return;
  const std::uint64_t at = sample - latency;
  double z = kNaN, b = kNaN, f = kNaN;
  {
    const std::lock_guard lock(mutex);
    if (at + history.capacity < history.end) return;  // already out of the ring
    const std::size_t i = history.slot(at);
    const auto pick = [&](int k, const std::vector<double>& delayed) {
      return filters[static_cast<std::size_t>(k)] ? filtered[k] : delayed[i];
    };
    // A filter spans ±latency: near a fault (or before it is full) its output is left out.
    const bool ready =
        std::all_of(filters.begin(), filters.end(), [](const auto& x) { return !x || x->ready(); });
    const bool trusted = ready && (!fault_seen || sample > last_fault + 2 * latency);
    b = trusted ? pick(0, history.base) : kNaN;
    const double b_dot = trusted ? pick(1, history.base) : kNaN;
    const double y = trusted ? pick(4, history.mass) : kNaN;
    const double y_dot = trusted ? pick(2, history.mass) : kNaN;
    const double y_ddot = trusted ? pick(3, history.mass) : kNaN;
    f = history.force[i];
    if (mass_relative) {  // the mass channel measures z itself: R = f − m z̈
      z = y;
      history.z_dot[i] = y_dot;
      history.r[i] = f - mass_kg * y_ddot;
    } else {  // z = y − b, ż = ẏ − ḃ, R = f − m z̈ = −m ÿ (eq. (1))
      z = y - b;
      history.z_dot[i] = y_dot - b_dot;
      history.r[i] = -mass_kg * y_ddot;
    }
    history.b[i] = b;
    history.z[i] = z;
    history.derived_end = at + 1;
  }
  check_alarms(at, z, b, f);
}

void Acquisition::Impl::push_filters(const double* inputs, std::uint64_t sample) {
  double filtered[5];
  for (std::size_t k = 0; k < filters.size(); ++k) {
    filtered[k] = filters[k] ? filters[k]->push(inputs[k]) : kNaN;
  }
  derive(sample, filtered);
}

void Acquisition::Impl::check_alarms(std::uint64_t sample, double z, double b, double f) {
  const AlarmLimits& limits = options.alarms;
  const std::optional<double> limit[3] = {limits.max_abs_z_m, limits.max_abs_base_m,
                                          limits.max_abs_force_n};
  const double value[3] = {z, b, f};
  const char* what[3] = {"|z|", "|b| (integration drift)", "|f|"};
  for (int k = 0; k < 3; ++k) {
    if (!limit[k] || !std::isfinite(value[k])) continue;
    if (alarm_armed[k] && std::abs(value[k]) > *limit[k]) {
      alarm_armed[k] = false;
      below_limit_samples[k] = 0;
      {
        const std::lock_guard lock(mutex);
        ++status.alarms;
      }
      log({time_of(sample), "alarm",
           std::string(what[k]) + " = " + std::to_string(std::abs(value[k])) + " exceeds " +
               std::to_string(*limit[k])});
    } else if (!alarm_armed[k]) {
      // Re-armed once the value has stayed well below the limit for a second: a quantity that
      // swings through zero every cycle (f, b) raises one alarm per excursion, not per cycle.
      if (std::abs(value[k]) < 0.9 * *limit[k]) {
        if (++below_limit_samples[k] >= static_cast<std::uint64_t>(rate_hz)) alarm_armed[k] = true;
      } else {
        below_limit_samples[k] = 0;
      }
    }
  }
}

void Acquisition::Impl::collect_cycles() {
  const auto& all = pipeline->cycles();
  if (all.size() == pipeline_cycles_seen && !pipeline->levels().empty() &&
      levels.size() == levels_done.size() + pipeline->levels().size()) {
    const std::lock_guard lock(mutex);
    current_level = pipeline->current_level();
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  double latency_s = -1.0;
  const std::lock_guard lock(mutex);
  for (std::size_t k = pipeline_cycles_seen; k < all.size(); ++k) {
    const auto start = static_cast<std::uint64_t>(std::ceil(all[k].start_s * rate_hz - 1e-9));
    for (const BlockArrival& a : arrivals) {
      if (start >= a.first_sample && start < a.end_sample) {
        latency_s = std::chrono::duration<double>(now - a.delivered).count();
        if (latencies_s.size() == kMaxLatencies) latencies_s.erase(latencies_s.begin());
        latencies_s.push_back(latency_s);
        break;
      }
    }
  }
  cycles.insert(cycles.end(), all.begin() + static_cast<std::ptrdiff_t>(pipeline_cycles_seen),
                all.end());
  pipeline_cycles_seen = all.size();
  levels = levels_done;
  levels.insert(levels.end(), pipeline->levels().begin(), pipeline->levels().end());
  current_level = pipeline->current_level();
  status.cycles = static_cast<long>(cycles.size());
  status.excluded_cycles = pipeline->excluded_cycles();
  status.levels = levels.size();
  if (latency_s >= 0) {
    status.edc_latency_s = latency_s;
    status.edc_latency_max_s = std::max(status.edc_latency_max_s, latency_s);
  }
}

void Acquisition::Impl::copy_monitor_counters() {
  if (!monitor) return;
  const StreamMonitor::Counters& c = monitor->counters();
  const std::lock_guard lock(mutex);
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
    recorder = std::make_unique<LiveRecorder>(path, *layout_copy, history.end,
                                              options.recorder_sync_interval);
    status.recording = true;
    StreamEvent started(time_of(history.end), "recording-started", path);
    started.wall = utc_now_iso8601();
    recorder->log(started);
    events.push_back(started);
  } catch (const InputError& error) {
    status.recorder_error = error.what();
    StreamEvent failed(time_of(history.end), "error", error.what());
    failed.wall = utc_now_iso8601();
    events.push_back(failed);
  }
}

void Acquisition::Impl::apply_recording_requests() {
  const std::lock_guard lock(mutex);
  if (recorder) recorder->maybe_write_sidecar();
  if (pending_stop_recording) {
    pending_stop_recording = false;
    if (recorder) {
      StreamEvent stopped(time_of(next_sample), "recording-stopped", recorder->path());
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

void Acquisition::Impl::run(Acquisition& owner) {
  // Events wait in the source until the layout is set up: a network sender's first levels come
  // right after its HELLO and must reach the pipeline and the recording.
  while (!stop.load() && !setup_layout()) {
    if (source->finished()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  open_pending_recording();
  log({0.0, "start", source->describe()});
  for (const std::string& warning : setup_warnings) log({0.0, "warning", warning});
  bool source_done = false;
  while (status.layout_known) {
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
    monitor->push(*block);
    queue->pop();
    copy_monitor_counters();
    apply_recording_requests();
  }
  if (monitor) monitor->flush();
  for (std::size_t c = 0; c < non_finite_runs.size(); ++c) {
    close_bad_run(non_finite_runs[c], "non-finite", static_cast<int>(c));
    close_bad_run(saturated_runs[c], "saturated", static_cast<int>(c));
  }
  handle_events();
  finish_pipeline();
  log({time_of(next_sample), "stop", source->describe()});
  copy_monitor_counters();
  {
    const std::lock_guard lock(mutex);
    pending_stop_recording = true;
  }
  apply_recording_requests();
  {
    const std::lock_guard lock(mutex);
    status.running = false;
  }
  owner.finished_.store(true, std::memory_order_release);
}

}  // namespace oscilab::daq
