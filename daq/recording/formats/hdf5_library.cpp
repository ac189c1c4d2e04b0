// The HDF5 reader's work in libhdf5's C API (hdf5_library.h): part of oscilab_hdf5_module, run in
// a child process. Every numeric 1-D or 2-D dataset is a signal named by its path; the rate and
// the unit come from attributes. See "HDF5 File Format Specification Version 3.0" (The HDF
// Group).
#include "daq/recording/formats/hdf5_library.h"
#include "daq/recording/file_bytes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>

#include <hdf5.h>

#include "daq/recording/formats/contents_text.h"
#include "daq/recording/message_text.h"

namespace oscilab::daq {
namespace {

// Attributes that state the rate, looked for in this order on the dataset, then on each group
// above it up to the root; the nearest one wins.
const std::vector<std::string> kRateHzAttributes = {"sample_rate_hz", "sample_rate",
                                                    "sampling_rate", "fs", "rate"};
const std::vector<std::string> kIntervalSAttributes = {
    "dt", "dT", "wf_increment", "time_step", "sampling_interval", "increment"};
// Attributes of the dataset that state its unit.
const std::vector<std::string> kUnitAttributes = {"unit", "units", "Unit", "unit_string"};

constexpr int kMaxDepth = 64;                // groups within groups
constexpr std::size_t kMaxObjects = 20000;   // links visited in one file
constexpr std::size_t kMaxAttributes = 64;   // attributes listed per object
constexpr std::size_t kMaxTextBytes = 4096;  // a string attribute longer than this is cut

// An hid_t closed by its own H5?close when it goes out of scope.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

// The value of a numeric attribute holding one value, a string attribute, or null otherwise.
nlohmann::json attribute_value(hid_t attribute) {
  const Handle type(H5Aget_type(attribute), H5Tclose);
  const Handle space(H5Aget_space(attribute), H5Sclose);
  if (!type.valid() || !space.valid()) return nullptr;
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (points != 1) return nullptr;
  if (type_class == H5T_INTEGER || type_class == H5T_FLOAT) {
    double value = 0.0;
    if (H5Aread(attribute, H5T_NATIVE_DOUBLE, &value) < 0) return nullptr;
    return value;
  }
  if (type_class != H5T_STRING) return nullptr;
  const htri_t variable = H5Tis_variable_str(type.get());
  const Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (variable < 0 || !memory_type.valid()) return nullptr;
  // The file's character set (h5py writes UTF-8): libhdf5 does not convert between them.
  if (H5Tset_cset(memory_type.get(), H5Tget_cset(type.get())) < 0) return nullptr;
  std::string text;
  if (variable > 0) {
    if (H5Tset_size(memory_type.get(), H5T_VARIABLE) < 0) return nullptr;
    char* pointer = nullptr;
    if (H5Aread(attribute, memory_type.get(), &pointer) < 0) return nullptr;
    if (pointer != nullptr) {
      text.assign(pointer, strnlen(pointer, kMaxTextBytes));
      H5free_memory(pointer);
    }
  } else {
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0 || size > (std::size_t{1} << 20)) return nullptr;
    // One more byte than stored: a null-terminated memory string of the stored size would drop
    // the last character of a null-padded one.
    if (H5Tset_size(memory_type.get(), size + 1) < 0) return nullptr;
    std::string buffer(size + 1, '\0');
    if (H5Aread(attribute, memory_type.get(), buffer.data()) < 0) return nullptr;
    text.assign(buffer.c_str(), strnlen(buffer.c_str(), std::min(size, kMaxTextBytes)));
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* data) {
  auto* names = static_cast<std::vector<std::string>*>(data);
  names->emplace_back(name);
  return names->size() >= kMaxAttributes ? 1 : 0;
}

// The attributes of an object that hold one number or a string, by name (at most 64).
nlohmann::json attributes_of(hid_t object) {
  std::vector<std::string> names;
  hsize_t index = 0;
  H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute_name, &names);
  nlohmann::json attributes = nlohmann::json::object();
  for (const std::string& name : names) {
    const Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), H5Aclose);
    if (!attribute.valid()) continue;
    nlohmann::json value = attribute_value(attribute.get());
    if (!value.is_null()) attributes[name] = std::move(value);
  }
  return attributes;
}

