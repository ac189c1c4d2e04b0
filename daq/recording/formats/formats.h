#pragma once

#include <string>
#include <vector>

#include "daq/recording/format_reader.h"

// The formats Oscilab reads, one file each under daq/recording/formats/, and the writers of the
// containers it records to.
namespace oscilab::daq {

/// Sound containers through libsndfile (WAV, FLAC, W64, RF64, AIFF, CAF, ...): the sidecar's
/// channels are the file's channels in order.
const FormatReader& sound_format();
/// NI TDMS (TDM Streaming) files: signals named "group/channel", DAQmx raw data scaled by the
/// file's linear scales.
const FormatReader& tdms_format();
/// Universal File Format dataset 58 (function at nodal DOF), ASCII "58" and binary "58b": one
/// signal per time response, named by its response DOF or "dataset <k>".
const FormatReader& uff_format();
/// Delimited text (CSV, TSV): columns by header name or by the sidecar's "column".
const FormatReader& csv_format();
/// MATLAB MAT-files (Level 4, Level 5, v7.3) through matio: real numeric matrices by variable name.
const FormatReader& mat_format();
/// HDF5 files through libhdf5: numeric 1-D and 2-D datasets by path, rate and unit from attributes.
const FormatReader& hdf5_format();

/// The libsndfile format Oscilab writes for a lower-case extension (".wav" → 64-bit float WAV,
/// ".flac" → 24-bit FLAC, ...), or 0 when the extension is not a sound container.
int sound_format_for(const std::string& extension);
/// Whether the libsndfile `format` stores 24-bit integers (FLAC), between these counts.
bool stores_24_bit_integers(int format);
inline constexpr double kInt24Min = -8388608.0;  // -2^23
inline constexpr double kInt24Max = 8388607.0;   // 2^23 - 1

/// Writes interleaved stored values (row r, channel c at r × channels + c) to `file_path` as a
/// sound container of `format`; `path` names the recording in messages. Throws InputError.
void write_sound(const std::vector<double>& stored, const Sidecar& sidecar, int format,
                 const std::string& file_path, const std::string& path);
/// Writes interleaved stored values as a CSV with a `t_s` column at full precision.
void write_csv(const std::vector<double>& stored, const Sidecar& sidecar,
               const std::string& file_path, const std::string& path);

}  // namespace oscilab::daq
