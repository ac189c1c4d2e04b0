// The MAT-file writer's calls into matio (mat_file_writer.h), compiled into oscilab_hdf5_module.
#include "daq/export/mat_file_writer.h"

#include <cerrno>
#include <cstdint>
#include <memory>
#include <string>

#include <matio.h>

#include "daq/recording/formats/matio_handles.h"

namespace oscilab::daq {
namespace {

// UTF-8 to UTF-16 code units, which is how MATLAB stores char arrays (miUINT16). A byte that does
// not start a valid sequence becomes U+FFFD, so any std::string can be written.
std::u16string utf16_of(const std::string& utf8) {
  std::u16string out;
  out.reserve(utf8.size());
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(utf8[i]); };
  std::size_t i = 0;
  while (i < utf8.size()) {
    const unsigned char lead = byte(i);
    int length = 0;
    char32_t code = 0;
    if (lead < 0x80) {
      length = 1;
      code = lead;
    } else if ((lead & 0xE0) == 0xC0) {
      length = 2;
      code = lead & 0x1F;
    } else if ((lead & 0xF0) == 0xE0) {
      length = 3;
      code = lead & 0x0F;
    } else if ((lead & 0xF8) == 0xF0) {
      length = 4;
      code = lead & 0x07;
    }
    bool valid = length > 0 && i + length <= utf8.size();
    for (int k = 1; valid && k < length; ++k) {
      valid = (byte(i + k) & 0xC0) == 0x80;
      code = (code << 6) | (byte(i + k) & 0x3F);
    }
    // Overlong forms, surrogates and values beyond U+10FFFF are not valid UTF-8.
    static constexpr char32_t kMinimum[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (valid &&
        (code < kMinimum[length] || code > 0x10FFFF || (code >= 0xD800 && code < 0xE000))) {
      valid = false;
    }
    if (!valid) {
      out.push_back(u'\uFFFD');
      ++i;
      continue;
    }
    if (code >= 0x10000) {
      code -= 0x10000;
      out.push_back(static_cast<char16_t>(0xD800 + (code >> 10)));
      out.push_back(static_cast<char16_t>(0xDC00 + (code & 0x3FF)));
    } else {
      out.push_back(static_cast<char16_t>(code));
    }
    i += length;
  }
  return out;
}

// A 1×k char array (name may be null for a cell element). matio copies the data.
MatVar char_variable(const char* name, const OscilabTextV1& text) {
  std::u16string units = utf16_of(std::string(text.utf8, text.size));
  std::size_t dims[2] = {1, units.size()};
  return MatVar(Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT16, 2, dims, units.data(), 0));
}

// An n×1 double column that points at `values` (matio neither copies nor frees it), so `values`
// must outlive the write.
MatVar double_column(const char* name, const double* values, std::size_t n) {
  std::size_t dims[2] = {n, 1};
  return MatVar(Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                              const_cast<double*>(values), MAT_F_DONT_COPY_DATA));
}

// n×1 cell of char. The cell owns its elements and frees them with itself.
MatVar string_cell(const char* name, const OscilabTextV1* texts, std::size_t n) {
  std::size_t dims[2] = {n, 1};
  MatVar cell(Mat_VarCreate(name, MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0));
  if (!cell) return cell;
  for (std::size_t i = 0; i < n; ++i) {
    MatVar element = char_variable(nullptr, texts[i]);
    if (!element) return MatVar();
    Mat_VarSetCell(cell.get(), static_cast<int>(i), element.release());
  }
  return cell;
}

MatVar logical_column(const char* name, const std::uint8_t* values, std::size_t n) {
  std::size_t dims[2] = {n, 1};
  return MatVar(Mat_VarCreate(name, MAT_C_UINT8, MAT_T_UINT8, 2, dims,
                              const_cast<std::uint8_t*>(values), MAT_F_LOGICAL));
}

MatVar make_variable(const OscilabMatVariableV1& v) {
  switch (v.kind) {
    case kOscilabMatDoubles:
      return double_column(v.name, v.doubles, v.rows);
    case kOscilabMatLogicals:
      return logical_column(v.name, v.logicals, v.rows);
    case kOscilabMatText:
      return char_variable(v.name, v.texts[0]);
    case kOscilabMatTexts:
      return string_cell(v.name, v.texts, v.rows);
    default:
      return MatVar();
  }
}

}  // namespace

OscilabMatWriteResultV1 write_mat_file(const char* path, const OscilabMatVariableV1* variables,
                                       std::size_t count) {
  errno = 0;
  MatFile mat(Mat_CreateVer(path, nullptr, MAT_FT_MAT5));
  if (!mat) return {kOscilabMatCannotCreate, 0, errno};
  for (std::size_t i = 0; i < count; ++i) {
    const MatVar variable = make_variable(variables[i]);
    if (!variable) return {kOscilabMatCannotMakeVariable, i, 0};
    if (Mat_VarWrite(mat.get(), variable.get(), MAT_COMPRESSION_ZLIB) != 0) {
      return {kOscilabMatCannotWriteVariable, i, 0};
    }
  }
  if (Mat_Close(mat.release()) != 0) return {kOscilabMatCannotClose, count, 0};
  return {kOscilabMatWritten, count, 0};
}

}  // namespace oscilab::daq