// "/a/b/c" → "/a/b"; "/a" → "/".
std::string parent_path(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == 0 || slash == std::string::npos ? "/" : path.substr(0, slash);
}

// The rate the nearest rate attribute states, with where it comes from, in `signal`.
void find_rate(hid_t file, const std::string& dataset_path, const nlohmann::json& own,
               FileSignal& signal) {
  std::string object_path = dataset_path;
  nlohmann::json attributes = own;
  for (int depth = 0; depth <= kMaxDepth; ++depth) {
    auto look = [&](const std::vector<std::string>& names, bool interval) {
      for (const std::string& name : names) {
        const auto it = attributes.find(name);
        if (it == attributes.end() || !it->is_number()) continue;
        const double value = it->get<double>();
        const std::string source = "attribute " + in_quotes(name) + " of " + object_path;
        if (!std::isfinite(value) || value <= 0.0) {
          signal.properties["sample_rate_ignored"] =
              source + " is " + number_text(value) + (interval ? " s" : " Hz") +
              ", not a positive " + (interval ? "interval" : "rate");
        } else {
          signal.sample_rate_hz = interval ? 1.0 / value : value;
          signal.properties["sample_rate_from"] =
              source + " (" + number_text(value) + (interval ? " s)" : " Hz)");
        }
        return true;
      }
      return false;
    };
    if (look(kRateHzAttributes, false) || look(kIntervalSAttributes, true)) return;
    if (object_path == "/") return;
    object_path = parent_path(object_path);
    const Handle group(H5Oopen(file, object_path.c_str(), H5P_DEFAULT), H5Oclose);
    if (!group.valid()) return;
    attributes = attributes_of(group.get());
  }
}

std::string type_name(hid_t type) {
  const H5T_class_t type_class = H5Tget_class(type);
  const std::size_t bits = H5Tget_size(type) * 8;
  if (type_class == H5T_FLOAT) return "float" + std::to_string(bits);
  return (H5Tget_sign(type) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
}

std::string class_refusal(H5T_class_t type_class) {
  switch (type_class) {
    case H5T_INTEGER:
    case H5T_FLOAT:
      return "";
    case H5T_COMPOUND:
      return "compound type";
    case H5T_STRING:
      return "strings";
    case H5T_VLEN:
      return "variable-length type";
    case H5T_ENUM:
      return "enumeration (booleans are one)";
    case H5T_ARRAY:
      return "array type";
    case H5T_REFERENCE:
      return "references";
    case H5T_OPAQUE:
      return "opaque type";
    case H5T_BITFIELD:
      return "bit field";
    default:
      return "a type that is not a number";
  }
}

// How many bytes of the file a dataset's values may take per value: a filtered (compressed)
// dataset may expand up to deflate's ratio.
bool has_filters(hid_t dataset) {
  const Handle plist(H5Dget_create_plist(dataset), H5Pclose);
  return plist.valid() && H5Pget_nfilters(plist.get()) > 0;
}

struct DatasetShape {
  hsize_t rows = 0;
  hsize_t cols = 1;  // 1 for a 1-D dataset
  int rank = 0;
};

// Why a dataset is not a signal, or "" with its shape and type in `shape`.
std::string dataset_refusal(hid_t dataset, hid_t type, std::size_t file_size, DatasetShape& shape) {
  if (std::string reason = class_refusal(H5Tget_class(type)); !reason.empty()) {
    return "not numeric: " + reason;
  }
  const std::size_t value_bytes = H5Tget_size(type);
  if (value_bytes == 0 || value_bytes > 16) return "numbers of an unusual size";
  const Handle space(H5Dget_space(dataset), H5Sclose);
  if (!space.valid()) return "its dataspace cannot be read";
  const H5S_class_t space_class = H5Sget_simple_extent_type(space.get());
  if (space_class == H5S_SCALAR) return "a single value (scalar)";
  if (space_class != H5S_SIMPLE) return "no values (null dataspace)";
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 1 || rank > 2) return std::to_string(rank) + " dimensions, not 1 or 2";
  // Values kept in other files (external raw data, virtual datasets) are not read: a file must
  // not make Oscilab read whatever other file it names.
  {
    const Handle plist(H5Dget_create_plist(dataset), H5Pclose);
    if (!plist.valid()) return "its creation properties cannot be read";
    if (H5Pget_layout(plist.get()) == H5D_VIRTUAL)
      return "a virtual dataset (values in other files)";
    if (H5Pget_external_count(plist.get()) != 0) return "its values are in external files";
  }
  hsize_t dims[2] = {0, 1};
  if (H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0) return "unreadable dimensions";
  shape = {dims[0], rank == 2 ? dims[1] : 1, rank};
  // Every value takes its size in the file, or 1/1032 of it when compressed.
  const std::size_t ratio = has_filters(dataset) ? kMaxDeflateRatio : 1;
  const hsize_t storage = H5Dget_storage_size(dataset);
  const hsize_t bound = storage / value_bytes * ratio;
  if (storage > file_size) return "its storage exceeds the file";
  if (shape.rows > 0 && shape.cols > 0 && (shape.rows > bound || shape.cols > bound / shape.rows)) {
    return "it declares " + std::to_string(shape.rows) + " x " + std::to_string(shape.cols) +
           " values, more than the file stores";
  }
  return "";
}

