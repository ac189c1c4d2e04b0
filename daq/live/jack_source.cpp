#include "daq/live/jack_source.h"

#include <jack/jack.h>
#include <soxr.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <limits>
#include <mutex>
#include <thread>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

constexpr std::size_t kMaxChannels = 16;
constexpr double kNoTime = std::numeric_limits<double>::quiet_NaN();
constexpr auto kIdleWait = std::chrono::milliseconds(2);  // ring empty: look again after this
// Frames lost within a segment are bridged with zeros up to this long (the resampler stays on
// its clock); a longer jump of the frame clock starts a new segment.
constexpr double kMaxBridgeS = 10.0;
constexpr std::size_t kMaxWithheld = 256;  // pending withheld intervals (merged beyond)

// One period (or part of one) as the process callback saw it.
struct Slot {
  std::uint32_t frame_time = 0;  // the server's frame clock at the slot's first frame
  std::uint32_t frames = 0;
  std::uint32_t disconnected = 0;  // bit c: channel c's port had no connection
  std::vector<float> data;         // frames × channels, interleaved; capacity fixed
};

// Lock-free single-producer, single-consumer ring of preallocated slots (as BlockQueue).
class SlotRing {
 public:
  void allocate(std::size_t slots, std::size_t frames, std::size_t channels) {
    slots_.assign(slots + 1, Slot{});
    for (Slot& slot : slots_) slot.data.assign(frames * channels, 0.0f);
    frames_ = frames;
    head_.store(0);
    tail_.store(0);
  }
  std::size_t slot_frames() const { return frames_; }
  Slot* begin_push() {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if ((tail + 1) % slots_.size() == head_.load(std::memory_order_acquire)) return nullptr;
    return &slots_[tail];
  }
  void end_push() {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    tail_.store((tail + 1) % slots_.size(), std::memory_order_release);
  }
  Slot* front() {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_.load(std::memory_order_acquire)) return nullptr;
    return &slots_[head];
  }
  void pop() {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    head_.store((head + 1) % slots_.size(), std::memory_order_release);
  }

 private:
  std::vector<Slot> slots_;
  std::size_t frames_ = 0;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

// libjack prints its errors (no server, ...) on stderr itself; the source reports them as
// one InputError or event instead.
void quiet(const char*) {}

jack_client_t* open_client(const std::string& name, const std::string& server,
                           jack_status_t& status) {
  static std::once_flag once;
  std::call_once(once, [] {
    jack_set_error_function(quiet);
    jack_set_info_function(quiet);
  });
  if (server.empty()) return jack_client_open(name.c_str(), JackNoStartServer, &status);
  return jack_client_open(name.c_str(),
                          static_cast<jack_options_t>(JackNoStartServer | JackServerName), &status,
                          server.c_str());
}

std::string server_text(const std::string& server) {
  return server.empty() ? "the default JACK server" : "JACK server \"" + server + "\"";
}

// JACK port short names: the channel's name with what JACK treats specially replaced.
std::string port_short_name(const std::string& channel) {
  std::string out = "in_" + channel;
  for (char& c : out) {
    if (c == ':' || static_cast<unsigned char>(c) < 0x20) c = '_';
  }
  return out.substr(0, 200);
}

soxr_t make_resampler(double rate_in, double rate_out, std::size_t channels, double passband_end,
                      std::string& error) {
  // One instance for every channel, interleaved: the same filter, hence the same delay, on each.
  const soxr_io_spec_t io = soxr_io_spec(SOXR_FLOAT32_I, SOXR_FLOAT64_I);
  soxr_quality_spec_t quality = soxr_quality_spec(SOXR_HQ, 0);  // 20 bits, linear phase
  quality.passband_end = passband_end;
  // Small DFTs: a latency of ~70 output samples instead of ~1300 with soxr's defaults, at
  // about the same throughput (~50 M frames/s of 2 channels on this machine).
  soxr_runtime_spec_t runtime = soxr_runtime_spec(1);
  runtime.log2_min_dft_size = 6;
  runtime.log2_large_dft_size = 8;
  soxr_error_t soxr_error = nullptr;
  soxr_t resampler = soxr_create(rate_in, rate_out, static_cast<unsigned>(channels), &soxr_error,
                                 &io, &quality, &runtime);
  if (soxr_error != nullptr) error = soxr_error;
  return resampler;
}

