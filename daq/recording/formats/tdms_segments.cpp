#include "daq/recording/formats/tdms_segments.h"

#include <algorithm>
#include <cstring>

#include "daq/recording/stored_samples.h"

namespace oscilab::daq::tdms {

std::string signal_name(const TdmsObject& object) {
  return object.names[0] + "/" + object.names[1];
}

void TdmsParser::run(const std::function<void(const SegmentData&)>& on_data) {
  const std::uint64_t size = file_.size_bytes();
  std::uint64_t position = 0;
  while (position < size) {
    where_ = "segment " + std::to_string(segments_) + " at byte " + std::to_string(position);
    const std::uint64_t remaining = size - position;
    unsigned char lead_in[kLeadInBytes];
    const auto lead_in_bytes = static_cast<std::size_t>(std::min(remaining, kLeadInBytes));
    file_.read(position, lead_in_bytes, lead_in);
    const std::size_t tag_bytes = std::min<std::size_t>(4, lead_in_bytes);
    if (std::memcmp(lead_in, "TDSm", tag_bytes) != 0) {
      std::string tag;
      for (std::size_t i = 0; i < tag_bytes; ++i) {
        const auto c = static_cast<char>(lead_in[i]);
        tag += (c >= 0x20 && c < 0x7F) ? std::string(1, c) : "\\x" + hex(lead_in[i]).substr(2);
      }
      fail(std::string(segments_ == 0 ? "not a TDMS file" : "not a TDMS segment") +
           ": it starts with \"" + tag + "\", not \"TDSm\"");
    }
    if (remaining < kLeadInBytes) {
      truncation_ = "the file ends " + std::to_string(remaining) +
                    " bytes into the lead-in of segment " + std::to_string(segments_) +
                    " (a file still being written?); those bytes are left out";
      break;
    }
    const std::uint32_t toc = load<std::uint32_t>(lead_in + 4, false);  // always little-endian
    const bool big_endian = (toc & kTocBigEndian) != 0;
    const auto version = load<std::uint32_t>(lead_in + 8, big_endian);
    const auto next_offset = load<std::uint64_t>(lead_in + 12, big_endian);
    const auto raw_offset = load<std::uint64_t>(lead_in + 20, big_endian);
    if (version != 4712 && version != 4713) {
      fail("unknown version " + std::to_string(version) + " (4712 and 4713 are read)");
    }
    if (segments_ == 0) version_ = version;
    const std::uint64_t after_lead_in = remaining - kLeadInBytes;
    if (raw_offset > after_lead_in) {
      fail("the raw data offset " + std::to_string(raw_offset) +
           " points beyond the end of the file (" + std::to_string(after_lead_in) +
           " bytes follow the lead-in)");
    }
    if (next_offset != kLengthUnknown && next_offset < raw_offset) {
      fail("the next segment offset " + std::to_string(next_offset) +
           " lies before the raw data offset " + std::to_string(raw_offset));
    }
    const bool truncated = next_offset == kLengthUnknown || next_offset > after_lead_in;
    const std::uint64_t end = truncated ? size : position + kLeadInBytes + next_offset;

    if ((toc & kTocMetaData) != 0) {
      read_metadata(position + kLeadInBytes, raw_offset, toc);
    }
    const std::uint64_t data_position = position + kLeadInBytes + raw_offset;
    const std::uint64_t data_bytes = (toc & kTocRawData) != 0 ? end - data_position : 0;
    std::uint64_t chunks = 0;
    if (data_bytes > 0) {
      update_layout(toc);
      if (chunk_bytes_ == 0) {
        fail("it holds " + std::to_string(data_bytes) +
             " bytes of raw data, but no channel has data in it");
      }
      chunks = data_bytes / chunk_bytes_;
      const std::uint64_t rest = data_bytes % chunk_bytes_;
      if (rest != 0 && !truncated) {
        fail("its " + std::to_string(data_bytes) + " bytes of raw data are not a whole number " +
             "of " + std::to_string(chunk_bytes_) + "-byte chunks");
      }
      if (truncated) {
        truncation_ = "segment " + std::to_string(segments_) + " is cut short (" +
                      (next_offset == kLengthUnknown
                           ? std::string("its length was never written")
                           : "it should end " + std::to_string(next_offset - after_lead_in) +
                                 " bytes after the end of the file") +
                      ", a file still being written?): its " + std::to_string(chunks) +
                      " whole chunks are read, " + std::to_string(rest) +
                      " bytes of a partial chunk are left out";
      }
    } else if (truncated) {
      truncation_ = "segment " + std::to_string(segments_) +
                    " is cut short (a file still being written?); it holds no raw data";
    }
    if (chunks > 0) {
      for (const ChunkEntry& entry : entries_) {
        // values × chunks ≤ the segment's bytes: no overflow.
        objects_[entry.object].values += static_cast<std::int64_t>(entry.index->values * chunks);
      }
      if (on_data) {
        SegmentData data;
        data.number = segments_;
        data.position = position;
        data.big_endian = big_endian;
        data.daqmx = (toc & kTocDAQmxRawData) != 0;
        data.data_position = data_position;
        data.chunk_bytes = chunk_bytes_;
        data.chunks = chunks;
        data.entries = &entries_;
        data.buffer_offsets = &buffer_offsets_;
        on_data(data);
      }
    }
    ++segments_;
    position = end;
  }
  if (segments_ == 0) throw InputError(path_ + ": not a TDMS file: the file is empty");
}

void TdmsParser::read_metadata(std::uint64_t offset, std::uint64_t size_bytes, std::uint32_t toc) {
  // size_bytes ≤ the bytes after the lead-in (checked): the allocation is bounded by the file.
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size_bytes));
  file_.read(offset, bytes.size(), bytes.data());
  std::string object_where;
  MetadataCursor cursor(bytes, offset, (toc & kTocBigEndian) != 0,
                        [&](const std::string& problem) { fail(object_where + problem); });
  if ((toc & kTocNewObjList) != 0) {
    for (const ListEntry& entry : list_) objects_[entry.object].list_position = -1;
    list_.clear();
  }
  const std::uint32_t count = cursor.u32("the number of objects");
  for (std::uint32_t i = 0; i < count; ++i) {
    object_where = "object " + std::to_string(i) + ": ";
    const std::string path = cursor.string("an object path");
    object_where = "object " + std::to_string(i) + " " + in_quotes(valid_utf8(path)) + ": ";
    const std::size_t object = find_or_add(path, object_where);
    TdmsObject& target = objects_[object];
    const std::uint32_t header = cursor.u32("a raw data index");
    ListEntry entry;
    entry.object = object;
    if (header == kIndexNoData) {
      entry.has_data = false;
      entry.index = target.last_index;
    } else if (header == kIndexSameAsPrevious) {
      if (!target.last_index) {
        fail(object_where +
             "its raw data index says \"same as the previous segment\", but no earlier "
             "segment gave one");
      }
      entry.has_data = true;
      entry.index = target.last_index;
    } else {
      if (target.names.size() != 2) fail(object_where + "only channels hold raw data");
      entry.has_data = true;
      entry.index = read_index(cursor, header, object_where);
      if (target.data_type && *target.data_type != entry.index->data_type) {
        fail(object_where + "its data type changes from " + type_name(*target.data_type) + " to " +
             type_name(entry.index->data_type));
      }
      if (!target.data_type) {
        target.data_type = entry.index->data_type;
        target.first_index = entry.index;
      }
      target.last_index = entry.index;
    }
    if (target.list_position >= 0) {
      list_[static_cast<std::size_t>(target.list_position)] = entry;
    } else {
      target.list_position = static_cast<int>(list_.size());
      list_.push_back(entry);
    }
    const std::uint32_t properties = cursor.u32("the number of properties");
    for (std::uint32_t p = 0; p < properties; ++p) {
      const std::string name = valid_utf8(cursor.string("a property name"));
      const std::uint32_t type = cursor.u32("a property type");
      std::optional<nlohmann::json> value = read_property_value(cursor, type);
      if (!value) {
        fail(object_where + "property " + in_quotes(name) + ": data type " + type_name(type) +
             " is not read");
      }
      target.properties[name] = std::move(*value);
    }
  }
  layout_valid_ = false;
}