struct Walk {
  hid_t file = -1;
  bool mat73 = false;  // a MAT v7.3 file: MATLAB's variables at the root, transposed
  std::size_t file_size = 0;
  std::set<std::pair<unsigned long, haddr_t>> visited;  // (file number, object address)
  std::size_t objects = 0;
  FileContents contents;
  nlohmann::json skipped = nlohmann::json::array();
};

struct Link {
  std::string name;
  H5L_type_t type;
};

herr_t collect_link(hid_t, const char* name, const H5L_info_t* info, void* data) {
  auto* links = static_cast<std::vector<Link>*>(data);
  links->push_back({name, info->type});
  return links->size() >= kMaxObjects ? 1 : 0;
}

// Whether the object was seen before (a second hard link or a cycle); marks it seen.
bool seen_before(Walk& walk, hid_t object) {
  H5O_info_t info;
  if (H5Oget_info2(object, &info, H5O_INFO_BASIC) < 0) return true;
  return !walk.visited.insert({info.fileno, info.addr}).second;
}

// The dimension samples run along: the longer one; when square, dim 0, or dim 1 in a MAT v7.3
// file (MATLAB's rows, which it stores as HDF5's second dimension).
int sample_dimension(const DatasetShape& shape, bool mat73) {
  if (shape.rank == 1 || shape.cols <= 1) return 0;
  if (shape.rows <= 1) return 1;
  if (shape.rows == shape.cols) return mat73 ? 1 : 0;
  return shape.cols > shape.rows ? 1 : 0;
}

void describe_dataset(Walk& walk, hid_t dataset, const std::string& path,
                      const std::string& stored_type = "") {
  const Handle type(H5Dget_type(dataset), H5Tclose);
  DatasetShape shape;
  const std::string reason = type.valid()
                                 ? dataset_refusal(dataset, type.get(), walk.file_size, shape)
                                 : "its type cannot be read";
  if (!reason.empty()) {
    walk.skipped.push_back({{"name", path}, {"reason", reason}});
    return;
  }
  FileSignal signal;
  signal.name = path;
  const bool vector = shape.rank == 1 || shape.rows <= 1 || shape.cols <= 1;
  signal.sample_count = static_cast<std::int64_t>(vector ? shape.rows * shape.cols
                                                         : std::max(shape.rows, shape.cols));
  signal.columns = vector ? 1 : static_cast<std::int64_t>(std::min(shape.rows, shape.cols));
  signal.stored_type = stored_type.empty() ? type_name(type.get()) : stored_type;
  if (H5Tget_order(type.get()) == H5T_ORDER_BE) signal.properties["byte_order"] = "big-endian";
  if (walk.mat73) {
    signal.properties["dims"] = {shape.cols, shape.rows};  // MATLAB's rows x columns
    if (!vector) {
      signal.properties["column_k_is"] =
          sample_dimension(shape, true) == 1 ? "column k of the matrix" : "row k of the matrix";
    }
  } else {
    signal.properties["dims"] =
        shape.rank == 1 ? nlohmann::json{shape.rows} : nlohmann::json{shape.rows, shape.cols};
    if (!vector) {
      signal.properties["column_k_is"] =
          sample_dimension(shape, false) == 1 ? "data[k, :]" : "data[:, k]";
    }
  }
  const nlohmann::json attributes = attributes_of(dataset);
  for (const std::string& name : kUnitAttributes) {
    const auto it = attributes.find(name);
    if (it != attributes.end() && it->is_string()) {
      signal.unit = it->get<std::string>();
      break;
    }
  }
  if (!walk.mat73) {
    find_rate(walk.file, path, attributes, signal);
    if (!attributes.empty()) signal.properties["attributes"] = attributes;
  }
  walk.contents.file_signals.push_back(std::move(signal));
}

