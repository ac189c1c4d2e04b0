#pragma once

#include <QList>
#include <QStringList>
#include <QUrl>

namespace oscilab::ui {

/// Files dropped on the main window, sorted into what File ▸ Open session and File ▸ Open would
/// each open, in the order they were dropped.
struct DroppedFiles {
  QStringList sessions;    // .json files whose "format" is a session's (kSessionFormat)
  QStringList recordings;  // anything else: data files (a sidecar's own data file in its place)
};

/// Sorts dropped URLs: local files only (a web address or a folder is left out). A recording's
/// sidecar stands for the data file beside it (same stem, a format Oscilab reads), and a
/// recording dropped twice (data file and sidecar) opens once. A .json that is neither a session
/// nor beside a data file counts as a recording: opening it reports why.
DroppedFiles sort_dropped_files(const QList<QUrl>& urls);

}  // namespace oscilab::ui