// How far (analysis samples) the resampler's impulse response reaches on either side, to
// 1e-6 of its peak: an impulse through a scratch instance of the same design.
int measure_reach(double rate_in, double rate_out, double passband_end) {
  std::string error;
  soxr_t scratch = make_resampler(rate_in, rate_out, 1, passband_end, error);
  if (scratch == nullptr) return 64;
  const auto frames = static_cast<std::size_t>(std::ceil(4.0 * rate_in));
  const auto at = static_cast<std::size_t>(std::ceil(2.0 * rate_in));
  std::vector<float> in(frames, 0.0f);
  in[at] = 1.0f;
  std::vector<double> out(static_cast<std::size_t>(std::ceil(5.0 * rate_out)) + 64, 0.0);
  std::size_t done = 0, produced = 0;
  soxr_process(scratch, in.data(), frames, &done, out.data(), out.size(), &produced);
  std::size_t tail = 0;
  soxr_process(scratch, nullptr, 0, nullptr, out.data() + produced, out.size() - produced, &tail);
  produced += tail;
  soxr_delete(scratch);
  double peak = 0.0;
  for (std::size_t k = 0; k < produced; ++k) peak = std::max(peak, std::abs(out[k]));
  const double centre = static_cast<double>(at) * rate_out / rate_in;
  double reach = 0.0;
  for (std::size_t k = 0; k < produced; ++k) {
    if (std::abs(out[k]) > 1e-6 * peak) {
      reach = std::max(reach, std::abs(static_cast<double>(k) - centre));
    }
  }
  return static_cast<int>(std::ceil(reach)) + 1;
}

}  // namespace

// --- the JACK client, the ring and the resampler ----------------------------------------------

struct JackSource::Impl {
  JackSource& owner;
  const Options& options;
  std::size_t channels = 0;

  // --- shared with JACK's threads (callbacks) ---
  jack_client_t* client = nullptr;
  std::vector<jack_port_t*> ports;
  std::vector<float*> buffers;  // the process callback's port buffers (sized before activation)
  SlotRing ring;
  std::atomic<bool> freewheeling{false}, shutdown{false}, connections_changed{false};
  std::atomic<bool> closing{false};  // the client is being deactivated: the callback never waits
  std::atomic<std::uint32_t> changed_rate{0};  // nonzero: the server switched to this rate
  std::atomic<std::uint64_t> xrun_count{0};
  std::atomic<std::uint32_t> xrun_frame{0};  // the server's frame clock at the last xrun
  std::atomic<std::uint64_t> dropped{0};     // frames the ring had no room for

  // --- the source's thread ---
  double rate_in = 0.0, rate_out = 0.0;
  std::uint32_t period = 0;
  soxr_t resampler = nullptr;
  int reach = 0;
  std::vector<double> full_scale;  // V per unit of full scale (1 without full_scale_v)
  std::vector<float> zeros;        // one slot of silence, to bridge lost frames
  std::vector<double> out;         // resampler output, interleaved
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
  std::vector<std::pair<std::uint64_t, std::uint64_t>> withheld;  // [from, to) stream samples
  bool clip_open = false;
  std::uint64_t clip_from = 0, clip_to = 0, clip_samples = 0;
  std::chrono::steady_clock::time_point last_reconnect_try;
  std::vector<std::atomic<double>> peaks;

  Impl(JackSource& owner_, const Options& options_)
      : owner(owner_), options(options_), channels(options_.ports.size()), peaks(channels) {
    for (const ChannelInfo& channel : options.calibration.channels) {
      full_scale.push_back(channel.full_scale_v.value_or(1.0));
    }
    withheld.reserve(kMaxWithheld);
  }
  ~Impl() {
    close();
    if (resampler != nullptr) soxr_delete(resampler);
  }