// MATLAB's class of a v7.3 variable (its "MATLAB_class" attribute) as a stored type, or "" when
// it is not a numeric matrix.
std::string mat73_stored_type(const std::string& matlab_class) {
  for (const char* numeric :
       {"int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "logical"}) {
    if (matlab_class == numeric) return matlab_class;
  }
  if (matlab_class == "double") return "float64";
  if (matlab_class == "single") return "float32";
  return "";
}

// A MAT v7.3 variable: a dataset at the root with a MATLAB_class attribute ("MAT-File Format",
// MathWorks, v7.3). Structs are groups; cells, strings and objects hold references.
void describe_mat73_variable(Walk& walk, hid_t object, const std::string& name, H5I_type_t kind) {
  if (name == "#refs#" || name == "#subsystem#") return;  // MATLAB's own storage
  const nlohmann::json attributes = attributes_of(object);
  const std::string matlab_class = attributes.value("MATLAB_class", std::string());
  const std::string stored_type = mat73_stored_type(matlab_class);
  if (kind != H5I_DATASET || stored_type.empty() || attributes.contains("MATLAB_sparse")) {
    walk.skipped.push_back(
        {{"name", name},
         {"reason", attributes.contains("MATLAB_sparse") ? "it is a sparse matrix"
                    : matlab_class.empty()
                        ? "it has no MATLAB_class"
                        : "it is of class " + matlab_class + ", not a numeric matrix"}});
    return;
  }
  if (attributes.value("MATLAB_empty", 0.0) != 0.0) {
    FileSignal signal;  // MATLAB stores an empty array's dimensions as its values
    signal.name = name;
    signal.stored_type = stored_type;
    walk.contents.file_signals.push_back(std::move(signal));
    return;
  }
  describe_dataset(walk, object, name, stored_type);
}

void walk_group(Walk& walk, hid_t group, const std::string& path, int depth) {
  std::vector<Link> links;
  hsize_t index = 0;
  if (H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &index, collect_link, &links) < 0) {
    walk.skipped.push_back({{"name", path}, {"reason", "its members cannot be listed"}});
  }
  for (const Link& link : links) {
    if (++walk.objects > kMaxObjects) {
      walk.skipped.push_back(
          {{"name", path}, {"reason", "more than 20000 objects; rest not listed"}});
      return;
    }
    const std::string member = (path == "/" ? "" : path) + "/" + link.name;
    if (link.type != H5L_TYPE_HARD) {
      walk.skipped.push_back(
          {{"name", member},
           {"reason", link.type == H5L_TYPE_SOFT ? "a soft link (not followed)"
                                                 : "an external or user-defined link (not "
                                                   "followed)"}});
      continue;
    }
    const Handle object(H5Oopen(group, link.name.c_str(), H5P_DEFAULT), H5Oclose);
    if (!object.valid()) {
      walk.skipped.push_back({{"name", member}, {"reason", "it cannot be opened"}});
      continue;
    }
    const H5I_type_t kind = H5Iget_type(object.get());
    if (kind != H5I_GROUP && kind != H5I_DATASET) continue;  // named datatypes
    if (seen_before(walk, object.get())) {
      walk.skipped.push_back({{"name", member},
                              {"reason",
                               "another link to an object listed "
                               "already"}});
      continue;
    }
    if (walk.mat73) {
      describe_mat73_variable(walk, object.get(), link.name, kind);
    } else if (kind == H5I_DATASET) {
      describe_dataset(walk, object.get(), member);
    } else if (depth >= kMaxDepth) {
      walk.skipped.push_back({{"name", member}, {"reason", "groups nested more than 64 deep"}});
    } else {
      walk_group(walk, object.get(), member, depth + 1);
    }
  }
}

void quiet_library() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

