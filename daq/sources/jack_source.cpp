#include "daq/sources/jack_source.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "analysis/common/input_error.h"
#include "daq/jack/interleaved_resampler.h"
#include "daq/jack/jack_capture_client.h"
#include "daq/sources/withheld_samples.h"

namespace oscilab::daq {
namespace {

constexpr std::size_t kMaxChannels = 16;
constexpr auto kIdleWait = std::chrono::milliseconds(2);  // ring empty: look again after this
// Frames lost within a segment are bridged with zeros up to this long (the resampler stays on
// its clock); a longer jump of the frame clock starts a new segment.
constexpr double kMaxBridgeS = 10.0;

JackCaptureClient::Options client_options(const JackSource::Options& options) {
  JackCaptureClient::Options o;
  o.server = options.server;
  o.client_name = options.client_name;
  o.capture_ports = options.ports;
  for (const ChannelInfo& channel : options.calibration.channels) {
    o.channel_names.push_back(channel.name);
  }
  o.ring_s = options.ring_s;
  return o;
}

}  // namespace

// --- the source's thread: ring slots through the resampler into blocks -------------------------

struct JackSource::Impl {
  JackSource& owner;
  const Options& options;
  std::size_t channels = 0;
  JackCaptureClient client;

  double rate_in = 0.0, rate_out = 0.0;
  std::uint32_t period = 0;
  InterleavedResampler resampler;
  int reach = 0;
  std::vector<double> full_scale;  // V per unit of full scale (1 without full_scale_v)
  std::vector<float> zeros;        // one slot of silence, to bridge lost frames
  std::vector<double> staging;     // one block being filled
  int staged_rows = 0;
  std::uint64_t staged_first = 0;
  std::uint64_t sequence = 0;
  // Segment: one resampler run on one unbroken server frame clock.
  bool segment_open = false, have_first_frame = false;
  std::uint64_t segment_base = 0;  // stream index of the segment's first analysis sample
  std::uint64_t segment_in = 0;    // server frames fed
  std::uint64_t segment_out = 0;   // analysis samples produced
  std::uint32_t next_frame = 0;    // the frame clock expected next
  std::uint32_t last_disconnected = 0;
  std::uint64_t xruns_seen = 0;
  std::uint64_t dropped_seen = 0;  // the client's dropped frames already counted
  WithheldSamples withheld;        // stream samples
  bool clip_open = false;
  std::uint64_t clip_from = 0, clip_to = 0, clip_samples = 0;
  std::vector<std::atomic<double>> peaks;

  Impl(JackSource& owner_, const Options& options_)
      : owner(owner_),
        options(options_),
        channels(options_.ports.size()),
        client(client_options(options_)),
        peaks(channels) {
    for (const ChannelInfo& channel : options.calibration.channels) {
      full_scale.push_back(channel.full_scale_v.value_or(1.0));
    }
  }
  ~Impl() { client.close(); }