  // JACK's callbacks (static trampolines below).
  int process(jack_nframes_t frames);

  std::string open();  // "" or why not
  void deactivate();
  void close();
  void connect_ports();
  void drain(bool wait_for_room);
  void feed(const float* frames, std::size_t count, bool wait_for_room);
  void bridge(std::uint64_t lost_frames, bool wait_for_room);
  void withhold_frames(std::uint64_t from_frame, std::uint64_t to_frame);
  void withhold(std::uint64_t from, std::uint64_t to);
  void emit(std::size_t produced, bool wait_for_room);
  void flush_staging(bool wait_for_room);
  void end_segment(bool wait_for_room);
  void begin_segment(std::uint64_t base);
  void check_clipping(const Slot& slot);
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

namespace {

int process_callback(jack_nframes_t frames, void* arg) {
  return static_cast<JackSource::Impl*>(arg)->process(frames);
}
void shutdown_callback(jack_status_t, const char*, void* arg) {
  static_cast<JackSource::Impl*>(arg)->shutdown.store(true, std::memory_order_release);
}
int xrun_callback(void* arg) {
  auto* impl = static_cast<JackSource::Impl*>(arg);
  impl->xrun_frame.store(jack_frame_time(impl->client), std::memory_order_relaxed);
  impl->xrun_count.fetch_add(1, std::memory_order_release);
  return 0;
}
int rate_callback(jack_nframes_t rate, void* arg) {
  auto* impl = static_cast<JackSource::Impl*>(arg);
  if (impl->rate_in > 0 && static_cast<double>(rate) != impl->rate_in) {
    impl->changed_rate.store(rate, std::memory_order_release);
  }
  return 0;
}
void connect_callback(jack_port_id_t, jack_port_id_t, int, void* arg) {
  static_cast<JackSource::Impl*>(arg)->connections_changed.store(true, std::memory_order_release);
}
void freewheel_callback(int starting, void* arg) {
  static_cast<JackSource::Impl*>(arg)->freewheeling.store(starting != 0, std::memory_order_release);
}

}  // namespace

// The real-time part: copies, interleaved, into preallocated slots. No lock, no allocation, no
// system call (jack_port_get_buffer, jack_port_connected and jack_last_frame_time read the
// server's shared memory). Freewheeling is not real time: then a full ring waits for room.
int JackSource::Impl::process(jack_nframes_t frames) {
  // Being deactivated: the server unplugs the ports, which is no fault of the stream.
  if (closing.load(std::memory_order_acquire)) return 0;
  const jack_nframes_t frame_time = jack_last_frame_time(client);
  std::uint32_t disconnected = 0;
  for (std::size_t c = 0; c < channels; ++c) {
    buffers[c] = static_cast<float*>(jack_port_get_buffer(ports[c], frames));
    if (jack_port_connected(ports[c]) == 0) disconnected |= 1u << c;
  }
  std::uint32_t done = 0;
  while (done < frames) {
    Slot* slot = ring.begin_push();
    if (slot == nullptr) {
      if (freewheeling.load(std::memory_order_acquire) &&
          !closing.load(std::memory_order_acquire)) {
        std::this_thread::sleep_for(std::chrono::microseconds(100));
        continue;
      }
      dropped.fetch_add(frames - done, std::memory_order_relaxed);
      return 0;
    }
    const std::uint32_t n =
        std::min<std::uint32_t>(frames - done, static_cast<std::uint32_t>(ring.slot_frames()));
    slot->frame_time = frame_time + done;
    slot->frames = n;
    slot->disconnected = disconnected;
    float* to = slot->data.data();
    for (std::uint32_t f = 0; f < n; ++f) {
      for (std::size_t c = 0; c < channels; ++c) *to++ = buffers[c][done + f];
    }
    ring.end_push();
    done += n;
  }
  return 0;
}

std::string JackSource::Impl::open() {
  jack_status_t status{};
  client = open_client(options.client_name, options.server, status);
  if (client == nullptr) {
    return server_text(options.server) + " is not running (or refused the client \"" +
           options.client_name + "\")";
  }
  for (const std::string& name : options.ports) {
    jack_port_t* port = jack_port_by_name(client, name.c_str());
    if (port == nullptr) {
      const std::string why =
          "port \"" + name + "\" does not exist on " + server_text(options.server);
      close();
      return why;
    }
    if ((jack_port_flags(port) & JackPortIsOutput) == 0 ||
        std::string(jack_port_type(port)) != JACK_DEFAULT_AUDIO_TYPE) {
      close();
      return "port \"" + name + "\" is not an audio output (a capture port) of " +
             server_text(options.server);
    }
  }
  ports.clear();
  for (const ChannelInfo& channel : options.calibration.channels) {
    jack_port_t* port = jack_port_register(client, port_short_name(channel.name).c_str(),
                                           JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
    if (port == nullptr) {
      close();
      return "cannot register port \"" + port_short_name(channel.name) + "\" on " +
             server_text(options.server);
    }
    ports.push_back(port);
  }
  rate_in = jack_get_sample_rate(client);
  period = jack_get_buffer_size(client);
  rate_out = options.analysis_rate_hz;
  if (!(rate_in > rate_out)) {
    close();
    return server_text(options.server) + " runs at " + std::to_string(rate_in) +
           " Hz, not above the analysis rate " + std::to_string(rate_out) + " Hz";
  }
  // Everything the callback touches is allocated here, before activation.
  const std::size_t slot_frames = std::max<std::uint32_t>(period, 64);
  const auto slots = static_cast<std::size_t>(
      std::ceil(options.ring_s * rate_in / static_cast<double>(slot_frames)) + 2);
  ring.allocate(slots, slot_frames, channels);
  buffers.assign(channels, nullptr);
  zeros.assign(slot_frames * channels, 0.0f);
  out.assign(
      (static_cast<std::size_t>(std::ceil(static_cast<double>(slot_frames) * rate_out / rate_in)) +
       4096) *
          channels,
      0.0);
  staging.assign(static_cast<std::size_t>(options.block_rows) * channels, 0.0);
  std::string error;
  if (resampler != nullptr) soxr_delete(resampler);
  resampler = make_resampler(rate_in, rate_out, channels, options.passband_end, error);
  if (resampler == nullptr) {
    close();
    return "resampler " + std::to_string(rate_in) + " Hz -> " + std::to_string(rate_out) +
           " Hz: " + error;
  }
  reach = measure_reach(rate_in, rate_out, options.passband_end);
  shutdown.store(false);
  closing.store(false);
  changed_rate.store(0);
  freewheeling.store(false);
  jack_set_process_callback(client, process_callback, this);
  jack_on_info_shutdown(client, shutdown_callback, this);
  jack_set_xrun_callback(client, xrun_callback, this);
  jack_set_sample_rate_callback(client, rate_callback, this);
  jack_set_port_connect_callback(client, connect_callback, this);
  jack_set_freewheel_callback(client, freewheel_callback, this);
  xruns_seen = xrun_count.load();
  if (jack_activate(client) != 0) {
    close();
    return "cannot activate the client on " + server_text(options.server);
  }
  connect_ports();
  return "";
}

void JackSource::Impl::deactivate() {
  closing.store(true, std::memory_order_release);
  if (client != nullptr) jack_deactivate(client);
}

void JackSource::Impl::close() {
  if (client != nullptr) {
    deactivate();
    jack_client_close(client);
    client = nullptr;
  }
  ports.clear();
}

void JackSource::Impl::connect_ports() {
  for (std::size_t c = 0; c < channels; ++c) {
    if (jack_port_connected_to(ports[c], options.ports[c].c_str()) != 0) continue;
    const int result = jack_connect(client, options.ports[c].c_str(), jack_port_name(ports[c]));
    (void)result;  // EEXIST or a port gone: the period's connection state tells
  }
  last_reconnect_try = std::chrono::steady_clock::now();
}

void JackSource::Impl::begin_segment(std::uint64_t base) {
  soxr_clear(resampler);
  segment_open = true;
  have_first_frame = false;
  segment_base = base;
  segment_in = segment_out = 0;
  // The filter starts on silence: its first reach samples are not the signal.
  withhold(base, base + static_cast<std::uint64_t>(reach));
}

void JackSource::Impl::withhold(std::uint64_t from, std::uint64_t to) {
  if (to <= from) return;
  for (auto& interval : withheld) {  // overlapping or touching: merged
    if (from <= interval.second && to >= interval.first) {
      interval.first = std::min(interval.first, from);
      interval.second = std::max(interval.second, to);
      return;
    }
  }
  if (withheld.size() == kMaxWithheld) {  // bounded: the last one grows to cover this too
    withheld.back().second = std::max(withheld.back().second, to);
    return;
  }
  withheld.emplace_back(from, to);
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
void JackSource::Impl::emit(std::size_t produced, bool wait_for_room) {
  for (std::size_t k = 0; k < produced; ++k) {
    const std::uint64_t index = segment_base + segment_out + k;
    bool skip = false;
    for (const auto& interval : withheld) {
      if (index >= interval.first && index < interval.second) {
        skip = true;
        break;
      }
    }
    if (skip) {
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
  const std::uint64_t done = segment_base + segment_out;
  withheld.erase(std::remove_if(withheld.begin(), withheld.end(),
                                [done](const auto& interval) { return interval.second <= done; }),
                 withheld.end());
}

void JackSource::Impl::feed(const float* frames, std::size_t count, bool wait_for_room) {
  std::size_t fed = 0;
  while (fed < count) {
    std::size_t used = 0, produced = 0;
    soxr_process(resampler, frames + fed * channels, count - fed, &used, out.data(),
                 out.size() / channels, &produced);
    fed += used;
    segment_in += used;
    emit(produced, wait_for_room);
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
    std::size_t produced = 0;
    soxr_process(resampler, nullptr, 0, nullptr, out.data(), out.size() / channels, &produced);
    if (produced == 0) break;
    emit(produced, wait_for_room);
  }
  flush_staging(wait_for_room);
  withheld.clear();
  segment_open = false;
}

void JackSource::Impl::check_clipping(const Slot& slot) {
  std::uint64_t clipped = 0;
  for (std::size_t c = 0; c < channels; ++c) {
    double peak = 0.0;
    for (std::uint32_t f = 0; f < slot.frames; ++f) {
      const double x = std::abs(static_cast<double>(slot.data[f * channels + c]));
      peak = std::max(peak, x);
      if (x >= kClipLevel) ++clipped;
    }
    double shown = peaks[c].load(std::memory_order_relaxed);
    while (peak > shown && !peaks[c].compare_exchange_weak(shown, peak)) {
    }
  }
  const std::uint64_t from = segment_in, to = segment_in + slot.frames;
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
  const std::uint64_t count = xrun_count.load(std::memory_order_acquire);
  if (count == xruns_seen) return;
  const std::uint64_t fresh = count - xruns_seen;
  xruns_seen = count;
  owner.xruns_.fetch_add(fresh, std::memory_order_relaxed);
  // The xrun's periods and the filter's reach of them are withheld, if still to come.
  const std::uint32_t at = xrun_frame.load(std::memory_order_relaxed);
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
  while (Slot* slot = ring.front()) {
    if (!segment_open) begin_segment(0);
    if (!have_first_frame && slot->disconnected != 0) {
      // The periods before the ports were first connected (they are connected just after
      // activation) are not part of the stream.
      ring.pop();
      continue;
    }
    if (!have_first_frame) {
      have_first_frame = true;
      next_frame = slot->frame_time;
      owner.post_event({time_of(segment_base),
                        EventKind::Connected,
                        server_text(options.server) + " at " + std::to_string(rate_in) +
                            " Hz, period " + std::to_string(period),
                        {{"server_rate_hz", rate_in},
                         {"period_frames", period},
                         {"server_frame", slot->frame_time},
                         {"resampler_reach", reach}}});
    }
    // Frames that never came (an xrun that dropped periods, a ring overrun).
    const auto jump = static_cast<std::int32_t>(slot->frame_time - next_frame);
    if (jump > 0 && jump <= static_cast<std::int64_t>(kMaxBridgeS * rate_in)) {
      bridge(static_cast<std::uint64_t>(jump), wait_for_room);
    } else if (jump != 0) {  // far ahead, or back: a new segment after what was made
      const std::uint64_t end = out_index(segment_in);
      owner.post_event({time_of(end), EventKind::Discontinuity,
                        "the JACK frame clock jumped by " + std::to_string(jump) + " frames"});
      end_segment(wait_for_room);
      const double ahead_s = jump > 0 ? static_cast<double>(jump) / rate_in : 0.0;
      begin_segment(end + 1 + static_cast<std::uint64_t>(std::llround(ahead_s * rate_out)));
      have_first_frame = true;
    }
    next_frame = slot->frame_time + slot->frames;
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
    if (slot->disconnected != 0) withhold_frames(segment_in, segment_in + slot->frames);
    check_clipping(*slot);
    feed(slot->data.data(), slot->frames, wait_for_room);
    ring.pop();
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
  impl_->close();
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
  jack_status_t status{};
  jack_client_t* client = open_client("oscilab-ports", server, status);
  if (client == nullptr) throw InputError(server_text(server) + " is not running");
  std::vector<std::string> names;
  if (const char** ports =
          jack_get_ports(client, nullptr, JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput)) {
    for (const char** p = ports; *p != nullptr; ++p) names.emplace_back(*p);
    jack_free(ports);
  }
  jack_client_close(client);
  return names;
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
    const bool freewheel = m.freewheeling.load(std::memory_order_acquire);
    const bool lost = m.shutdown.load(std::memory_order_acquire);
    const std::uint32_t new_rate = m.changed_rate.load(std::memory_order_acquire);
    if (!lost && new_rate == 0) {
      m.handle_xruns();
      const bool had = m.ring.front() != nullptr;
      m.drain(freewheel);
      if (m.connections_changed.exchange(false) ||
          (m.last_disconnected != 0 &&
           std::chrono::steady_clock::now() - m.last_reconnect_try >
               std::chrono::duration<double>(options_.reconnect_interval_s))) {
        if (m.last_disconnected != 0) m.connect_ports();
      }
      if (!had) std::this_thread::sleep_for(kIdleWait);
      continue;
    }
    // The server went away or changed its rate: what it delivered is kept, the client closed,
    // and a new one opened once the server answers.
    if (!lost) m.deactivate();
    m.drain(false);
    const std::uint64_t end = m.segment_open ? m.out_index(m.segment_in) : resume_at;
    m.end_segment(false);
    if (lost) {
      server_losses_.fetch_add(1, std::memory_order_relaxed);
      post_event({m.time_of(end), EventKind::ServerShutdown,
                  server_text(options_.server) + " shut down; reconnecting"});
    } else {
      rate_changes_.fetch_add(1, std::memory_order_relaxed);
      post_event({m.time_of(end),
                  EventKind::RateChanged,
                  server_text(options_.server) + " changed its rate from " +
                      std::to_string(m.rate_in) + " to " + std::to_string(new_rate) + " Hz",
                  {{"from_hz", m.rate_in}, {"to_hz", new_rate}}});
    }
    m.close();
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
    post_event(
        {m.time_of(resume_at),
         EventKind::Reconnected,
         server_text(options_.server) + " answers again after " + std::to_string(away_s) + " s",
         {{"away_s", away_s}, {"server_rate_hz", m.rate_in}}});
  }
  // Stopped: what the ring holds, then the filter's tail.
  m.deactivate();
  m.drain(false);
  m.end_segment(false);
  m.close();
}

}  // namespace oscilab::daq
