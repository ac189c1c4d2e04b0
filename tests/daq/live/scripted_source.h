#pragma once

#include <chrono>
#include <thread>
#include <vector>

#include "daq/recording/recording.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq::testing {

/// A source that delivers blocks prepared by a test (cut from a recording, then dropped,
/// duplicated, reordered or corrupted), waiting for room in the queue, then ends: the faults a
/// real stream can have, made exactly and reproducibly.
class ScriptedSource final : public SampleSource {
 public:
  struct Block {
    std::uint64_t sequence = 0;
    std::uint64_t first_sample = 0;
    std::vector<double> values;  // rows × channels stored values
    int rows = 0;
  };
  /// `wait`: wait for room in the queue (else drop and count, as live hardware does);
  /// `pause_us`: between blocks, so a slow consumer falls behind gradually.
  /// `burst`: the first `burst` blocks are pushed without waiting whatever `wait` says (a
  /// consumer that has not started yet loses what does not fit).
  ScriptedSource(Sidecar layout, std::vector<Block> blocks, std::vector<StreamEvent> events = {},
                 bool wait = true, int pause_us = 0, std::size_t burst = 0)
      : blocks_(std::move(blocks)),
        events_(std::move(events)),
        wait_(wait),
        pause_us_(pause_us),
        burst_(burst) {
    channels_ = static_cast<int>(layout.channels.size());
    for (const Block& b : blocks_) max_rows_ = std::max(max_rows_, b.rows);
    set_layout(layout);
  }
  ~ScriptedSource() override { stop(); }
  int max_block_rows() const override { return max_rows_; }
  std::string describe() const override { return "scripted"; }

  /// Cuts the stored samples of a recording into blocks of `rows`, numbered in order.
  static std::vector<Block> cut(const Recording& recording, int rows) {
    std::vector<Block> blocks;
    const Eigen::Index n = recording.samples_stored.rows();
    const auto channels = recording.samples_stored.cols();
    for (Eigen::Index first = 0; first < n; first += rows) {
      Block b;
      b.sequence = blocks.size();
      b.first_sample = static_cast<std::uint64_t>(first);
      b.rows = static_cast<int>(std::min<Eigen::Index>(rows, n - first));
      for (int r = 0; r < b.rows; ++r) {
        for (Eigen::Index c = 0; c < channels; ++c) {
          b.values.push_back(recording.samples_stored(first + r, c));
        }
      }
      blocks.push_back(std::move(b));
    }
    return blocks;
  }

 private:
  void run() override {
    for (StreamEvent& event : events_) post_event(event);
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      const Block& b = blocks_[i];
      if (stop_requested()) return;
      if (pause_us_ > 0) std::this_thread::sleep_for(std::chrono::microseconds(pause_us_));
      RawBlock* block = begin_block(wait_ && i >= burst_);
      if (block == nullptr) {
        count_overflow(b.first_sample);
        continue;
      }
      std::copy(b.values.begin(), b.values.end(), block->values.begin());
      block->sequence = b.sequence;
      block->first_sample = b.first_sample;
      block->rows = b.rows;
      block->channels = channels_;
      end_block(*block);
    }
  }

  std::vector<Block> blocks_;
  std::vector<StreamEvent> events_;
  bool wait_;
  int pause_us_;
  std::size_t burst_;
  int channels_ = 0;
  int max_rows_ = 1;
};

}  // namespace oscilab::daq::testing
