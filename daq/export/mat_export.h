#pragma once

#include <string>
#include <vector>

#include "analysis/pipeline/edc_table.h"
#include "daq/recording/recording.h"

namespace oscilab::daq {

/// A valid MATLAB variable name for `name` (what `matlab.lang.makeValidName` would give, up to
/// details): every character other than an ASCII letter, digit or underscore becomes `_`; a name
/// that does not start with a letter gets the prefix `x`; a MATLAB keyword (`end`, `for`, ...)
/// gets a trailing `_`; the result is cut to 63 characters (`namelengthmax`). Never empty.
std::string matlab_identifier(const std::string& name);

/// The variable names write_recording_mat gives the channels, in channel order: each channel's
/// matlab_identifier, made unique against each other and the fixed names of the file (`t_s`,
/// `sample_rate_hz`, ...) by a suffix `_2`, `_3`, ...
std::vector<std::string> mat_channel_variables(const Sidecar& sidecar);

/// Writes a recording to a MATLAB v5 MAT-file (zlib-compressed elements, which MATLAB ≥ 7,
/// Octave and scipy.io.loadmat read) as plain variables:
///
///   t_s                  n×1 double, i / sample_rate_hz [s]
///   <channel>            n×1 double per channel, in SI (m/s^2, m/s, m or N), named by
///                        mat_channel_variables
///   sample_rate_hz       1×1 double
///   mass_kg              1×1 double, only when the sidecar gives it
///   sidecar_json         1×k char, the whole sidecar (sidecar_to_json), UTF-16 code units
///   channel_names        c×1 cell of char: the sidecar's channel names, in channel order
///   channel_variables    c×1 cell of char: the variable holding each channel
///   channel_units        c×1 cell of char: the SI unit of each channel
///
/// Non-finite samples (gaps, see Sidecar::invalid_intervals) are written as they are (NaN).
/// The file is written under a temporary name and renamed into place, so a failure leaves no
/// half-written file. Throws InputError naming `path` on any failure.
void write_recording_mat(const Recording& recording, const std::string& path);

/// The EDC table's rows and columns are the core's (analysis/pipeline/edc_table.h).
using analysis::edc_table_rows;
using analysis::EdcTableRow;

/// Writes an EDC table to a MATLAB v5 MAT-file as column vectors of one row per level: every
/// column of analysis::edc_table_columns, named and ordered as the CSV of `analyze --edc`
/// (docs/contracts.md §3). Real and integer columns are n×1 double, flags (`usable`) n×1
/// logical, text (`well`, `record`, `flags`) n×1 cell of char. Same atomic write as
/// write_recording_mat. Throws InputError naming `path` on any failure, including an empty
/// table (no stepped-sine level).
void write_edc_mat(const std::vector<EdcTableRow>& rows, const std::string& path);

}  // namespace oscilab::daq