  std::string open();  // "" or why not
  void drain(bool wait_for_room);
  void feed(const float* frames, std::size_t count, bool wait_for_room);
  void bridge(std::uint64_t lost_frames, bool wait_for_room);
  void withhold_frames(std::uint64_t from_frame, std::uint64_t to_frame);
  void withhold(std::uint64_t from, std::uint64_t to) { withheld.add(from, to); }
  void emit(const double* out, std::size_t produced, bool wait_for_room);
  void flush_staging(bool wait_for_room);
  void end_segment(bool wait_for_room);
  void begin_segment(std::uint64_t base);
  void check_clipping(const FrameSlot& slot, std::uint32_t first_frame);
  void close_clip_run();
  void handle_xruns();
  double time_of(std::uint64_t sample) const {
    return static_cast<double>(sample) / options.analysis_rate_hz;
  }
  std::uint64_t out_index(std::uint64_t segment_frame) const {
    return segment_base + static_cast<std::uint64_t>(
                              std::floor(static_cast<double>(segment_frame) * rate_out / rate_in));
  }
};

std::string JackSource::Impl::open() {
  std::string error = client.open();
  if (!error.empty()) return error;
  rate_in = client.rate_hz();
  period = client.period_frames();
  rate_out = options.analysis_rate_hz;
  if (!(rate_in > rate_out)) {
    client.close();
    return jack_server_text(options.server) + " runs at " + std::to_string(rate_in) +
           " Hz, not above the analysis rate " + std::to_string(rate_out) + " Hz";
  }
  // Everything the source's thread needs per slot is allocated here, before activation.
  const std::size_t slot_frames = client.ring().slot_frames();
  zeros.assign(slot_frames * channels, 0.0f);
  staging.assign(static_cast<std::size_t>(options.block_rows) * channels, 0.0);
  error = resampler.open(rate_in, rate_out, channels, options.passband_end, slot_frames);
  if (!error.empty()) {
    client.close();
    return "resampler " + std::to_string(rate_in) + " Hz -> " + std::to_string(rate_out) +
           " Hz: " + error;
  }
  reach = InterleavedResampler::measure_reach(rate_in, rate_out, options.passband_end);
  xruns_seen = client.xruns();
  dropped_seen = client.dropped_frames();
  return client.activate();
}

void JackSource::Impl::begin_segment(std::uint64_t base) {
  resampler.clear();
  segment_open = true;
  have_first_frame = false;
  segment_base = base;
  segment_in = segment_out = 0;
  // The filter starts on silence: its first reach samples are not the signal.
  withhold(base, base + static_cast<std::uint64_t>(reach));
}

void JackSource::Impl::withhold_frames(std::uint64_t from_frame, std::uint64_t to_frame) {
  const auto r = static_cast<std::uint64_t>(reach);
  const std::uint64_t from = out_index(from_frame);
  withhold(from > segment_base + r ? from - r : segment_base, out_index(to_frame) + r + 1);
}

void JackSource::Impl::flush_staging(bool wait_for_room) {
  if (staged_rows == 0) return;
  RawBlock* block = owner.begin_block(wait_for_room);
  if (block != nullptr) {
    std::copy_n(staging.begin(),
                static_cast<std::ptrdiff_t>(staged_rows) * static_cast<std::ptrdiff_t>(channels),
                block->values.begin());
    block->sequence = sequence;
    block->first_sample = staged_first;
    block->rows = staged_rows;
    block->channels = static_cast<int>(channels);
    owner.end_block(*block);
  } else if (!owner.stop_requested()) {
    owner.count_overflow(staged_first);
  }
  ++sequence;
  staged_rows = 0;
}

// Hands on `produced` analysis samples from `out`, stored as volts, except those withheld.
void JackSource::Impl::emit(const double* out, std::size_t produced, bool wait_for_room) {
  for (std::size_t k = 0; k < produced; ++k) {
    const std::uint64_t index = segment_base + segment_out + k;
    if (withheld.contains(index)) {
      flush_staging(wait_for_room);  // the next block starts after the withheld samples
      continue;
    }
    if (staged_rows > 0 && staged_first + static_cast<std::uint64_t>(staged_rows) != index) {
      flush_staging(wait_for_room);
    }
    if (staged_rows == 0) staged_first = index;
    double* row = staging.data() + static_cast<std::size_t>(staged_rows) * channels;
    for (std::size_t c = 0; c < channels; ++c) row[c] = out[k * channels + c] * full_scale[c];
    if (++staged_rows == options.block_rows) flush_staging(wait_for_room);
  }
  segment_out += produced;
  // Intervals wholly behind the output are done with.
  withheld.drop_before(segment_base + segment_out);
}

void JackSource::Impl::feed(const float* frames, std::size_t count, bool wait_for_room) {
  std::size_t fed = 0;
  while (fed < count) {
    std::size_t used = 0;
    const std::size_t produced = resampler.process(frames + fed * channels, count - fed, used);
    fed += used;
    segment_in += used;
    emit(resampler.output(), produced, wait_for_room);
    if (used == 0 && produced == 0) break;  // cannot happen with room for the output
  }
}

void JackSource::Impl::bridge(std::uint64_t lost_frames, bool wait_for_room) {
  const std::uint64_t first = segment_in;
  withhold_frames(first, first + lost_frames);
  const std::size_t chunk = zeros.size() / channels;
  while (lost_frames > 0) {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(lost_frames, chunk));
    feed(zeros.data(), n, wait_for_room);
    lost_frames -= n;
  }
}

