#pragma once

#include <functional>
#include <memory>
#include <string>

#include <QMainWindow>
#include <QString>

#include "daq/recording/recording.h"

class QAction;

namespace oscilab::ui {

class IdentificationPanel;
class RecordView;

/// The Oscilab main window: File ▸ Open a recording and review it in a RecordView; the
/// identification panel (a dock on the right) fits the friction model to the opened stepped-sine
/// recordings and diagnoses what it misses.
///
/// A recording that cannot be read never ends the program: the reader's message goes to the
/// status bar, to the error_reported signal and, when interactive errors are on (the default),
/// to a modal message box; the recording shown before stays.
class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  /// Reads a recording from a path; throws oscilab::InputError on bad input.
  using Loader = std::function<daq::Recording(const std::string& path)>;

  /// `loader` defaults to daq::read_recording.
  explicit MainWindow(QWidget* parent = nullptr, Loader loader = {});
  ~MainWindow() override;

  /// Reads and shows the recording at `path`. On failure reports the error (see the class
  /// comment) and returns false.
  bool open_recording(const QString& path);
  /// Shows a recording already in memory; the title names its source_path, or "untitled".
  void show_recording(std::shared_ptr<const daq::Recording> recording);

  /// Off: errors are reported by the status bar and error_reported only, without a modal
  /// message box (for tests and unattended screenshots).
  void set_interactive_errors(bool on) { interactive_errors_ = on; }

  RecordView* record_view() const { return record_view_; }
  IdentificationPanel* identification_panel() const { return identification_panel_; }
  QAction* open_action() const { return open_action_; }
  QAction* fit_action() const { return fit_action_; }
  QAction* auto_value_range_action() const { return auto_value_range_action_; }
  QAction* quit_action() const { return quit_action_; }

 Q_SIGNALS:
  /// A recording could not be opened; `message` names the file and the problem.
  void error_reported(const QString& message);
  /// A recording was opened and is shown.
  void recording_opened(const QString& path);

 private:
  void choose_and_open();
  void report_error(const QString& message);

  Loader loader_;
  bool interactive_errors_ = true;
  QString last_directory_;
  RecordView* record_view_ = nullptr;
  IdentificationPanel* identification_panel_ = nullptr;
  QAction* open_action_ = nullptr;
  QAction* fit_action_ = nullptr;
  QAction* auto_value_range_action_ = nullptr;
  QAction* quit_action_ = nullptr;
};

}  // namespace oscilab::ui
