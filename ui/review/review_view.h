#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QString>
#include <QWidget>

#include "daq/recording/opened_recording.h"
#include "ui/plots/annotation.h"
#include "ui/review/review_cycle_plot.h"
#include "ui/review/review_loop_plot.h"
#include "ui/review/review_model.h"
#include "ui/review/review_slice_plots.h"

class QComboBox;
class QCustomPlot;
class QLabel;
class QListWidget;
class QSplitter;
class QTabWidget;

namespace oscilab::ui {

class LevelTable;
class RecordView;

/// The record review: the opened recordings over time (RecordView) above tabs with the
/// levels of the offline analysis (a sortable table and the Fig. 9 response-input loop of the
/// selected levels), each cycle's EDC over time, the restoring-force slices (stiffness slice with
/// the fitted K(z) of eq. (2), damping slices of Fig. 7c) and the annotations.
///
/// One time cursor is shared by every time plot (the record view and the cycle plot): the mouse,
/// a click or a level selection moves it. Annotations are notes at a time of a recording, drawn
/// as labelled lines on the time plots.
///
/// The view holds the controls (record selector, level table, annotations, tabs) and ties the
/// plots together (ReviewLoopPlot, ReviewCyclePlot, ReviewSlicePlots); it computes nothing: the
/// analysis comes ready-made (analyze_review, on a worker thread of the main window), rows and
/// loops from review_model.h. UI thread only.
class ReviewView : public QWidget {
  Q_OBJECT

 public:
  /// A recording the review can show, with the (absolute) path it was opened from.
  struct Opened {
    std::string path;
    std::shared_ptr<const daq::OpenedRecording> recording;
  };

  explicit ReviewView(QWidget* parent = nullptr);
  ~ReviewView() override;

  /// The recordings that can be shown (the record selector lists them). The recording shown
  /// stays unless it is no longer among them.
  void set_recordings(std::vector<Opened> recordings);
  const std::vector<Opened>& recordings() const { return recordings_; }
  /// Shows `recording` in the time plots (null clears).
  void show_recording(std::shared_ptr<const daq::OpenedRecording> recording);
  /// Path of the recording shown: its Opened path, else its source_path; empty without one.
  std::string shown_path() const;

  /// Shows an analysis of the recordings (null: none yet). The selection is cleared.
  void set_analysis(std::shared_ptr<const ReviewAnalysis> analysis);
  const ReviewAnalysis* analysis() const { return analysis_.get(); }
  /// Says the analysis is running (or not): a hint in the plots until set_analysis.
  void set_analysis_running(bool running);

  /// Selects levels in the table and draws their loops; the first (the current one) is shown in
  /// the time plots. `move_view`: its recording is shown, the time window moves to it and the
  /// cursor to its middle (held there).
  void select_levels(const std::vector<LevelKey>& keys, bool move_view = true);
  std::vector<LevelKey> selected_levels() const;

  /// Moves the shared cursor of every time plot (to the nearest sample).
  void set_cursor_time(double t_s);
  std::optional<double> cursor_time() const;

  /// Replaces the annotations (of every recording; those of the shown one are drawn).
  void set_annotations(std::vector<Annotation> annotations);
  const std::vector<Annotation>& annotations() const { return annotations_; }
  /// Adds a note on the shown recording at the cursor (without a cursor: the middle of the time
  /// window). Returns false when no recording is shown.
  bool add_annotation(const QString& text);
  void remove_annotation(int index);

  RecordView* record_view() const { return record_view_; }
  LevelTable* level_table() const { return level_table_; }
  /// Fig. 9: f = −m b̈ against z, one QCPCurve per selected level, one axis rect per well
  /// (the first is the plot's default axisRect()).
  QCustomPlot* loop_plot() const { return loops_.plot(); }
  /// EDC of every fitted cycle against time, the steady cycles of each level by well.
  QCustomPlot* cycle_plot() const { return cycles_.plot(); }
  QCustomPlot* stiffness_plot() const { return slices_.stiffness_plot(); }
  QCustomPlot* damping_plot() const { return slices_.damping_plot(); }
  /// The fitted K(z) with standard errors.
  QLabel* stiffness_label() const { return slices_.stiffness_label(); }
  QListWidget* annotation_list() const { return annotation_list_; }
  QComboBox* record_box() const { return record_box_; }
  /// Analysis notes and errors above the plots (hidden when there are none).
  QLabel* message_label() const { return message_label_; }
  /// Tabs: Levels, Cycles, Restoring force, Annotations.
  QTabWidget* tabs() const { return tabs_; }
  QSplitter* splitter() const { return splitter_; }

  enum Tab { kLevelsTab, kCyclesTab, kRestoringForceTab, kAnnotationsTab };

 Q_SIGNALS:
  /// The shared cursor moved to `t_s`.
  void cursor_moved(double t_s);
  /// Another recording is shown in the time plots.
  void recording_shown(const QString& path);
  void annotations_changed();
  /// The level selection changed (the current level first).
  void levels_selected(const std::vector<oscilab::ui::LevelKey>& keys);

 private:
  void on_levels_selected(const std::vector<LevelKey>& keys);
  void show_record_index(int index);
  int shown_record() const;  // index into analysis_->campaign.records, or -1
  void update_marks();
  void update_annotation_list();
  void plot_cycles();
  void plot_cycle_cursor();
  void go_to_annotation(int index);

  std::vector<Opened> recordings_;
  std::shared_ptr<const ReviewAnalysis> analysis_;
  std::vector<Annotation> annotations_;
  bool analysis_running_ = false;
  bool move_view_on_select_ = true;

  QLabel* message_label_ = nullptr;
  QComboBox* record_box_ = nullptr;
  QLabel* hint_label_ = nullptr;
  QSplitter* splitter_ = nullptr;
  RecordView* record_view_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  LevelTable* level_table_ = nullptr;
  ReviewLoopPlot loops_;
  ReviewCyclePlot cycles_;
  ReviewSlicePlots slices_;
  QListWidget* annotation_list_ = nullptr;
};

}  // namespace oscilab::ui