void JackSource::Impl::end_segment(bool wait_for_room) {
  if (!segment_open) return;
  close_clip_run();
  // The filter's tail: the last input frames, completed with silence; the samples the silence
  // reaches are not the signal.
  const std::uint64_t end = out_index(segment_in);
  withhold(end > segment_base + static_cast<std::uint64_t>(reach)
               ? end - static_cast<std::uint64_t>(reach)
               : segment_base,
           end + 1);
  for (;;) {
    const std::size_t produced = resampler.flush();
    if (produced == 0) break;
    emit(resampler.output(), produced, wait_for_room);
  }
  flush_staging(wait_for_room);
  withheld.clear();
  segment_open = false;
}

// Clipping among the slot's frames from `first_frame` on (those not fed before).
void JackSource::Impl::check_clipping(const FrameSlot& slot, std::uint32_t first_frame) {
  std::uint64_t clipped = 0;
  for (std::size_t c = 0; c < channels; ++c) {
    double peak = 0.0;
    for (std::uint32_t f = first_frame; f < slot.frames; ++f) {
      const double x = std::abs(static_cast<double>(slot.data[f * channels + c]));
      peak = std::max(peak, x);
      if (x >= kClipLevel) ++clipped;
    }
    double shown = peaks[c].load(std::memory_order_relaxed);
    while (peak > shown && !peaks[c].compare_exchange_weak(shown, peak)) {
    }
  }
  const std::uint64_t from = segment_in, to = segment_in + (slot.frames - first_frame);
  if (clipped == 0) {
    close_clip_run();
    return;
  }
  owner.clipped_samples_.fetch_add(clipped, std::memory_order_relaxed);
  const auto r = static_cast<std::uint64_t>(reach);
  const std::uint64_t out_from =
      out_index(from) > segment_base + r ? out_index(from) - r : segment_base;
  const std::uint64_t out_to = out_index(to) + r;
  if (!clip_open) {
    clip_open = true;
    clip_from = out_from;
    clip_samples = 0;
  }
  clip_to = out_to;
  clip_samples += clipped;
}

void JackSource::Impl::close_clip_run() {
  if (!clip_open) return;
  clip_open = false;
  owner.post_event(
      {time_of(clip_from),
       EventKind::Clipped,
       std::to_string(clip_samples) + " input sample(s) at full scale",
       {{"samples", clip_samples}, {"from_s", time_of(clip_from)}, {"to_s", time_of(clip_to)}}});
}

void JackSource::Impl::handle_xruns() {
  // Frames the ring had no room for: counted here; the frame clock's jump they leave is bridged
  // (or starts a new segment) in drain(), as for an xrun's.
  if (const std::uint64_t dropped = client.dropped_frames(); dropped != dropped_seen) {
    owner.dropped_frames_.fetch_add(dropped - dropped_seen, std::memory_order_relaxed);
    dropped_seen = dropped;
  }
  const std::uint64_t count = client.xruns();
  if (count == xruns_seen) return;
  const std::uint64_t fresh = count - xruns_seen;
  xruns_seen = count;
  owner.xruns_.fetch_add(fresh, std::memory_order_relaxed);
  // The xrun's periods and the filter's reach of them are withheld, if still to come.
  const std::uint32_t at = client.last_xrun_frame();
  double t_s = kNoTime;
  if (segment_open && have_first_frame) {
    const auto behind = static_cast<std::int32_t>(next_frame - at);  // frames since the xrun
    const std::int64_t frame = static_cast<std::int64_t>(segment_in) - behind;
    const std::int64_t from =
        std::max<std::int64_t>(0, frame - 2 * static_cast<std::int64_t>(period));
    const std::int64_t to = std::max<std::int64_t>(from, frame + static_cast<std::int64_t>(period));
    withhold_frames(static_cast<std::uint64_t>(from), static_cast<std::uint64_t>(to));
    t_s = time_of(out_index(static_cast<std::uint64_t>(std::max<std::int64_t>(0, frame))));
  }
  owner.post_event({t_s,
                    EventKind::Xrun,
                    "the JACK server reported " + std::to_string(fresh) + " xrun(s)",
                    {{"xruns", fresh}}});
}