// The innermost message of libhdf5's error stack, e.g. "file signature not found".
herr_t innermost_error(unsigned, const H5E_error2_t* error, void* data) {
  if (error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
  return 0;
}

std::string library_problem(const std::string& what) {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, innermost_error, &message);
  return message.empty() ? what : what + " (libhdf5: " + message + ")";
}

hid_t open_file(const std::string& path) {
  return H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
}

}  // namespace

void initialise_hdf5() { H5open(); }

ChildReply describe_hdf5_file(const std::string& path, bool mat73) {
  quiet_library();
  const Handle file(open_file(path), H5Fclose);
  if (!file.valid()) return {false, library_problem("not an HDF5 file libhdf5 can open")};
  Walk walk;
  walk.file = file.get();
  walk.mat73 = mat73;
  walk.file_size = file_bytes(path);
  const Handle root(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose);
  if (!root.valid()) return {false, library_problem("its root group cannot be opened")};
  seen_before(walk, root.get());
  walk_group(walk, root.get(), "/", mat73 ? kMaxDepth : 0);
  hsize_t user_block = 0;
  const Handle plist(H5Fget_create_plist(file.get()), H5Pclose);
  if (plist.valid()) H5Pget_userblock(plist.get(), &user_block);
  unsigned super_version = 0;
  walk.contents.container = mat73 ? "MATLAB 7.3 MAT-file (HDF5" : "HDF5";
  if (plist.valid() &&
      H5Pget_version(plist.get(), &super_version, nullptr, nullptr, nullptr) >= 0) {
    walk.contents.container += ", superblock version " + std::to_string(super_version);
  }
  if (user_block > 0) {
    walk.contents.container += ", " + std::to_string(user_block) + "-byte user block";
  }
  if (mat73) walk.contents.container += ")";
  if (!mat73) walk.contents.properties["attributes"] = attributes_of(root.get());
  walk.contents.properties["skipped"] = walk.skipped;
  return {true, contents_to_text(walk.contents)};
}

ChildReply read_hdf5_values(const std::string& path, const std::string& name,
                            std::int64_t sample_count, int column, bool mat73) {
  quiet_library();
  const std::string where = (mat73 ? "variable " : "dataset ") + name;
  const std::string dataset_path = mat73 ? "/" + name : name;
  const Handle file(open_file(path), H5Fclose);
  if (!file.valid()) return {false, library_problem("not an HDF5 file libhdf5 can open")};
  const Handle dataset(H5Dopen2(file.get(), dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) return {false, library_problem(where + ": cannot be opened")};
  const Handle type(H5Dget_type(dataset.get()), H5Tclose);
  DatasetShape shape;
  const std::string reason =
      type.valid() ? dataset_refusal(dataset.get(), type.get(), file_bytes(path), shape)
                   : "its type cannot be read";
  if (!reason.empty()) return {false, where + ": " + reason};
  const bool vector = shape.rank == 1 || shape.rows <= 1 || shape.cols <= 1;
  const auto count = static_cast<hsize_t>(sample_count);
  if ((vector ? shape.rows * shape.cols : std::max(shape.rows, shape.cols)) != count) {
    return {false, where + ": its size changed while it was read"};
  }
  const Handle file_space(H5Dget_space(dataset.get()), H5Sclose);
  if (!file_space.valid()) return {false, library_problem(where + ": no dataspace")};
  if (shape.rank == 2) {
    // Samples along the longer dimension (dim 0 when square); `column` picks the other index.
    const int along = sample_dimension(shape, mat73);
    hsize_t start[2] = {0, 0};
    hsize_t edge[2] = {1, 1};
    start[1 - along] = static_cast<hsize_t>(std::max(column, 0));
    edge[along] = count;
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, edge, nullptr) < 0) {
      return {false, library_problem(where + ": cannot select its column")};
    }
  }
  const Handle memory_space(H5Screate_simple(1, &count, nullptr), H5Sclose);
  std::string reply(count * sizeof(double), '\0');
  if (!memory_space.valid() || H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, memory_space.get(),
                                       file_space.get(), H5P_DEFAULT, reply.data()) < 0) {
    return {false, library_problem(where + ": its values cannot be read")};
  }
  return {true, std::move(reply)};
}

}  // namespace oscilab::daq
