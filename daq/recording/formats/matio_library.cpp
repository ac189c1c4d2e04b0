// The MAT-file reader's work in matio (matio_library.h): part of oscilab_hdf5_module, run in a
// child process. Real numeric matrices of Level 4 and Level 5 files are signals; see "MAT-File
// Format" (The MathWorks, 2021) for the Level 5 layout. (v7.3 files are read by hdf5_library.)
#include "daq/recording/formats/matio_library.h"
#include "daq/recording/file_bytes.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <vector>

#include <hdf5.h>
#include <matio.h>

#include "daq/recording/formats/contents_text.h"
#include "daq/recording/formats/matio_handles.h"
#include "daq/recording/message_text.h"

namespace oscilab::daq {
namespace {

// The last error matio logged in this (child) process, for the reply.
std::string& matio_message() {
  static std::string message;
  return message;
}

void log_matio(int level, char* message) {
  if ((level & (MATIO_LOG_LEVEL_ERROR | MATIO_LOG_LEVEL_CRITICAL)) != 0 && message != nullptr &&
      matio_message().empty()) {
    matio_message() = message;
    std::replace(matio_message().begin(), matio_message().end(), '\n', ' ');
  }
}

// What the child does first: matio's messages into matio_message() instead of stderr, and
// libhdf5's error stack (v7.3 files) silenced.
void quiet_libraries() {
  Mat_LogInitFunc("oscilab", log_matio);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

std::string with_matio_message(std::string problem) {
  if (!matio_message().empty()) problem += " (matio: " + matio_message() + ")";
  return problem;
}

// The numeric classes: their name as a stored type and their size in bytes; 0 for the others.
std::size_t class_bytes(matio_classes class_type) {
  switch (class_type) {
    case MAT_C_DOUBLE:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return 8;
    case MAT_C_SINGLE:
    case MAT_C_INT32:
    case MAT_C_UINT32:
      return 4;
    case MAT_C_INT16:
    case MAT_C_UINT16:
      return 2;
    case MAT_C_INT8:
    case MAT_C_UINT8:
      return 1;
    default:
      return 0;
  }
}

std::string class_name(matio_classes class_type) {
  switch (class_type) {
    case MAT_C_DOUBLE:
      return "float64";
    case MAT_C_SINGLE:
      return "float32";
    case MAT_C_INT8:
      return "int8";
    case MAT_C_UINT8:
      return "uint8";
    case MAT_C_INT16:
      return "int16";
    case MAT_C_UINT16:
      return "uint16";
    case MAT_C_INT32:
      return "int32";
    case MAT_C_UINT32:
      return "uint32";
    case MAT_C_INT64:
      return "int64";
    case MAT_C_UINT64:
      return "uint64";
    case MAT_C_CELL:
      return "a cell array";
    case MAT_C_STRUCT:
      return "a struct";
    case MAT_C_OBJECT:
      return "an object";
    case MAT_C_CHAR:
      return "a char array";
    case MAT_C_SPARSE:
      return "a sparse matrix";
    case MAT_C_FUNCTION:
      return "a function handle";
    case MAT_C_OPAQUE:
      return "an opaque object (string, table, datetime, ...)";
    default:
      return "of no class (empty)";
  }
}

// Samples run along the longer dimension of a matrix (rows when it is square): the dimension
// index (0: rows, 1: columns) for `dims`.
int sample_dimension(std::size_t rows, std::size_t cols) { return cols > rows ? 1 : 0; }

// Why a variable is not a signal, or "" when it is one.
std::string refusal(const matvar_t& variable, std::size_t file_size) {
  if (class_bytes(variable.class_type) == 0) {
    return "it is " + class_name(variable.class_type) + ", not a numeric matrix";
  }
  if (variable.isComplex) return "it is complex";
  if (variable.rank != 2 || variable.dims == nullptr) {
    return "it has " + std::to_string(variable.rank) + " dimensions, not 2";
  }
  // Every value takes at least one byte of the file, or 1/1032 of one when compressed.
  const std::size_t rows = variable.dims[0];
  const std::size_t cols = variable.dims[1];
  const std::size_t bound =
      file_size *
      (variable.compression == MAT_COMPRESSION_NONE ? std::size_t{1} : kMaxDeflateRatio);
  if (rows > 0 && cols > 0 && (rows > bound || cols > bound / rows)) {
    return "it declares " + std::to_string(rows) + " x " + std::to_string(cols) +
           " values, more than the file can hold";
  }
  return "";
}

std::string container_text(mat_t* mat, int variables, int compressed) {
  switch (Mat_GetVersion(mat)) {
    case MAT_FT_MAT73:
      return "MATLAB 7.3 MAT-file (HDF5)";
    case MAT_FT_MAT4:
      return "MATLAB 4 MAT-file";
    default:
      if (compressed == 0) return "MATLAB 5.0 MAT-file (v5, uncompressed)";
      if (compressed == variables) return "MATLAB 5.0 MAT-file (v5, compressed)";
      return "MATLAB 5.0 MAT-file (v5, " + std::to_string(compressed) + " of " +
             std::to_string(variables) + " variables compressed)";
  }
}

}  // namespace

ChildReply describe_mat_file(const std::string& path) {
  quiet_libraries();
  const MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat) return {false, with_matio_message("not a MAT-file matio can open")};
  const std::size_t size = file_bytes(path);
  FileContents contents;
  nlohmann::json skipped = nlohmann::json::array();
  std::set<std::string> names;
  int variables = 0;
  int compressed = 0;
  while (MatVar variable{Mat_VarReadNextInfo(mat.get())}) {
    ++variables;
    if (variable->compression != MAT_COMPRESSION_NONE) ++compressed;
    const std::string name = variable->name != nullptr ? variable->name : "";
    if (name.empty() || !names.insert(name).second) {
      skipped.push_back({{"name", name},
                         {"reason", name.empty() ? "it has no name"
                                                 : "a second variable of "
                                                   "that name"}});
      continue;
    }
    if (const std::string reason = refusal(*variable, size); !reason.empty()) {
      skipped.push_back({{"name", name}, {"reason", reason}});
      continue;
    }
    const std::size_t rows = variable->dims[0];
    const std::size_t cols = variable->dims[1];
    FileSignal signal;
    signal.name = name;
    const bool vector = rows <= 1 || cols <= 1;
    signal.sample_count = static_cast<std::int64_t>(vector ? rows * cols : std::max(rows, cols));
    signal.columns = vector ? 1 : static_cast<std::int64_t>(std::min(rows, cols));
    // matio tells a Level 5 element's storage type (miUINT8 for a double of small integers)
    // only when it reads the values: the class stands for it.
    signal.stored_type = variable->isLogical ? "logical" : class_name(variable->class_type);
    signal.properties["dims"] = {rows, cols};
    if (!vector) {
      signal.properties["column_k_is"] =
          sample_dimension(rows, cols) == 0 ? "column k of the matrix" : "row k of the matrix";
    }
    contents.file_signals.push_back(std::move(signal));
  }
  if (!matio_message().empty()) return {false, with_matio_message("matio cannot read it")};
  if (variables == 0) return {false, "no variables (an empty or damaged MAT-file)"};
  contents.container = container_text(mat.get(), variables, compressed);
  const char* header = Mat_GetHeader(mat.get());
  if (header != nullptr) {
    std::string text(header, strnlen(header, 116));
    while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
    contents.properties["header"] = text;
  }
  contents.properties["skipped"] = skipped;
  return {true, contents_to_text(contents)};
}

namespace {

template <typename T>
void append_as_double(const char* bytes, std::size_t count, std::vector<double>& out) {
  for (std::size_t i = 0; i < count; ++i) {
    T value;
    std::memcpy(&value, bytes + i * sizeof(T), sizeof(T));
    out.push_back(static_cast<double>(value));
  }
}

}  // namespace

ChildReply read_mat_values(const std::string& path, const std::string& name,
                           std::int64_t sample_count, std::int64_t columns, int column) {
  quiet_libraries();
  const MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat) return {false, with_matio_message("not a MAT-file matio can open")};
  const MatVar variable{Mat_VarReadInfo(mat.get(), name.c_str())};
  const std::string where = "variable " + in_quotes(name);
  if (!variable) return {false, with_matio_message(where + ": matio cannot find it")};
  if (const std::string reason = refusal(*variable, file_bytes(path)); !reason.empty()) {
    return {false, where + ": " + reason};
  }
  const std::size_t rows = variable->dims[0];
  const std::size_t cols = variable->dims[1];
  const bool vector = rows <= 1 || cols <= 1;
  const auto count = static_cast<std::size_t>(sample_count);
  const std::size_t expected_columns = vector ? 1 : std::min(rows, cols);
  if ((vector ? rows * cols : std::max(rows, cols)) != count ||
      static_cast<std::int64_t>(expected_columns) != columns) {
    return {false, where + ": its size changed while it was read"};
  }
  // The whole variable, then the column: matio 1.5.23's Mat_VarReadData ignores the column
  // offset of a one-column slab of a Level 5 matrix, so it is not used.
  const MatVar full{Mat_VarRead(mat.get(), name.c_str())};
  if (!full || full->data == nullptr || full->class_type != variable->class_type ||
      full->rank != 2 || full->dims[0] != rows || full->dims[1] != cols ||
      full->nbytes < rows * cols * class_bytes(full->class_type)) {
    return {false, with_matio_message(where + ": matio cannot read its values")};
  }
  // Column-major: element (r, c) at r + c * rows. Samples run along `along`; `column` is the
  // index in the other dimension.
  const int along = vector ? (rows == 1 ? 1 : 0) : sample_dimension(rows, cols);
  const std::size_t fixed = static_cast<std::size_t>(std::max(column, 0));
  const std::size_t first = along == 0 ? fixed * rows : fixed;
  const std::size_t step = along == 0 ? 1 : rows;
  const std::size_t bytes = class_bytes(variable->class_type);
  std::vector<char> buffer(count * bytes);
  const char* source = static_cast<const char*>(full->data);
  for (std::size_t i = 0; i < count; ++i) {
    std::memcpy(buffer.data() + i * bytes, source + (first + i * step) * bytes, bytes);
  }
  std::vector<double> values;
  values.reserve(count);
  const char* data = buffer.data();
  switch (variable->class_type) {
    case MAT_C_DOUBLE:
      append_as_double<double>(data, count, values);
      break;
    case MAT_C_SINGLE:
      append_as_double<float>(data, count, values);
      break;
    case MAT_C_INT8:
      append_as_double<std::int8_t>(data, count, values);
      break;
    case MAT_C_UINT8:
      append_as_double<std::uint8_t>(data, count, values);
      break;
    case MAT_C_INT16:
      append_as_double<std::int16_t>(data, count, values);
      break;
    case MAT_C_UINT16:
      append_as_double<std::uint16_t>(data, count, values);
      break;
    case MAT_C_INT32:
      append_as_double<std::int32_t>(data, count, values);
      break;
    case MAT_C_UINT32:
      append_as_double<std::uint32_t>(data, count, values);
      break;
    case MAT_C_INT64:
      append_as_double<std::int64_t>(data, count, values);
      break;
    case MAT_C_UINT64:
      append_as_double<std::uint64_t>(data, count, values);
      break;
    default:
      return {false, where + ": not numeric"};
  }
  std::string reply(values.size() * sizeof(double), '\0');
  std::memcpy(reply.data(), values.data(), reply.size());
  return {true, std::move(reply)};
}

}  // namespace oscilab::daq
