// NI TDMS files, read from NI's "TDMS File Format Internal Structure". A file is a chain of
// segments; each has a 28-byte lead-in (tag "TDSm", table of contents, version, next-segment and
// raw-data offsets), optional metadata (objects with their raw data indexes and properties) and
// raw data in chunks. describe() reads lead-ins and metadata only and seeks over the raw data;
// read_signal() walks the same metadata again and reads one channel's values where they lie.
//
// Memory stays proportional to the metadata and to the values asked for: the layout of the
// current segment is kept, not one per segment, and every declared count is checked against the
// bytes that can hold it before anything is allocated.
//
// tdms_segments walks the file's layout, tdms_metadata decodes the metadata, tdms_values reads
// and converts the stored values, tdms_scales applies the file's own scaling.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/formats/tdms_scales.h"
#include "daq/recording/formats/tdms_segments.h"
#include "daq/recording/formats/tdms_values.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

using tdms::ChunkEntry;
using tdms::daqmx_type_info;
using tdms::DaqmxScaler;
using tdms::number_property;
using tdms::RawIndex;
using tdms::read_strided;
using tdms::Sample;
using tdms::scale_plan;
using tdms::ScalePlan;
using tdms::SegmentData;
using tdms::signal_name;
using tdms::TdmsObject;
using tdms::TdmsParser;
using tdms::type_info;
using tdms::TypeInfo;

std::string stored_type(const TdmsObject& object) {
  if (!object.first_index) return "none";
  const RawIndex& index = *object.first_index;
  if (!index.daqmx) return type_info(index.data_type)->name;
  const DaqmxScaler& scaler = index.scalers.front();
  std::string text = std::string(daqmx_type_info(scaler.type)->name) +
                     (scaler.bit ? " (DAQmx digital line" : " (DAQmx raw data");
  if (index.scalers.size() > 1) text += ", " + std::to_string(index.scalers.size()) + " scalers";
  return text + ")";
}

class TdmsFormat final : public SignalFileReader {
 public:
  std::string_view format_name() const override { return "NI TDMS"; }
  bool matches_signature(std::string_view head) const override {
    return head.substr(0, 4) == "TDSm";
  }
  bool matches_extension(std::string_view extension) const override { return extension == ".tdms"; }

  FileContents describe(const std::string& path) const override {
    TdmsParser parser(path);
    parser.run(nullptr);
    FileContents contents;
    contents.container = "NI TDMS (version " + std::to_string(parser.version()) + "), " +
                         std::to_string(parser.segments()) +
                         (parser.segments() == 1 ? " segment" : " segments");
    if (!parser.truncation().empty()) contents.container += "; " + parser.truncation();
    contents.properties["file"] = nlohmann::json::object();
    contents.properties["groups"] = nlohmann::json::object();
    if (!parser.truncation().empty()) contents.properties["truncation"] = parser.truncation();
    // A Silixa iDAS interrogator gives its rate only as a property of the file (root) object.
    std::optional<double> file_rate_hz;
    for (const TdmsObject& object : parser.objects()) {
      if (object.names.empty()) {
        file_rate_hz = number_property(object.properties, "SamplingFrequency[Hz]");
      }
    }
    for (const TdmsObject& object : parser.objects()) {
      if (object.names.empty()) {
        contents.properties["file"] = object.properties;
      } else if (object.names.size() == 1) {
        contents.properties["groups"][object.names[0]] = object.properties;
      } else {
        FileSignal signal;
        signal.name = signal_name(object);
        signal.sample_count = object.values;
        const auto unit = object.properties.find("unit_string");
        if (unit != object.properties.end() && unit->is_string()) {
          signal.unit = unit->get<std::string>();
        }
        const std::optional<double> increment_s =
            number_property(object.properties, "wf_increment");
        if (increment_s && std::isfinite(*increment_s) && *increment_s > 0.0 &&
            std::isfinite(1.0 / *increment_s)) {
          signal.sample_rate_hz = 1.0 / *increment_s;
        } else if (file_rate_hz && std::isfinite(*file_rate_hz) && *file_rate_hz > 0.0) {
          signal.sample_rate_hz = *file_rate_hz;
        }
        signal.stored_type = stored_type(object);
        signal.properties = object.properties;
        contents.file_signals.push_back(std::move(signal));
      }
    }
    return contents;
  }

