#include "ui/review/dropped_files.h"

#include <exception>

#include <QDir>
#include <QFileInfo>

#include "daq/recording/format_reader.h"
#include "daq/recording/json_file.h"
#include "daq/recording/sidecar.h"
#include "ui/review/review_session.h"

namespace oscilab::ui {
namespace {

bool is_session_file(const QString& path) {
  if (QFileInfo(path).suffix().toLower() != "json") return false;
  constexpr std::uintmax_t kMaxSessionBytes = 64u << 20;  // as read_session: a session is kB
  try {
    const nlohmann::json value = daq::read_json_file(path.toStdString(), kMaxSessionBytes);
    const auto format = value.is_object() ? value.find("format") : value.end();
    return format != value.end() && format->is_string() &&
           format->get<std::string>() == kSessionFormat;
  } catch (const std::exception&) {  // not JSON: File ▸ Open says what is wrong with it
    return false;
  }
}

// The data file a sidecar describes: the file beside it of the same stem in a format Oscilab
// reads; the sidecar itself when there is none (opening it then says why).
QString data_file_of(const QString& sidecar) {
  const QFileInfo info(sidecar);
  const QStringList siblings =
      info.dir().entryList({info.completeBaseName() + ".*"}, QDir::Files, QDir::Name);
  for (const QString& name : siblings) {
    const std::string extension = "." + QFileInfo(name).suffix().toLower().toStdString();
    if (extension == ".json") continue;
    for (const daq::FormatReader* format : daq::known_formats()) {
      if (format->matches_extension(extension)) return info.dir().absoluteFilePath(name);
    }
  }
  return sidecar;
}

}  // namespace

DroppedFiles sort_dropped_files(const QList<QUrl>& urls) {
  QStringList files;
  for (const QUrl& url : urls) {
    if (url.isLocalFile() && QFileInfo(url.toLocalFile()).isFile()) {
      files << QFileInfo(url.toLocalFile()).absoluteFilePath();
    }
  }
  QStringList sidecars_of_data;  // sidecars of the data files dropped
  for (const QString& file : files) {
    if (QFileInfo(file).suffix().toLower() == "json") continue;
    sidecars_of_data << QFileInfo(QString::fromStdString(daq::sidecar_path_for(file.toStdString())))
                            .absoluteFilePath();
  }
  DroppedFiles sorted;
  for (const QString& file : files) {
    if (is_session_file(file)) {
      sorted.sessions << file;
    } else if (!sidecars_of_data.contains(file)) {
      const QString data = QFileInfo(file).suffix().toLower() == "json" ? data_file_of(file) : file;
      if (!sorted.recordings.contains(data)) sorted.recordings << data;
    }
  }
  return sorted;
}

}  // namespace oscilab::ui
