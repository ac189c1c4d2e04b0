// JSON, array and path conversions between Python and the C++ core.
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "bindings.h"

namespace oscilab::python {

py::object to_python(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(json.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(json.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(json.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(json.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(json.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const auto& item : json) list.append(to_python(item));
      return list;
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (auto it = json.begin(); it != json.end(); ++it) dict[py::str(it.key())] = to_python(*it);
      return dict;
    }
    default:
      return py::none();  // binary and discarded values never come out of the core
  }
}

namespace {

// A Python value nested like any JSON Oscilab parses, at most kMaxJsonDepth deep: a deeper one
// (or a list holding itself) would overflow the stack here and in the core.
nlohmann::json to_json_at(const py::handle& object, const std::string& where, std::size_t depth) {
  if (object.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(object)) return object.cast<bool>();
  if (py::isinstance<py::int_>(object)) return object.cast<std::int64_t>();
  if (py::isinstance<py::float_>(object)) return object.cast<double>();
  if (py::isinstance<py::str>(object)) return object.cast<std::string>();
  const bool nested = py::isinstance<py::dict>(object) || py::isinstance<py::list>(object) ||
                      py::isinstance<py::tuple>(object) || py::isinstance<py::array>(object);
  if (nested && depth >= kMaxJsonDepth) {
    throw InputError(where + ": nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  }
  if (py::isinstance<py::dict>(object)) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : object.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key)) throw InputError(where + ": dict keys must be str");
      const std::string name = key.cast<std::string>();
      out[name] = to_json_at(value, where + "." + name, depth + 1);
    }
    return out;
  }
  if (py::isinstance<py::list>(object) || py::isinstance<py::tuple>(object) ||
      py::isinstance<py::array>(object)) {
    nlohmann::json out = nlohmann::json::array();
    std::size_t i = 0;
    for (const auto& item : object) {
      out.push_back(to_json_at(item, where + "[" + std::to_string(i++) + "]", depth + 1));
    }
    return out;
  }
  // NumPy scalars and other numbers: through their Python value.
  if (py::hasattr(object, "item") && py::hasattr(object, "dtype")) {
    return to_json_at(object.attr("item")(), where, depth);
  }
  throw InputError(where + ": cannot be written as JSON (" +
                   py::str(py::type::of(object).attr("__name__")).cast<std::string>() + ")");
}

}  // namespace

nlohmann::json to_json(const py::handle& object, const std::string& where) {
  return to_json_at(object, where, 0);
}

nlohmann::json json_argument(const py::handle& object, const std::string& where) {
  if (py::isinstance<py::str>(object)) {
    return parse_json_within_limits(object.cast<std::string>(), where);
  }
  return to_json(object, where);
}

py::array_t<double> to_array(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  if (v.size() > 0) std::memcpy(out.mutable_data(), v.data(), sizeof(double) * v.size());
  return out;
}

py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(out.mutable_data(), v.data(), sizeof(double) * v.size());
  return out;
}

py::array_t<double> to_array(const Eigen::MatrixXd& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) view(r, c) = m(r, c);
  }
  return out;
}

py::array_t<std::int64_t> to_int_array(const std::vector<int>& v) {
  py::array_t<std::int64_t> out(static_cast<py::ssize_t>(v.size()));
  std::int64_t* data = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) data[i] = v[i];
  return out;
}

Eigen::VectorXd to_vector(const py::handle& object, const std::string& where) {
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
  } catch (const py::error_already_set&) {
    throw InputError(where + ": not an array of numbers");
  }
  if (!array || array.ndim() != 1) throw InputError(where + ": must be a 1-D array of numbers");
  Eigen::VectorXd out(array.shape(0));
  if (out.size() > 0) std::memcpy(out.data(), array.data(), sizeof(double) * out.size());
  return out;
}

bool is_path(const py::handle& object) {
  return py::isinstance<py::str>(object) || py::isinstance<py::bytes>(object) ||
         py::hasattr(object, "__fspath__");
}

std::string path_string(const py::handle& object) {
  // os.fsdecode(os.fspath(p)): str, bytes (file-system encoding) and os.PathLike, as open() takes.
  const py::module_ os = py::module_::import("os");
  return os.attr("fsdecode")(os.attr("fspath")(object)).cast<std::string>();
}

namespace {

std::string type_name(const py::handle& object) {
  return py::str(py::type::of(object).attr("__name__")).cast<std::string>();
}

}  // namespace

double number_argument(const py::handle& object, const std::string& name) {
  const bool number = (py::isinstance<py::int_>(object) || py::isinstance<py::float_>(object) ||
                       py::hasattr(object, "__float__")) &&
                      !py::isinstance<py::str>(object) && !py::isinstance<py::bytes>(object);
  if (!number) throw py::type_error(name + ": expected a number, not " + type_name(object));
  return py::float_(py::reinterpret_borrow<py::object>(object)).cast<double>();
}

std::string text_argument(const py::handle& object, const std::string& name) {
  if (!py::isinstance<py::str>(object)) {
    throw py::type_error(name + ": expected a str, not " + type_name(object));
  }
  return object.cast<std::string>();
}

analysis::Well well_argument(const std::string& well) {
  const std::optional<analysis::Well> parsed = analysis::parse_well(well);
  if (parsed != analysis::Well::Positive && parsed != analysis::Well::Negative) {
    throw InputError("well: \"" + well + "\" is not positive or negative");
  }
  return *parsed;
}

std::vector<analysis::Well> wells_argument(const std::string& well) {
  if (well == "both") return {analysis::Well::Positive, analysis::Well::Negative};
  return {well_argument(well)};
}

std::vector<std::string> path_list(const py::handle& object, const std::string& where) {
  if (is_path(object)) return {path_string(object)};
  std::vector<std::string> out;
  try {
    for (const auto& item : object) out.push_back(path_string(item));
  } catch (const py::error_already_set&) {
    throw InputError(where + ": expected a path or a sequence of paths");
  }
  if (out.empty()) throw InputError(where + ": no recordings given");
  return out;
}

}  // namespace oscilab::python
