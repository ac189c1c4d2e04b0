#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "daq/recording/sidecar.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

/// Samples from a sound card (or any JACK client) through a JACK server: the live path from real
/// acquisition hardware (docs/live.md, "JACK").
///
/// The source registers a client on the server it is told (JackCaptureClient: its input ports
/// `in_<channel>`), connects each to the capture port given for its channel, and activates. In
/// JACK's process callback it only copies the period's frames, interleaved, into a
/// single-producer ring of fixed slots allocated before activation (FrameSlotRing): no lock, no
/// allocation, no system call there. (While the server freewheels, which is not real time, a
/// full ring makes the callback wait for room instead of dropping: a freewheeling run is
/// lossless.) Each slot carries the server's frame time, so the source sees frames that never
/// came (xruns, a ring overrun) as a jump of the frame clock.
///
/// The source's own thread drains the ring, checks each input sample against the interface's
/// full scale (|x| ≥ kClipLevel: clipped), and resamples all channels together in one libsoxr
/// instance (InterleavedResampler: every channel has the same filter and delay) from the
/// server's rate to the analysis rate, handing on every analysis sample but those a fault
/// reaches (WithheldSamples):
///   - anti-alias filter: SOXR_HQ (20-bit precision, ≥ 120 dB stopband rejection), linear phase,
///     passband flat to passband_end × the analysis Nyquist (0.6: 153.6 Hz at 512 Hz), stopband
///     from the analysis Nyquist (256 Hz) up;
///   - soxr removes the filter's group delay itself: output sample k is the input signal at
///     t = k / analysis rate exactly (tested to 1e-6 of full scale on a sine). What remains is a
///     latency, soxr_delay(): ~70 analysis samples (≤ 140 ms at 512 Hz) with the DFT sizes used
///     (2^6..2^8), held back and delivered once computed; it shifts when samples arrive, never
///     their sample index;
///   - the stream's sample clock counts analysis samples from the first frame on: after N
///     server frames, N × rate_out / rate_in samples (minus the latency until the end, when the
///     filter's tail is flushed).
/// Stored values are volts, sample × full_scale_v (or the fraction of full scale without it), so
/// the sidecar's `unit` "V" and `scale` (the sensitivity) make them physical.
///
/// Faults, each counted (counters()), posted as an event, and left out of the analysis:
///   - `xrun`: the server reported one (jack_set_xrun_callback); the analysis samples within a
///     period and the filter's reach of it are withheld (a gap downstream);
///   - frames lost (an xrun that dropped periods, a ring overrun): zeros keep the resampler on
///     its clock, and the analysis samples they reach are withheld (a gap);
///   - `port-disconnected` / `port-connected` (jack_set_port_connect_callback, and each period's
///     connection state): while a port is unconnected its frames count as lost; the source
///     reconnects it every reconnect_interval_s;
///   - `server-shutdown` (jack_on_info_shutdown) and `rate-changed`
///     (jack_set_sample_rate_callback): the source closes its client and opens a new one every
///     reconnect_interval_s until the server answers (`reconnected`); the stream clock runs on
///     by the wall time it was away, which shows as a gap;
///   - `clipped`: input samples at full scale; an `invalid` stretch (from_s, to_s) covering
///     the analysis samples they reach.
///
/// Thread-safety: as SampleSource; peaks() from any thread.
class JackSource final : public SampleSource {
 public:
  /// |x| at or above this (of full scale) counts as clipped: 24-bit interfaces give at most
  /// 1 − 2⁻²³ and clip there; −0.0009 dB below full scale leaves room for a DC offset's rounding.
  static constexpr double kClipLevel = 0.9999;

  struct Options {
    std::string server;  // empty: the default server
    std::string client_name = "oscilab";
    std::vector<std::string> ports;     // capture port of each calibration channel, in order
    Sidecar calibration;                // channels, mass, excitation; rate replaced (below)
    double analysis_rate_hz = 512.0;    // what the stream delivers
    double passband_end = 0.6;          // × the analysis Nyquist kept flat (soxr passband_end)
    int block_rows = 16;                // analysis samples per block (31 ms at 512 Hz)
    double ring_s = 2.0;                // server-rate frames the ring holds
    double reconnect_interval_s = 0.5;  // server or port gone: try again this often
  };

  /// Checks the options against the calibration (one port per channel, at most 16), opens a
  /// client on the server and checks that every port exists and gives audio. Throws InputError
  /// naming the server or the port.
  explicit JackSource(Options options);
  ~JackSource() override;

  /// The audio output ports of a server (what can be captured: "system:capture_1", another
  /// client's outputs), for a port choice. Throws InputError naming the server when none runs.
  static std::vector<std::string> capture_ports(const std::string& server);

  /// Per channel, the peak |sample| since the last call in % of full scale (level meters).
  std::vector<double> peaks();
  /// The server's rate now (0 while it is gone).
  double server_rate_hz() const { return server_rate_hz_.load(std::memory_order_acquire); }
  /// Output samples the resampler's impulse response reaches on either side (measured at each
  /// start: 24 at 48 kHz → 512 Hz); what a fault withholds around the samples it touches.
  int resampler_reach() const { return reach_.load(std::memory_order_acquire); }

  int max_block_rows() const override { return options_.block_rows; }
  int max_channels() const override { return static_cast<int>(options_.ports.size()); }
  std::string describe() const override;

 private:
  struct Impl;  // the client, the resampler and the stream's clock (jack_source.cpp)
  void run() override;
  void kind_counters(SourceCounters& counters) const override;

  Options options_;
  std::unique_ptr<Impl> impl_;
  std::atomic<double> server_rate_hz_{0.0};
  std::atomic<int> reach_{0};
  std::atomic<std::uint64_t> xruns_{0}, server_losses_{0}, port_disconnections_{0},
      rate_changes_{0}, dropped_frames_{0}, clipped_samples_{0}, reconnections_{0},
      failed_reconnects_{0};
};

}  // namespace oscilab::daq