std::size_t TdmsParser::find_or_add(const std::string& path, const std::string& object_where) {
  const auto found = by_path_.find(path);
  if (found != by_path_.end()) return found->second;
  TdmsObject object;
  object.path = path;
  if (!split_path(path, object.names)) {
    fail(object_where + "not an object path (/, /'group' or /'group'/'channel')");
  }
  objects_.push_back(std::move(object));
  by_path_.emplace(path, objects_.size() - 1);
  return objects_.size() - 1;
}

std::shared_ptr<const RawIndex> TdmsParser::read_index(MetadataCursor& cursor, std::uint32_t header,
                                                       const std::string& object_where) {
  auto index = std::make_shared<RawIndex>();
  if (header == kIndexFormatChangingScaler || header == kIndexDigitalLineScaler) {
    read_daqmx_index(cursor, header, object_where, *index);
  } else {
    read_plain_index(cursor, header, object_where, *index);
  }
  return index;
}

void TdmsParser::read_daqmx_index(MetadataCursor& cursor, std::uint32_t header,
                                  const std::string& object_where, RawIndex& index) {
  const std::uint64_t file_size = file_.size_bytes();
  index.daqmx = true;
  index.data_type = cursor.u32("a DAQmx data type");
  if (index.data_type != kTypeDaqmxRaw) {
    const TypeInfo* type = type_info(index.data_type);
    if (!type || !type->sample) {
      fail(object_where + "DAQmx raw data of data type " + type_name(index.data_type) +
           " is not read");
    }
  }
  const std::uint32_t dimension = cursor.u32("the array dimension");
  if (dimension != 1) {
    fail(object_where + "array dimension " + std::to_string(dimension) + " (only 1 is defined)");
  }
  index.values = cursor.u64("the number of values");
  if (index.values > file_size) {
    fail(object_where + "it declares " + std::to_string(index.values) +
         " values per chunk, more than the file's " + std::to_string(file_size) + " bytes");
  }
  const bool digital = header == kIndexDigitalLineScaler;
  const std::size_t scaler_bytes = digital ? 17 : 20;
  const std::uint32_t scalers = cursor.u32("the number of DAQmx scalers");
  if (scalers == 0 || scalers > cursor.remaining() / scaler_bytes) {
    fail(object_where + "it declares " + std::to_string(scalers) +
         " DAQmx scalers, which the metadata cannot hold");
  }
  for (std::uint32_t s = 0; s < scalers; ++s) {
    DaqmxScaler scaler;
    scaler.type = cursor.u32("a DAQmx scaler");
    scaler.buffer = cursor.u32("a DAQmx scaler");
    const std::uint32_t offset = cursor.u32("a DAQmx scaler");
    if (digital) {
      cursor.skip(1, "a DAQmx scaler");  // sample format bitmap
      scaler.byte_offset = offset / 8;
      scaler.bit = static_cast<int>(offset % 8);
    } else {
      cursor.skip(4, "a DAQmx scaler");  // sample format bitmap
      scaler.byte_offset = offset;
    }
    scaler.scale_id = cursor.u32("a DAQmx scaler");
    const TypeInfo* type = daqmx_type_info(scaler.type);
    if (!type) {
      fail(object_where + "DAQmx scaler " + std::to_string(s) + ": unknown data type " +
           std::to_string(scaler.type));
    }
    if (digital && (type->sample == Sample::F32 || type->sample == Sample::F64)) {
      fail(object_where + "a digital line scaler of data type " + type->name);
    }
    index.scalers.push_back(scaler);
  }
  const std::uint32_t widths = cursor.u32("the number of raw data widths");
  if (widths > cursor.remaining() / 4) {
    fail(object_where + "it declares " + std::to_string(widths) +
         " raw data widths, which the metadata cannot hold");
  }
  for (std::uint32_t w = 0; w < widths; ++w) {
    const std::uint32_t width = cursor.u32("a raw data width");
    if (width == 0) fail(object_where + "raw buffer " + std::to_string(w) + " has width 0");
    if (index.values > file_size / width) {
      fail(object_where + "raw buffer " + std::to_string(w) + " of " +
           std::to_string(index.values) + " values of " + std::to_string(width) +
           " bytes would be larger than the file");
    }
    index.widths_bytes.push_back(width);
  }
  for (std::size_t s = 0; s < index.scalers.size(); ++s) {
    const DaqmxScaler& scaler = index.scalers[s];
    if (scaler.buffer >= index.widths_bytes.size()) {
      fail(object_where + "DAQmx scaler " + std::to_string(s) + " reads raw buffer " +
           std::to_string(scaler.buffer) + ", but there are " +
           std::to_string(index.widths_bytes.size()));
    }
    const std::uint64_t end =
        std::uint64_t{scaler.byte_offset} + daqmx_type_info(scaler.type)->size_bytes;
    if (end > index.widths_bytes[scaler.buffer]) {
      fail(object_where + "DAQmx scaler " + std::to_string(s) + " reads bytes up to " +
           std::to_string(end) + " of a " + std::to_string(index.widths_bytes[scaler.buffer]) +
           "-byte stride");
    }
  }
}

