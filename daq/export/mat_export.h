#pragma once

#include <string>
#include <vector>

#include "analysis/edc/level_tracker.h"
#include "analysis/pipeline/offline_analysis.h"
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

/// One row of the EDC table (docs/contracts.md §3) with the record it comes from.
struct EdcTableRow {
  std::string record;  // the recording's name; may be empty
  analysis::LevelResult level;
  std::string flags;  // analysis::level_flags: the level's, and per-unit-mass without a mass
};

/// Every level of every record of a campaign, in record then level order (the rows of
/// `oscilab-cli analyze --edc`).
std::vector<EdcTableRow> edc_table_rows(const analysis::CampaignAnalysis& campaign);

/// Writes an EDC table to a MATLAB v5 MAT-file as column vectors of one row per level: the
/// contract's columns `well` (n×1 cell of char: positive, negative, cross-well, unknown),
/// `f0_n`, `edc_mean_j`, `edc_std_j`, `cycles` (n×1 double), then `record` and `flags` (n×1 cell
/// of char), `edc_noise_floor_j`, `edc_eq13_mean_j`, `edc_trapz_mean_j`, `z1_abs_m`,
/// `z_mean_m`, `start_s`, `end_s` (n×1 double) and `usable` (n×1 logical). Same atomic write
/// as write_recording_mat. Throws InputError naming `path` on any failure, including an empty
/// table (no stepped-sine level).
void write_edc_mat(const std::vector<EdcTableRow>& rows, const std::string& path);

}  // namespace oscilab::daq
