#pragma once

// The layout of a TDMS file, read from NI's "TDMS File Format Internal Structure": a chain of
// segments, each with a 28-byte lead-in (tag "TDSm", table of contents, version, next-segment and
// raw-data offsets), optional metadata (objects with their raw data indexes and properties) and
// raw data in chunks.
//
// Memory stays proportional to the metadata: the layout of the current segment is kept, not one
// per segment, and every declared count is checked against the bytes that can hold it before
// anything is allocated.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/tdms_metadata.h"
#include "daq/recording/formats/tdms_values.h"

namespace oscilab::daq::tdms {

// Table of contents flags of the lead-in.
inline constexpr std::uint32_t kTocMetaData = 1u << 1;
inline constexpr std::uint32_t kTocNewObjList = 1u << 2;
inline constexpr std::uint32_t kTocRawData = 1u << 3;
inline constexpr std::uint32_t kTocInterleavedData = 1u << 5;
inline constexpr std::uint32_t kTocBigEndian = 1u << 6;
inline constexpr std::uint32_t kTocDAQmxRawData = 1u << 7;

inline constexpr std::uint64_t kLeadInBytes = 28;
// The next-segment offset of a segment whose writer did not finish it.
inline constexpr std::uint64_t kLengthUnknown = 0xFFFFFFFFFFFFFFFFull;

// Raw data index headers.
inline constexpr std::uint32_t kIndexSameAsPrevious = 0x00000000;
inline constexpr std::uint32_t kIndexNoData = 0xFFFFFFFF;
inline constexpr std::uint32_t kIndexFormatChangingScaler = 0x00001269;
inline constexpr std::uint32_t kIndexDigitalLineScaler = 0x0000126A;

// One DAQmx scaler: where one of a channel's raw values lies in a raw buffer's stride.
struct DaqmxScaler {
  std::uint32_t type = 0;  // kDaqmxTypes
  std::uint32_t buffer = 0;
  std::uint32_t byte_offset = 0;  // of the value within the stride
  std::optional<int> bit;         // digital line scaler: the line's bit in that value
  std::uint32_t scale_id = 0;
};

// How an object's values lie in each chunk of a segment (its raw data index).
struct RawIndex {
  bool daqmx = false;
  std::uint32_t data_type = 0;
  std::uint64_t values = 0;      // per chunk
  std::uint64_t size_bytes = 0;  // per chunk (not DAQmx)
  std::vector<DaqmxScaler> scalers;
  std::vector<std::uint32_t> widths_bytes;  // DAQmx: the stride of each raw buffer
};

struct TdmsObject {
  std::string path;                // as in the file
  std::vector<std::string> names;  // none: the file; group; group and channel
  nlohmann::json properties = nlohmann::json::object();
  std::shared_ptr<const RawIndex> last_index;  // for "same as previous segment"
  std::optional<std::uint32_t> data_type;      // the first one with data; it may not change
  std::shared_ptr<const RawIndex> first_index;
  std::int64_t values = 0;
  int list_position = -1;  // in the current segment's object list
};

// One entry of a segment's object list.
struct ListEntry {
  std::size_t object = 0;
  bool has_data = false;
  std::shared_ptr<const RawIndex> index;
};

// One channel's values in every chunk of a segment.
struct ChunkEntry {
  std::size_t object = 0;
  const RawIndex* index = nullptr;
  std::uint64_t offset_bytes = 0;  // contiguous: its block; interleaved: within a row
  std::uint64_t stride_bytes = 0;  // between its values (not DAQmx)
};

// The raw data of one segment that holds data.
struct SegmentData {
  int number = 0;
  std::uint64_t position = 0;  // of the lead-in
  bool big_endian = false;
  bool daqmx = false;
  std::uint64_t data_position = 0;
  std::uint64_t chunk_bytes = 0;
  std::uint64_t chunks = 0;
  const std::vector<ChunkEntry>* entries = nullptr;
  const std::vector<std::uint64_t>* buffer_offsets = nullptr;  // DAQmx, within a chunk
};

// "group/channel": the names of a channel as in the file, joined by '/'.
std::string signal_name(const TdmsObject& object);

// Walks the segments of a TDMS file: lead-ins and metadata, seeking over the raw data. Calls
// `on_data` for each segment that holds whole chunks of data.
class TdmsParser {
 public:
  explicit TdmsParser(const std::string& path) : path_(path), file_(path) {}

  const TdmsFile& file() const { return file_; }
  const std::vector<TdmsObject>& objects() const { return objects_; }
  int segments() const { return segments_; }
  std::uint32_t version() const { return version_; }
  const std::string& truncation() const { return truncation_; }

  // Reads every segment (once per parser); throws InputError at the first malformed one. A last
  // segment cut short is read up to its last whole chunk and noted in truncation().
  void run(const std::function<void(const SegmentData&)>& on_data);

  // Throws InputError naming the file and the segment being read.
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_ + ": " + where_ + ": " + problem);
  }

 private:
  void read_metadata(std::uint64_t offset, std::uint64_t size_bytes, std::uint32_t toc);
  std::size_t find_or_add(const std::string& path, const std::string& object_where);
  std::shared_ptr<const RawIndex> read_index(MetadataCursor& cursor, std::uint32_t header,
                                             const std::string& object_where);
  // The two kinds of raw data index read_index reads: a DAQmx one (`header` its kind: the
  // scalers and raw buffer widths) and a plain one (`header` its length).
  void read_daqmx_index(MetadataCursor& cursor, std::uint32_t header,
                        const std::string& object_where, RawIndex& index);
  void read_plain_index(MetadataCursor& cursor, std::uint32_t header,
                        const std::string& object_where, RawIndex& index);
  // The layout of a chunk for the current object list (recomputed when the metadata or the
  // kind of segment changes).
  void update_layout(std::uint32_t toc);

  std::string path_;
  TdmsFile file_;
  std::vector<TdmsObject> objects_;
  std::unordered_map<std::string, std::size_t> by_path_;
  std::vector<ListEntry> list_;
  std::vector<ChunkEntry> entries_;
  std::vector<std::uint64_t> buffer_offsets_;
  std::uint64_t chunk_bytes_ = 0;
  bool layout_valid_ = false;
  std::uint32_t layout_kind_ = 0;
  int segments_ = 0;
  std::uint32_t version_ = 0;
  std::string where_;
  std::string truncation_;
};

}  // namespace oscilab::daq::tdms