void JackSource::Impl::drain(bool wait_for_room) {
  while (FrameSlot* slot = client.ring().front()) {
    if (!segment_open) begin_segment(0);
    if (!have_first_frame && slot->disconnected != 0) {
      // The periods before the ports were first connected (they are connected just after
      // activation) are not part of the stream.
      client.ring().pop();
      continue;
    }
    if (!have_first_frame) {
      have_first_frame = true;
      next_frame = slot->frame_time;
      owner.post_event({time_of(segment_base),
                        EventKind::Connected,
                        jack_server_text(options.server) + " at " + std::to_string(rate_in) +
                            " Hz, period " + std::to_string(period),
                        {{"server_rate_hz", rate_in},
                         {"period_frames", period},
                         {"server_frame", slot->frame_time},
                         {"resampler_reach", reach}}});
    }
    // Frames that never came (an xrun that dropped periods, a ring overrun).
    const auto jump = static_cast<std::int32_t>(slot->frame_time - next_frame);
    const auto within_bridge = [&](std::int64_t frames) {
      return frames <= static_cast<std::int64_t>(kMaxBridgeS * rate_in);
    };
    std::uint32_t repeated = 0;  // the slot's leading frames that were fed already
    if (jump > 0 && within_bridge(jump)) {
      bridge(static_cast<std::uint64_t>(jump), wait_for_room);
    } else if (jump < 0 && within_bridge(-static_cast<std::int64_t>(jump))) {
      // Frames the clock says were fed already: a period the server ran again after an xrun
      // (JACK 2 does under load, the frame clock one period back). The stream keeps its clock:
      // the repeated frames are skipped, the rest fed; the xrun itself is withheld by its own
      // report (handle_xruns).
      const auto back = static_cast<std::uint64_t>(-static_cast<std::int64_t>(jump));
      repeated = static_cast<std::uint32_t>(std::min<std::uint64_t>(back, slot->frames));
      if (repeated == slot->frames) {
        client.ring().pop();
        continue;
      }
    } else if (jump != 0) {  // far ahead, or far back: a new segment after what was made
      const std::uint64_t end = out_index(segment_in);
      owner.post_event({time_of(end), EventKind::Discontinuity,
                        "the JACK frame clock jumped by " + std::to_string(jump) + " frames"});
      end_segment(wait_for_room);
      const double ahead_s = jump > 0 ? static_cast<double>(jump) / rate_in : 0.0;
      begin_segment(end + 1 + static_cast<std::uint64_t>(std::llround(ahead_s * rate_out)));
      have_first_frame = true;
    }
    next_frame = slot->frame_time + slot->frames;  // past what was fed, repeated frames or not
    // Ports without a connection give silence: counted once per loss, their frames withheld.
    const std::uint32_t lost = slot->disconnected & ~last_disconnected;
    const std::uint32_t back = last_disconnected & ~slot->disconnected;
    for (std::size_t c = 0; c < channels; ++c) {
      const std::string& channel = options.calibration.channels[c].name;
      if ((lost >> c) & 1u) {
        owner.port_disconnections_.fetch_add(1, std::memory_order_relaxed);
        owner.post_event({time_of(out_index(segment_in)),
                          EventKind::PortDisconnected,
                          "\"" + options.ports[c] + "\" (" + channel + ") is not connected",
                          {{"port", options.ports[c]}, {"channel", channel}}});
      }
      if ((back >> c) & 1u) {
        owner.post_event({time_of(out_index(segment_in)),
                          EventKind::PortConnected,
                          "\"" + options.ports[c] + "\" (" + channel + ") is connected again",
                          {{"port", options.ports[c]}, {"channel", channel}}});
      }
    }
    last_disconnected = slot->disconnected;
    const std::uint32_t fresh = slot->frames - repeated;
    if (slot->disconnected != 0) withhold_frames(segment_in, segment_in + fresh);
    check_clipping(*slot, repeated);
    feed(slot->data.data() + static_cast<std::size_t>(repeated) * channels, fresh, wait_for_room);
    client.ring().pop();
  }
}