// A plain raw data index; `header` is its length in bytes, itself included.
void TdmsParser::read_plain_index(MetadataCursor& cursor, std::uint32_t header,
                                  const std::string& object_where, RawIndex& index) {
  const std::uint64_t file_size = file_.size_bytes();
  const std::size_t start = cursor.position() - 4;
  if (header < 20) {
    fail(object_where + "raw data index length " + std::to_string(header) +
         " (20, or 28 for strings)");
  }
  if (header - 4 > cursor.remaining()) {
    fail(object_where + "its raw data index of " + std::to_string(header) +
         " bytes points beyond the end of the metadata");
  }
  index.data_type = cursor.u32("a data type");
  const TypeInfo* type = type_info(index.data_type);
  if (!type) fail(object_where + "unknown data type " + hex(index.data_type));
  const std::uint32_t dimension = cursor.u32("the array dimension");
  if (dimension != 1) {
    fail(object_where + "array dimension " + std::to_string(dimension) + " (only 1 is defined)");
  }
  index.values = cursor.u64("the number of values");
  if (index.data_type == kTypeString) {
    if (header < 28) {
      fail(object_where + "a raw data index of strings needs 28 bytes, not " +
           std::to_string(header));
    }
    index.size_bytes = cursor.u64("the size of the strings");
    // Each string has a 4-byte end offset before the text.
    if (index.size_bytes > file_size || index.values > index.size_bytes / 4) {
      fail(object_where + "strings of " + std::to_string(index.size_bytes) + " bytes for " +
           std::to_string(index.values) + " values do not fit the file");
    }
  } else {
    if (type->size_bytes == 0) {
      fail(object_where + "data type " + type_name(index.data_type) +
           " is not read (its size in the raw data is not documented)");
    }
    if (index.values > file_size / type->size_bytes) {
      fail(object_where + "it declares " + std::to_string(index.values) + " values of " +
           type->name + " per chunk, more than the file holds");
    }
    index.size_bytes = index.values * type->size_bytes;
  }
  cursor.skip(start + header - cursor.position(), "the raw data index");
}

