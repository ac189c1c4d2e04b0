#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QMainWindow>
#include <QString>
#include <QStringList>

#include <nlohmann/json.hpp>

#include "analysis/pipeline/pipeline_settings.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/opened_recording.h"
#include "ui/review/review_session.h"

class QAction;
class QDockWidget;
class QDragEnterEvent;
class QDropEvent;
class QLabel;
class QMenu;
class QProgressBar;
class QPushButton;
class QTabWidget;
class QTimer;

namespace oscilab::ui {

class BackgroundJob;
class ExportMenu;
class IdentificationPanel;
class LiveMonitor;
class RecordView;
class ReviewView;
struct ReviewAnalysis;

/// The Oscilab main window. Its central widget is a tab widget whose first tab, "Review", is the
/// record review (ReviewView): File ▸ Open one or several recordings, see them over time, the
/// levels of their offline analysis with the loop of each, the restoring-force slices, and
/// annotations; File ▸ Save/Open session keeps all of it. The identification panel (a dock on the
/// right) fits the friction model to the opened stepped-sine recordings and diagnoses what it
/// misses.
///
/// The offline analysis of the opened recordings (analyze_review) runs on a worker thread
/// whenever the set of recordings or the settings change, with its progress in the status bar;
/// the UI thread never waits for it. analysis_finished() says when a result is shown.
///
/// A recording or session that cannot be read never ends the program: the message goes to the
/// status bar, to the error_reported signal and, when interactive errors are on (the default),
/// to a modal message box; what was shown before stays.
class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  /// Opens a recording at a path to be looked at, with progress and cancellation; throws
  /// oscilab::InputError on bad input and daq::OpeningCancelled when cancelled. It runs on a
  /// worker thread (ui/review/recording_opener).
  using Loader = std::function<daq::OpenedRecording(const std::string& path,
                                                    const daq::OpeningControl& control)>;

  /// Asks a person how a file without a sidecar maps onto channels; nothing: not opened.
  using MappingAsker =
      std::function<std::optional<daq::Sidecar>(const QString& path, const daq::FileContents&)>;

  /// `loader` defaults to daq::open_recording_for_review (a sound container's samples stay in
  /// its file).
  explicit MainWindow(QWidget* parent = nullptr, Loader loader = {});

  /// Replaces the ChannelMappingDialog that File ▸ Open shows for a file without a sidecar (the
  /// answer is saved as the file's sidecar before it is read).
  void set_mapping_asker(MappingAsker asker) { mapping_asker_ = std::move(asker); }
  ~MainWindow() override;

  /// Reads the recording at `path`, adds it to the opened recordings (opening a path again
  /// re-reads it) and shows it; the analysis restarts. The file is read on a worker thread while
  /// the window keeps repainting; a long opening shows its progress in a dialog that can cancel
  /// it (ui/review/recording_opener). On failure reports the error (see the class comment) and
  /// returns false; a cancelled opening says so in the status bar and returns false.
  bool open_recording(const QString& path);
  /// Opens each of `paths` in order and shows the first that opened; returns how many opened.
  int open_recordings(const QStringList& paths);
  /// Shows a recording in the time plots; the title names its source_path, or "untitled".
  void show_recording(std::shared_ptr<const daq::OpenedRecording> recording);
  /// The opened recordings' absolute paths, in the order they were opened.
  QStringList opened_paths() const;

  /// Settings of the offline analysis (the next analysis uses them; a change restarts it).
  void set_analysis_settings(const analysis::PipelineSettings& settings);
  const analysis::PipelineSettings& analysis_settings() const { return settings_; }
  /// The analysis shown, or null before the first finished.
  std::shared_ptr<const ReviewAnalysis> analysis() const { return analysis_; }
  bool analysis_running() const;

  /// Writes the session (recordings, settings, layout, view, selection, annotations, live) to
  /// `path`. On failure reports the error and returns false.
  bool save_session(const QString& path);
  /// Replaces the review by the session at `path`. A bad file is reported (naming the file and
  /// field) and changes nothing: returns false. Recordings that cannot be found are reported by
  /// name and the others opened; the selected levels come back when the analysis finishes.
  bool open_session(const QString& path);
  /// The session as it would be saved now.
  Session current_session() const;

  /// Off: errors are reported by the status bar and error_reported only, without a modal
  /// message box, and Mark uses a default note instead of asking (for tests and screenshots).
  void set_interactive_errors(bool on) { interactive_errors_ = on; }
  bool interactive_errors() const { return interactive_errors_; }