// --- JackSource -------------------------------------------------------------------------------

JackSource::JackSource(Options options) : options_(std::move(options)) {
  const std::string where = "jack source";
  if (options_.ports.empty()) throw InputError(where + ": no capture port given");
  if (options_.ports.size() > kMaxChannels) {
    throw InputError(where + ": " + std::to_string(options_.ports.size()) + " ports, at most " +
                     std::to_string(kMaxChannels));
  }
  if (options_.ports.size() != options_.calibration.channels.size()) {
    throw InputError(where + ": " + std::to_string(options_.ports.size()) +
                     " port(s) for the calibration's " +
                     std::to_string(options_.calibration.channels.size()) +
                     " channel(s): give one port per channel, in the calibration's order");
  }
  for (std::size_t i = 0; i < options_.ports.size(); ++i) {
    if (options_.ports[i].empty()) {
      throw InputError(where + ": port " + std::to_string(i + 1) + " is empty");
    }
  }
  if (!(options_.analysis_rate_hz > 0) || !std::isfinite(options_.analysis_rate_hz)) {
    throw InputError(where + ": analysis rate " + std::to_string(options_.analysis_rate_hz) +
                     " Hz must be positive");
  }
  if (!(options_.passband_end >= 0.1 && options_.passband_end <= 0.95)) {
    throw InputError(where + ": passband end " + std::to_string(options_.passband_end) +
                     " must be within 0.1..0.95 of the analysis Nyquist frequency");
  }
  if (options_.block_rows < 1 || options_.block_rows > 65536) {
    throw InputError(where + ": block size " + std::to_string(options_.block_rows) +
                     " samples must be within 1..65536");
  }
  if (!(options_.ring_s >= 0.1) || !(options_.reconnect_interval_s > 0)) {
    throw InputError(where + ": the ring must hold at least 0.1 s and reconnection take time");
  }
  Sidecar layout = options_.calibration;
  layout.sample_rate_hz = options_.analysis_rate_hz;
  layout.csv.reset();
  layout.invalid_intervals.clear();
  if (layout.excitation && layout.excitation->frequency_hz &&
      *layout.excitation->frequency_hz >= 0.5 * options_.analysis_rate_hz) {
    throw InputError(where + ": excitation " + std::to_string(*layout.excitation->frequency_hz) +
                     " Hz is not below the Nyquist frequency of the analysis rate " +
                     std::to_string(options_.analysis_rate_hz) + " Hz");
  }
  for (const ChannelInfo& channel : layout.channels) {
    if (channel.ac_coupling_hz && *channel.ac_coupling_hz >= 0.5 * options_.analysis_rate_hz) {
      throw InputError(where + ": channel \"" + channel.name + "\": ac_coupling_hz " +
                       std::to_string(*channel.ac_coupling_hz) +
                       " Hz is not below the analysis Nyquist frequency");
    }
  }
  layout.extra["jack"] = {{"server", options_.server.empty() ? "default" : options_.server},
                          {"ports", options_.ports},
                          {"resampler",
                           {{"library", "libsoxr"},
                            {"quality", "SOXR_HQ"},
                            {"passband_end", options_.passband_end},
                            {"stopband_begin", 1.0}}}};
  impl_ = std::make_unique<Impl>(*this, options_);
  // Fails now, naming the server or the port, rather than on the source's thread.
  const std::string error = impl_->open();
  if (!error.empty()) throw InputError(where + ": " + error);
  server_rate_hz_.store(impl_->rate_in);
  reach_.store(impl_->reach);
  layout.extra["jack"]["server_rate_hz"] = impl_->rate_in;
  impl_->client.close();
  set_layout(layout);
}

JackSource::~JackSource() {
  stop();
  impl_.reset();
}

std::string JackSource::describe() const {
  return "JACK " + (options_.server.empty() ? std::string("default") : options_.server);
}

std::vector<std::string> JackSource::capture_ports(const std::string& server) {
  return JackCaptureClient::capture_ports(server);
}

