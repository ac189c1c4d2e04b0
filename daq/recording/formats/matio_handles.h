#pragma once

#include <memory>

#include <matio.h>

// Owning handles of matio's files and variables, for the HDF5/MAT module's reader and writer.
namespace oscilab::daq {

struct MatClose {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
using MatFile = std::unique_ptr<mat_t, MatClose>;

struct MatVarFree {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};
using MatVar = std::unique_ptr<matvar_t, MatVarFree>;

}  // namespace oscilab::daq