void TdmsParser::update_layout(std::uint32_t toc) {
  const std::uint32_t kind = toc & (kTocInterleavedData | kTocDAQmxRawData);
  if (layout_valid_ && kind == layout_kind_) return;
  entries_.clear();
  buffer_offsets_.clear();
  chunk_bytes_ = 0;
  const std::uint64_t file_size = file_.size_bytes();
  auto add_bytes = [&](std::uint64_t bytes) {
    // Both ≤ the file size, so the sum cannot overflow.
    chunk_bytes_ += bytes;
    if (chunk_bytes_ > file_size) {
      fail("its chunks of " + std::to_string(chunk_bytes_) +
           " bytes or more are larger than the file");
    }
  };
  std::vector<std::uint64_t> buffer_values;
  for (const ListEntry& item : list_) {
    if (!item.has_data || item.index->values == 0) continue;
    const RawIndex& index = *item.index;
    const TdmsObject& object = objects_[item.object];
    const std::string object_where = "channel " + in_quotes(valid_utf8(object.path)) + ": ";
    if ((toc & kTocDAQmxRawData) != 0) {
      if (!index.daqmx) fail(object_where + "a plain raw data index in a DAQmx segment");
      if (entries_.empty()) {
        buffer_values.assign(index.widths_bytes.size(), 0);
      } else if (index.widths_bytes != entries_.front().index->widths_bytes) {
        fail(object_where + "its raw data widths differ from those of the other channels");
      }
      for (const DaqmxScaler& scaler : index.scalers) {
        std::uint64_t& values = buffer_values[scaler.buffer];
        if (values != 0 && values != index.values) {
          fail(object_where + "raw buffer " + std::to_string(scaler.buffer) + " holds " +
               std::to_string(values) + " values per chunk for one channel and " +
               std::to_string(index.values) + " for another");
        }
        values = index.values;
      }
    } else {
      if (index.daqmx) {
        fail(object_where + "a DAQmx raw data index in a segment without DAQmx raw data");
      }
      if ((toc & kTocInterleavedData) != 0) {
        if (index.data_type == kTypeString) fail(object_where + "interleaved strings");
        if (!entries_.empty() && entries_.front().index->values != index.values) {
          fail(object_where + "interleaved with " + std::to_string(index.values) +
               " values per chunk, another channel has " +
               std::to_string(entries_.front().index->values));
        }
      }
    }
    entries_.push_back(ChunkEntry{item.object, item.index.get(), 0, 0});
  }
  if ((toc & kTocDAQmxRawData) != 0) {
    if (!entries_.empty()) {
      const std::vector<std::uint32_t>& widths = entries_.front().index->widths_bytes;
      for (std::size_t b = 0; b < widths.size(); ++b) {
        buffer_offsets_.push_back(chunk_bytes_);
        add_bytes(buffer_values[b] * widths[b]);  // checked against the file size on reading
      }
    }
  } else if ((toc & kTocInterleavedData) != 0) {
    std::uint64_t row_bytes = 0;
    for (ChunkEntry& entry : entries_) {
      entry.offset_bytes = row_bytes;
      row_bytes += type_info(entry.index->data_type)->size_bytes;
    }
    for (ChunkEntry& entry : entries_) entry.stride_bytes = row_bytes;
    if (!entries_.empty()) {
      if (entries_.front().index->values > file_size / row_bytes) {
        fail("its interleaved rows of " + std::to_string(row_bytes) + " bytes are more than " +
             "the file holds");
      }
      add_bytes(entries_.front().index->values * row_bytes);
    }
  } else {
    for (ChunkEntry& entry : entries_) {
      entry.offset_bytes = chunk_bytes_;
      entry.stride_bytes = type_info(entry.index->data_type)->size_bytes;
      add_bytes(entry.index->size_bytes);
    }
  }
  layout_valid_ = true;
  layout_kind_ = kind;
}

}  // namespace oscilab::daq::tdms