void JackSource::kind_counters(SourceCounters& counters) const {
  JackCounters& c = counters.jack;
  c.xruns = xruns_.load(std::memory_order_relaxed);
  c.server_losses = server_losses_.load(std::memory_order_relaxed);
  c.port_disconnections = port_disconnections_.load(std::memory_order_relaxed);
  c.rate_changes = rate_changes_.load(std::memory_order_relaxed);
  c.dropped_frames = dropped_frames_.load(std::memory_order_relaxed);
  c.clipped_samples = clipped_samples_.load(std::memory_order_relaxed);
  c.reconnections = reconnections_.load(std::memory_order_relaxed);
  c.failed_reconnects = failed_reconnects_.load(std::memory_order_relaxed);
}

std::vector<double> JackSource::peaks() {
  std::vector<double> out;
  for (auto& peak : impl_->peaks) out.push_back(100.0 * peak.exchange(0.0));
  return out;
}

void JackSource::run() {
  Impl& m = *impl_;
  std::string error = m.open();
  if (!error.empty()) {
    post_event({kNoTime, EventKind::Error, "jack source: " + error});
    return;
  }
  server_rate_hz_.store(m.rate_in);
  reach_.store(m.reach);
  std::uint64_t resume_at = 0;  // stream index where the next segment starts
  while (!stop_requested()) {
    const bool freewheel = m.client.freewheeling();
    const bool lost = m.client.shut_down();
    const std::uint32_t new_rate = m.client.changed_rate();
    if (!lost && new_rate == 0) {
      m.handle_xruns();
      const bool had = m.client.ring().front() != nullptr;
      m.drain(freewheel);
      if (m.client.take_connections_changed() ||
          (m.last_disconnected != 0 &&
           std::chrono::steady_clock::now() - m.client.last_connect_try() >
               std::chrono::duration<double>(options_.reconnect_interval_s))) {
        if (m.last_disconnected != 0) m.client.connect_ports();
      }
      if (!had) std::this_thread::sleep_for(kIdleWait);
      continue;
    }
    // The server went away or changed its rate: what it delivered is kept, the client closed,
    // and a new one opened once the server answers.
    if (!lost) m.client.deactivate();
    m.drain(false);
    const std::uint64_t end = m.segment_open ? m.out_index(m.segment_in) : resume_at;
    m.end_segment(false);
    if (lost) {
      server_losses_.fetch_add(1, std::memory_order_relaxed);
      post_event({m.time_of(end), EventKind::ServerShutdown,
                  jack_server_text(options_.server) + " shut down; reconnecting"});
    } else {
      rate_changes_.fetch_add(1, std::memory_order_relaxed);
      post_event({m.time_of(end),
                  EventKind::RateChanged,
                  jack_server_text(options_.server) + " changed its rate from " +
                      std::to_string(m.rate_in) + " to " + std::to_string(new_rate) + " Hz",
                  {{"from_hz", m.rate_in}, {"to_hz", new_rate}}});
    }
    m.client.close();
    server_rate_hz_.store(0.0);
    const auto away_from = std::chrono::steady_clock::now();
    std::string why;
    while (!stop_requested()) {
      why = m.open();
      if (why.empty()) break;
      failed_reconnects_.fetch_add(1, std::memory_order_relaxed);
      std::this_thread::sleep_for(std::chrono::duration<double>(options_.reconnect_interval_s));
    }
    if (!why.empty()) break;  // stopped while away
    const double away_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - away_from).count();
    server_rate_hz_.store(m.rate_in);
    reach_.store(m.reach);
    reconnections_.fetch_add(1, std::memory_order_relaxed);
    // The stream clock runs on by the time away: the next samples follow a gap.
    resume_at =
        end + 1 + static_cast<std::uint64_t>(std::llround(away_s * options_.analysis_rate_hz));
    m.begin_segment(resume_at);
    post_event({m.time_of(resume_at),
                EventKind::Reconnected,
                jack_server_text(options_.server) + " answers again after " +
                    std::to_string(away_s) + " s",
                {{"away_s", away_s}, {"server_rate_hz", m.rate_in}}});
  }
  // Stopped: what the ring holds, then the filter's tail.
  m.client.deactivate();
  m.drain(false);
  m.end_segment(false);
  m.client.close();
}

}  // namespace oscilab::daq