  std::vector<double> read_signal(const std::string& path, const FileSignal& signal,
                                  int column) const override {
    TdmsParser layout(path);
    layout.run(nullptr);
    const std::vector<TdmsObject>& objects = layout.objects();
    std::optional<std::size_t> found;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects[i].names.size() != 2 || signal_name(objects[i]) != signal.name) continue;
      if (found) {
        throw InputError(path + ": two channels are named " + in_quotes(signal.name) + " (" +
                         in_quotes(objects[*found].path) + " and " + in_quotes(objects[i].path) +
                         ")");
      }
      found = i;
    }
    if (!found) {
      throw InputError(path + ": the file holds no channel " + in_quotes(signal.name));
    }
    if (column > 0) {
      throw InputError(path + ": " + in_quotes(signal.name) + " has one column, not " +
                       std::to_string(column + 1));
    }
    const TdmsObject& object = objects[*found];
    if (!object.first_index) return {};
    if (!object.first_index->daqmx && !type_info(object.first_index->data_type)->sample) {
      throw InputError(path + ": " + in_quotes(signal.name) + " stores " +
                       type_info(object.first_index->data_type)->name +
                       " values, which are not samples (int8 to uint64, float32 and float64 "
                       "are read)");
    }
    const ScalePlan plan = scale_plan(object, path);

    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(object.values));  // ≤ the file's raw data bytes
    std::vector<unsigned char> buffer;
    TdmsParser data(path);
    data.run([&](const SegmentData& segment) {
      const auto entry = std::find_if(segment.entries->begin(), segment.entries->end(),
                                      [&](const ChunkEntry& e) { return e.object == *found; });
      if (entry == segment.entries->end()) return;
      const RawIndex& index = *entry->index;
      Sample sample = Sample::F64;
      std::uint64_t first_bytes = 0;
      std::uint64_t stride_bytes = 0;
      std::uint64_t size_bytes = 0;
      std::optional<int> bit;
      if (index.daqmx) {
        const DaqmxScaler* scaler = nullptr;
        for (const DaqmxScaler& candidate : index.scalers) {
          if (plan.scale_id ? candidate.scale_id == *plan.scale_id : index.scalers.size() == 1) {
            scaler = &candidate;
            break;
          }
        }
        if (!scaler) {
          data.fail(in_quotes(signal.name) + ": " +
                    (plan.scale_id
                         ? "no DAQmx scaler has scale ID " + std::to_string(*plan.scale_id)
                         : std::to_string(index.scalers.size()) +
                               " DAQmx scalers and no NI_Scale property picks one"));
        }
        const TypeInfo* type = daqmx_type_info(scaler->type);
        sample = *type->sample;
        size_bytes = type->size_bytes;
        first_bytes = (*segment.buffer_offsets)[scaler->buffer] + scaler->byte_offset;
        stride_bytes = index.widths_bytes[scaler->buffer];
        bit = scaler->bit;
      } else {
        const TypeInfo* type = type_info(index.data_type);
        sample = *type->sample;
        size_bytes = type->size_bytes;
        first_bytes = entry->offset_bytes;
        stride_bytes = entry->stride_bytes;
      }
      for (std::uint64_t chunk = 0; chunk < segment.chunks; ++chunk) {
        read_strided(data.file(), segment.data_position + chunk * segment.chunk_bytes + first_bytes,
                     index.values, stride_bytes, size_bytes, sample, segment.big_endian, bit,
                     buffer, values);
      }
    });
    for (const auto& [slope, intercept] : plan.steps) {
      for (double& value : values) value = slope * value + intercept;
    }
    return values;
  }
};

}  // namespace

const FormatReader& tdms_format() {
  static const TdmsFormat format;
  return format;
}

}  // namespace oscilab::daq
