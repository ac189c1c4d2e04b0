#pragma once

#include <functional>
#include <memory>

#include <QString>

#include "daq/recording/opened_recording.h"

class QWidget;

namespace oscilab::ui {

/// Opens a recording on a worker thread while the UI thread's event loop keeps running, so that
/// the window repaints and a live acquisition's views keep updating while a long file is decoded.
/// From `kProgressDelayMs` on, a progress dialog, modal for `parent`'s window, shows how far the
/// opening has gone (`label`) and can cancel it (its Cancel button or Escape).
///
/// Returns what `open` returned; rethrows what it threw (InputError, daq::OpeningCancelled after
/// a cancel, anything else) on the UI thread. Returns only after the worker has ended.
///
/// Thread-safety: for the UI thread; `open` runs on the worker and must only touch what it is
/// given.
std::shared_ptr<daq::OpenedRecording> open_off_the_ui_thread(
    QWidget* parent, const QString& label,
    const std::function<daq::OpenedRecording(const daq::OpeningControl&)>& open);

/// How long an opening runs before its progress dialog appears, in ms: a short file opens without
/// a flash of a dialog.
inline constexpr int kProgressDelayMs = 400;

}  // namespace oscilab::ui