  /// The central tab widget: "Review" first; other pages (a live monitor) are added after it.
  QTabWidget* central_tabs() const { return central_tabs_; }
  ReviewView* review_view() const { return review_view_; }
  RecordView* record_view() const;
  IdentificationPanel* identification_panel() const { return identification_panel_; }
  /// The Live tab's monitor (owned by the window, like the review and the fit panel).
  LiveMonitor* live_monitor() const { return live_monitor_; }
  /// File ▸ Export: plots, the level table, the recording shown, the EDC table.
  ExportMenu* export_menu() const { return export_menu_; }
  QAction* open_action() const { return open_action_; }
  QAction* open_session_action() const { return open_session_action_; }
  QAction* save_session_action() const { return save_session_action_; }
  QAction* mark_action() const { return mark_action_; }
  QAction* fit_action() const { return fit_action_; }
  QAction* auto_value_range_action() const { return auto_value_range_action_; }
  QAction* cursor_follows_mouse_action() const { return cursor_follows_mouse_action_; }
  QAction* quit_action() const { return quit_action_; }
  /// View ▸ Zoom in (Ctrl++), Zoom out (Ctrl+-), Reset zoom (Ctrl+0: the whole record on the
  /// record view) and Undo zoom (Ctrl+Z, Backspace), on the plot under the mouse or the one it was
  /// over last (ExportMenu::plot_to_export); ui/plot_zoom.
  QAction* zoom_in_action() const { return zoom_in_action_; }
  QAction* zoom_out_action() const { return zoom_out_action_; }
  QAction* reset_zoom_action() const { return reset_zoom_action_; }
  QAction* undo_zoom_action() const { return undo_zoom_action_; }
  /// Review ▸ Next level (Alt+Down) and Previous level (Alt+Up): the level table's next or
  /// previous row, selected alone.
  QAction* next_level_action() const { return next_level_action_; }
  QAction* previous_level_action() const { return previous_level_action_; }
  /// Every menu action with a shortcut, one "Menu ▸ Action: keys" line each (Help ▸ Keyboard
  /// shortcuts shows them).
  QStringList shortcut_lines() const;
  /// Shown in the status bar after a live recording finished: it opens for review but joins the
  /// fit set only when this is clicked ("Add NAME to the fit set", or "Add N recordings …" for
  /// the recordings made since the last click).
  QPushButton* fit_set_offer_button() const { return fit_set_offer_; }

 Q_SIGNALS:
  /// A recording or session could not be opened (or saved); `message` names the file and the
  /// problem.
  void error_reported(const QString& message);
  /// A recording was opened and is shown.
  void recording_opened(const QString& path);
  /// An analysis of the opened recordings finished and is shown.
  void analysis_finished();

 protected:
  /// Recordings (data files or sidecars) and sessions dropped on the window open as File ▸ Open
  /// and File ▸ Open session would open them (ui/review/dropped_files).
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  struct OpenedFile;
  void open_live_recording(const QString& path);
  // The constructor's parts: the Review and Live tabs with the fit panel's dock (returned), the
  // status bar's analysis and fit-set widgets, the menus and the toolbar.
  QDockWidget* build_views();
  void build_status_bar();
  void build_menus(QDockWidget* dock);
  void build_toolbar();
  void add_zoom_actions(QMenu* menu);
  void step_level(int step);
  void choose_and_open();
  void choose_and_open_session();
  void choose_and_save_session();
  void mark_at_cursor();
  void report_error(const QString& message, const QString& title);
  enum class LoadOutcome { Opened, Failed, Cancelled };
  LoadOutcome load(const QString& path, QString& error, bool join_fit = true);
  void sync_recordings();
  void schedule_analysis();
  void start_analysis();
  void on_analysis_finished(bool cancelled);
  void update_title();

  Loader loader_;
  MappingAsker mapping_asker_;
  bool interactive_errors_ = true;
  QString last_directory_;
  std::vector<OpenedFile> opened_;
  analysis::PipelineSettings settings_;

  BackgroundJob* analysis_job_ = nullptr;
  QTimer* analysis_timer_ = nullptr;                 // coalesces changes into one analysis
  bool analysis_again_ = false;                      // the recordings changed while an analysis ran
  std::shared_ptr<ReviewAnalysis> analysis_result_;  // written by the worker
  std::shared_ptr<const ReviewAnalysis> analysis_;   // shown
  std::vector<Session::LevelRef> pending_levels_;    // a session's, until its analysis is shown

  QTabWidget* central_tabs_ = nullptr;
  LiveMonitor* live_monitor_ = nullptr;
  ReviewView* review_view_ = nullptr;
  IdentificationPanel* identification_panel_ = nullptr;
  QLabel* analysis_label_ = nullptr;
  QProgressBar* analysis_progress_ = nullptr;
  QAction* open_action_ = nullptr;
  QAction* open_session_action_ = nullptr;
  QAction* save_session_action_ = nullptr;
  QAction* mark_action_ = nullptr;
  QAction* fit_action_ = nullptr;
  QAction* auto_value_range_action_ = nullptr;
  QAction* cursor_follows_mouse_action_ = nullptr;
  QAction* quit_action_ = nullptr;
  QAction* zoom_in_action_ = nullptr;
  QAction* zoom_out_action_ = nullptr;
  QAction* reset_zoom_action_ = nullptr;
  QAction* undo_zoom_action_ = nullptr;
  QAction* next_level_action_ = nullptr;
  QAction* previous_level_action_ = nullptr;
  QPushButton* fit_set_offer_ = nullptr;
  QStringList offered_paths_;  // the live recordings fit_set_offer_ would add
  ExportMenu* export_menu_ = nullptr;
};

}  // namespace oscilab::ui
