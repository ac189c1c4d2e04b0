#include "ui/review/review_view.h"

#include <algorithm>

#include <QAction>
#include <QComboBox>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QSignalBlocker>
#include <QSplitter>
#include <QTabWidget>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/pipeline/result_units.h"
#include "ui/qt_text.h"
#include "ui/review/level_table.h"
#include "ui/review/record_view.h"

namespace oscilab::ui {
namespace {}  // namespace

ReviewView::ReviewView(QWidget* parent) : QWidget(parent) {
  message_label_ = new QLabel;
  message_label_->setObjectName("review_message");
  message_label_->setWordWrap(true);
  message_label_->setContentsMargins(6, 2, 6, 2);
  message_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  message_label_->hide();

  record_box_ = new QComboBox;
  record_box_->setObjectName("record_box");
  record_box_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
  record_box_->setToolTip(tr("The recording shown in the time plots"));
  hint_label_ = new QLabel(
      tr("Click: hold the cursor \u00b7 Ctrl+M: mark it \u00b7 Ctrl-click levels: overlay loops"));
  hint_label_->setStyleSheet("color: gray");
  hint_label_->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  // The hint gives way (cut) before the record selector does.
  hint_label_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  auto* top_row = new QHBoxLayout;
  top_row->setContentsMargins(6, 2, 6, 2);
  top_row->addWidget(new QLabel(tr("Recording:")));
  top_row->addWidget(record_box_);
  top_row->addWidget(hint_label_, 1);

  record_view_ = new RecordView;

  // Levels: the table beside the loop plot (Fig. 9).
  level_table_ = new LevelTable;
  level_table_->setObjectName("level_table");
  auto* levels_page = new QSplitter(Qt::Horizontal);
  levels_page->addWidget(level_table_);
  levels_page->addWidget(loops_.plot());
  levels_page->setStretchFactor(0, 3);
  levels_page->setStretchFactor(1, 2);
  levels_page->setChildrenCollapsible(false);

  annotation_list_ = new QListWidget;
  annotation_list_->setObjectName("annotation_list");
  annotation_list_->setToolTip(tr("Double-click: go to the note; Delete: remove it"));
  auto* remove = new QAction(tr("Remove annotation"), annotation_list_);
  remove->setShortcut(QKeySequence::Delete);
  remove->setShortcutContext(Qt::WidgetShortcut);
  annotation_list_->addAction(remove);
  annotation_list_->setContextMenuPolicy(Qt::ActionsContextMenu);
  connect(remove, &QAction::triggered, this,
          [this] { remove_annotation(annotation_list_->currentRow()); });
  connect(annotation_list_, &QListWidget::itemDoubleClicked, this,
          [this](QListWidgetItem* item) { go_to_annotation(annotation_list_->row(item)); });

  tabs_ = new QTabWidget;
  tabs_->setObjectName("review_tabs");
  tabs_->addTab(levels_page, tr("Levels"));
  tabs_->addTab(cycles_.plot(), tr("Cycles"));
  tabs_->addTab(slices_.page(), tr("Restoring force"));
  tabs_->addTab(annotation_list_, tr("Annotations"));

  splitter_ = new QSplitter(Qt::Vertical);
  splitter_->setObjectName("review_splitter");
  splitter_->addWidget(record_view_);
  splitter_->addWidget(tabs_);
  splitter_->setStretchFactor(0, 2);
  splitter_->setStretchFactor(1, 3);
  splitter_->setChildrenCollapsible(false);
  // The time plots keep room for two channels; the tabs take the rest, 2 : 3 to start with
  // (the tab pages' size hints would otherwise squeeze the time plots to nothing).
  record_view_->setMinimumHeight(240);
  tabs_->setMinimumHeight(260);
  splitter_->setSizes({400, 600});

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(message_label_);
  layout->addLayout(top_row);
  layout->addWidget(splitter_, 1);

  connect(level_table_, &LevelTable::levels_selected, this, &ReviewView::on_levels_selected);
  connect(record_box_, &QComboBox::currentIndexChanged, this, [this](int index) {
    if (index >= 0 && std::size_t(index) < recordings_.size()) {
      show_recording(recordings_[std::size_t(index)].recording);
    }
  });
  connect(record_view_, &RecordView::cursor_moved, this, [this](double t_s) {
    plot_cycle_cursor();
    Q_EMIT cursor_moved(t_s);
  });
  // The cycle plot shows the record view's time window, its EDC axis the values in it.
  connect(record_view_, &RecordView::time_window_changed, this,
          [this](double start_s, double end_s) { cycles_.follow_time_window(start_s, end_s); });
  // A click on the cycle plot moves the shared cursor there and holds it.
  QCustomPlot* cycle_plot = cycles_.plot();
  connect(cycle_plot, &QCustomPlot::mouseRelease, this, [this, cycle_plot](QMouseEvent* event) {
    if (event->button() != Qt::LeftButton) return;
    if (cycle_plot->axisRectAt(event->position()) == nullptr) return;
    record_view_->set_cursor_follows_mouse(false);
    set_cursor_time(cycle_plot->xAxis->pixelToCoord(event->position().x()));
  });

  set_analysis(nullptr);
}

ReviewView::~ReviewView() = default;

void ReviewView::set_recordings(std::vector<Opened> recordings) {
  recordings_ = std::move(recordings);
  const QSignalBlocker block(record_box_);
  record_box_->clear();
  int shown = -1;
  for (std::size_t i = 0; i < recordings_.size(); ++i) {
    const QString path = qtext(recordings_[i].path);
    record_box_->addItem(QFileInfo(path).fileName());
    record_box_->setItemData(int(i), path, Qt::ToolTipRole);
    if (recordings_[i].recording.get() == record_view_->recording()) shown = int(i);
  }
  record_box_->setCurrentIndex(shown);
}

std::string ReviewView::shown_path() const {
  const daq::OpenedRecording* shown = record_view_->recording();
  if (!shown) return {};
  for (const Opened& opened : recordings_) {
    if (opened.recording.get() == shown) return opened.path;
  }
  return shown->source_path;
}

void ReviewView::show_recording(std::shared_ptr<const daq::OpenedRecording> recording) {
  record_view_->set_recording(std::move(recording));
  {
    const QSignalBlocker block(record_box_);
    int shown = -1;
    for (std::size_t i = 0; i < recordings_.size(); ++i) {
      if (recordings_[i].recording.get() == record_view_->recording()) shown = int(i);
    }
    record_box_->setCurrentIndex(shown);
  }
  plot_cycles();
  update_marks();
  plot_cycle_cursor();
  const TimeWindow window = record_view_->time_window();
  cycles_.follow_time_window(window.start_s, window.end_s);
  Q_EMIT recording_shown(qtext(shown_path()));
}

int ReviewView::shown_record() const {
  if (!analysis_ || !record_view_->recording()) return -1;
  for (std::size_t i = 0; i < analysis_->recordings.size(); ++i) {
    if (analysis_->recordings[i].get() == record_view_->recording()) return int(i);
  }
  return -1;
}

void ReviewView::show_record_index(int index) {
  if (!analysis_ || index < 0 || std::size_t(index) >= analysis_->recordings.size()) return;
  show_recording(analysis_->recordings[std::size_t(index)]);
}

void ReviewView::set_analysis_running(bool running) {
  analysis_running_ = running;
  if (!analysis_) set_analysis(nullptr);
}

void ReviewView::set_analysis(std::shared_ptr<const ReviewAnalysis> analysis) {
  analysis_ = std::move(analysis);
  if (analysis_) analysis_running_ = false;
  // Without a mass the forces and energies are per unit mass: every label says so.
  const analysis::MassBasis basis =
      analysis_ ? analysis::mass_basis(analysis_->campaign) : analysis::MassBasis::Absolute;
  const QString force_unit = qtext(analysis::result_unit("N", basis));
  const QString energy_unit = qtext(analysis::result_unit("mJ", basis));
  level_table_->set_rows(analysis_ ? level_rows(analysis_->campaign) : std::vector<LevelRow>{},
                         force_unit, energy_unit);
  cycles_.set_energy_unit(energy_unit);

  QStringList lines;
  if (analysis_) {
    for (const std::string& error : analysis_->errors)
      lines << tr("Left out: %1").arg(qtext(error));
    // Each note once, with the records it concerns.
    const analysis::CampaignAnalysis& campaign = analysis_->campaign;
    for (const analysis::SharedNote& note : analysis::shared_notes(campaign)) {
      lines << qtext(analysis::note_text(note, campaign.records.size()));
    }
    if (campaign.z_about_mean)
      lines << tr("Restoring force: %1").arg(qtext(analysis::kZAboutMeanNote));
    if (!analysis_->campaign.rfs_message.empty()) {
      lines << tr("Restoring force: %1").arg(qtext(analysis_->campaign.rfs_message));
    }
  }
  message_label_->setText(lines.join('\n'));
  message_label_->setVisible(!lines.isEmpty());

  // The measurement at first look: a few levels of each well until levels are selected.
  loops_.show(analysis_.get(),
              analysis_ ? overview_levels(analysis_->campaign) : std::vector<LevelKey>{});
  plot_cycles();
  plot_cycle_cursor();
  slices_.show(analysis_.get(), analysis_running_);
  // Records without a stepped-sine level (a random test) open on their restoring-force slices
  // rather than on an empty level table.
  if (analysis_ && !analysis_->campaign.records.empty() && tabs_->currentIndex() == kLevelsTab) {
    bool any_level = false;
    for (const analysis::RecordAnalysis& record : analysis_->campaign.records) {
      any_level = any_level || !record.levels.empty();
    }
    if (!any_level) tabs_->setCurrentIndex(kRestoringForceTab);
  }
}

void ReviewView::select_levels(const std::vector<LevelKey>& keys, bool move_view) {
  move_view_on_select_ = move_view;
  level_table_->select_levels(keys);
  move_view_on_select_ = true;
}

std::vector<LevelKey> ReviewView::selected_levels() const {
  return level_table_->selected_levels();
}

void ReviewView::on_levels_selected(const std::vector<LevelKey>& keys) {
  // No selection: the overview's levels, as at first look.
  loops_.show(analysis_.get(),
              keys.empty() && analysis_ ? overview_levels(analysis_->campaign) : keys);
  const analysis::LevelResult* level =
      analysis_ && !keys.empty() ? find_level(analysis_->campaign, keys.front()) : nullptr;
  if (level && move_view_on_select_) {
    if (shown_record() != keys.front().record) show_record_index(keys.front().record);
    const TimeWindow window = level_time_window(*level);
    record_view_->set_time_window(window.start_s, window.end_s);
    record_view_->set_cursor_follows_mouse(false);
    set_cursor_time(level_cursor_time_s(*level));
  }
  Q_EMIT levels_selected(keys);
}

void ReviewView::set_cursor_time(double t_s) { record_view_->set_cursor_time(t_s); }

std::optional<double> ReviewView::cursor_time() const { return record_view_->cursor_time(); }

void ReviewView::set_annotations(std::vector<Annotation> annotations) {
  annotations_ = std::move(annotations);
  update_marks();
  update_annotation_list();
  Q_EMIT annotations_changed();
}

bool ReviewView::add_annotation(const QString& note) {
  const std::string path = shown_path();
  if (path.empty()) return false;
  const TimeWindow window = record_view_->time_window();
  const double t_s = cursor_time().value_or(0.5 * (window.start_s + window.end_s));
  annotations_.push_back({path, t_s, note.toStdString()});
  update_marks();
  update_annotation_list();
  annotation_list_->setCurrentRow(int(annotations_.size()) - 1);
  Q_EMIT annotations_changed();
  return true;
}

void ReviewView::remove_annotation(int index) {
  if (index < 0 || std::size_t(index) >= annotations_.size()) return;
  annotations_.erase(annotations_.begin() + index);
  update_marks();
  update_annotation_list();
  Q_EMIT annotations_changed();
}

void ReviewView::go_to_annotation(int index) {
  if (index < 0 || std::size_t(index) >= annotations_.size()) return;
  const Annotation& annotation = annotations_[std::size_t(index)];
  if (shown_path() != annotation.recording) {
    for (const Opened& opened : recordings_) {
      if (opened.path == annotation.recording) show_recording(opened.recording);
    }
  }
  const TimeWindow window = record_view_->time_window();
  if (annotation.t_s < window.start_s || annotation.t_s > window.end_s) {
    const double half_s = 0.5 * window.width_s();
    record_view_->set_time_window(annotation.t_s - half_s, annotation.t_s + half_s);
  }
  record_view_->set_cursor_follows_mouse(false);
  set_cursor_time(annotation.t_s);
}

void ReviewView::update_marks() {
  const std::string path = shown_path();
  std::vector<RecordView::Mark> marks;
  for (const Annotation& annotation : annotations_) {
    if (!path.empty() && annotation.recording == path) {
      marks.push_back({annotation.t_s, qtext(annotation.text)});
    }
  }
  record_view_->set_marks(marks);
  cycles_.set_marks(marks);
}

void ReviewView::update_annotation_list() {
  annotation_list_->clear();
  for (const Annotation& annotation : annotations_) {
    const QString path = qtext(annotation.recording);
    auto* item = new QListWidgetItem(tr("%1   t = %2 s   %3")
                                         .arg(QFileInfo(path).fileName())
                                         .arg(annotation.t_s, 0, 'f', 3)
                                         .arg(qtext(annotation.text)));
    item->setToolTip(path);
    annotation_list_->addItem(item);
  }
  tabs_->setTabText(kAnnotationsTab, annotations_.empty()
                                         ? tr("Annotations")
                                         : tr("Annotations (%1)").arg(annotations_.size()));
}

void ReviewView::plot_cycles() {
  cycles_.show(analysis_.get(), shown_record(), analysis_running_, record_view_->time_window());
}

void ReviewView::plot_cycle_cursor() { cycles_.show_cursor(cursor_time(), shown_record() >= 0); }

}  // namespace oscilab::ui
