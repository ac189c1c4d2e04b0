#include "ui/review_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

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
#include "ui/display_units.h"
#include "ui/level_table.h"
#include "ui/plot_helpers.h"
#include "ui/record_view.h"
#include "ui/time_marks.h"
#include "ui/well_colours.h"

namespace oscilab::ui {
namespace {

// At most this many loops are drawn at once (Fig. 9 overlays two; more become unreadable).
constexpr std::size_t kMaxLoops = 8;
// Scatter points per slice plot: enough to show the cloud, few enough to redraw at once.
constexpr std::size_t kMaxScatterPoints = 20000;
// Points of the fitted K(z) curve.
constexpr int kCurvePoints = 200;
// Space around fitted data ranges, as a fraction of their span.
constexpr double kRangeMargin = 0.05;
// Damping slices: green around z₋*, yellow-orange around z₊* (Fig. 7c; Okabe–Ito colours).
const QColor kSliceColour[2] = {QColor(0, 158, 115), QColor(230, 159, 0)};
const QColor kSampleColour(86, 180, 233);  // stiffness-slice samples: light blue (Fig. 7b)
const QColor kFitColour(200, 0, 0);        // the fitted K(z): red (Fig. 7b)

QString text(const std::string& s) { return QString::fromStdString(s); }

// A title row above the axes of `plot`.
QCPTextElement* add_title(QCustomPlot* plot, const QString& title) {
  plot->plotLayout()->insertRow(0);
  QFont font = plot->font();
  font.setBold(true);
  auto* element = new QCPTextElement(plot, title, font);
  plot->plotLayout()->addElement(0, 0, element);
  return element;
}

QCustomPlot* make_plot(const QString& x_label, const QString& y_label) {
  auto* plot = new QCustomPlot;
  plot->setAutoAddPlottableToLegend(true);
  plot->xAxis->setLabel(x_label);
  plot->yAxis->setLabel(y_label);
  plot->xAxis->setNumberFormat("gb");
  plot->yAxis->setNumberFormat("gb");
  for (QCPAxis* axis : {plot->xAxis2, plot->yAxis2}) {  // a frame: top and right as lines
    axis->setVisible(true);
    axis->setTicks(false);
    axis->setTickLabels(false);
  }
  plot->setMinimumSize(260, 200);
  return plot;
}

// Largest |value| of a set of vectors, for a display unit.
double max_abs(std::initializer_list<const std::vector<double>*> vectors) {
  double m = 0.0;
  for (const auto* v : vectors) {
    for (double x : *v) {
      if (std::isfinite(x)) m = std::max(m, std::abs(x));
    }
  }
  return m;
}

// Axis range of `values` with a margin; [−1, 1] when there are none.
void fit_axis(QCPAxis* axis, double lo, double hi) {
  if (!(lo <= hi)) {
    axis->setRange(-1.0, 1.0);
    return;
  }
  const double pad = hi > lo ? kRangeMargin * (hi - lo) : std::max(1.0, std::abs(hi)) * 0.1;
  axis->setRange(lo - pad, hi + pad);
}

}  // namespace

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
  loop_plot_ = make_plot(tr("z [mm]"), tr("f = \u2212m d\u00b2b/dt\u00b2 [N]"));
  loop_plot_->setObjectName("loop_plot");
  add_title(loop_plot_, tr("Response-input loops of the selected levels (Fig. 9)"));
  // Row 1: one axis rect per well side by side (each zoomed to its loops, as Fig. 9b/c); row 2:
  // the legend, below them so that it hides no loop.
  QCPAxisRect* first_rect = loop_plot_->axisRect();
  loop_plot_->plotLayout()->take(first_rect);
  loop_grid_ = new QCPLayoutGrid;
  loop_plot_->plotLayout()->addElement(1, 0, loop_grid_);
  loop_grid_->addElement(0, 0, first_rect);
  loop_grid_->setColumnSpacing(4);
  first_rect->insetLayout()->take(loop_plot_->legend);
  loop_plot_->plotLayout()->addElement(2, 0, loop_plot_->legend);
  loop_plot_->plotLayout()->setRowStretchFactor(2, 0.001);
  loop_plot_->legend->setVisible(true);
  loop_plot_->legend->setFillOrder(QCPLayoutGrid::foColumnsFirst);
  auto* levels_page = new QSplitter(Qt::Horizontal);
  levels_page->addWidget(level_table_);
  levels_page->addWidget(loop_plot_);
  levels_page->setStretchFactor(0, 3);
  levels_page->setStretchFactor(1, 2);
  levels_page->setChildrenCollapsible(false);

  // Cycles: each fitted cycle's EDC over time, a time plot sharing the cursor.
  cycle_plot_ = make_plot(tr("time [s]"), tr("EDC per cycle [mJ]"));
  cycle_plot_->setObjectName("cycle_plot");
  add_title(cycle_plot_, tr("Energy dissipated in each fitted cycle (\u00a74.1)"));
  cycle_plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
  cycle_plot_->yAxis->setTicker(QSharedPointer<QCPAxisTickerLog>::create());
  cycle_plot_->legend->setVisible(true);
  cycle_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignBottom | Qt::AlignRight);
  cycle_plot_->addLayer("cursor", cycle_plot_->layer("main"), QCustomPlot::limAbove);
  cycle_plot_->layer("cursor")->setMode(QCPLayer::lmBuffered);
  cycle_cursor_ = new QCPItemStraightLine(cycle_plot_);
  cycle_cursor_->setLayer("cursor");
  cycle_cursor_->setPen(QPen(QColor(60, 60, 60), 1.0, Qt::DashLine));
  cycle_cursor_->setVisible(false);

  // Restoring force: stiffness slice and damping slices side by side, the fit below.
  stiffness_plot_ = make_plot(tr("z [mm]"), tr("R [N]"));
  stiffness_plot_->setObjectName("stiffness_plot");
  add_title(stiffness_plot_, tr("Stiffness slice: R at small |\u017c| (\u00a73.1, Fig. 7b)"));
  stiffness_plot_->legend->setVisible(true);
  stiffness_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  damping_plot_ = make_plot(tr("\u017c [mm/s]"), tr("D = R \u2212 K(z) [N]"));
  damping_plot_->setObjectName("damping_plot");
  add_title(damping_plot_,
            tr("Damping slices at the stable equilibria: |z \u2212 z\u0304| < \u03b5_d (Fig. 7c)"));
  damping_plot_->legend->setVisible(true);
  damping_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  stiffness_label_ = new QLabel;
  stiffness_label_->setObjectName("stiffness_fit");
  stiffness_label_->setWordWrap(true);
  stiffness_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  stiffness_label_->setContentsMargins(6, 2, 6, 4);
  auto* slices = new QSplitter(Qt::Horizontal);
  slices->addWidget(stiffness_plot_);
  slices->addWidget(damping_plot_);
  slices->setChildrenCollapsible(false);
  auto* rfs_page = new QWidget;
  auto* rfs_layout = new QVBoxLayout(rfs_page);
  rfs_layout->setContentsMargins(0, 0, 0, 0);
  rfs_layout->setSpacing(0);
  rfs_layout->addWidget(slices, 1);
  rfs_layout->addWidget(stiffness_label_);

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
  tabs_->addTab(cycle_plot_, tr("Cycles"));
  tabs_->addTab(rfs_page, tr("Restoring force"));
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
  connect(record_view_, &RecordView::time_window_changed, this, &ReviewView::follow_time_window);
  // A click on the cycle plot moves the shared cursor there and holds it.
  connect(cycle_plot_, &QCustomPlot::mouseRelease, this, [this](QMouseEvent* event) {
    if (event->button() != Qt::LeftButton) return;
    if (cycle_plot_->axisRectAt(event->position()) == nullptr) return;
    record_view_->set_cursor_follows_mouse(false);
    set_cursor_time(cycle_plot_->xAxis->pixelToCoord(event->position().x()));
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
    const QString path = text(recordings_[i].path);
    record_box_->addItem(QFileInfo(path).fileName());
    record_box_->setItemData(int(i), path, Qt::ToolTipRole);
    if (recordings_[i].recording.get() == record_view_->recording()) shown = int(i);
  }
  record_box_->setCurrentIndex(shown);
}

std::string ReviewView::shown_path() const {
  const daq::Recording* shown = record_view_->recording();
  if (!shown) return {};
  for (const Opened& opened : recordings_) {
    if (opened.recording.get() == shown) return opened.path;
  }
  return shown->source_path;
}

void ReviewView::show_recording(std::shared_ptr<const daq::Recording> recording) {
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
  follow_time_window(window.start_s, window.end_s);
  Q_EMIT recording_shown(text(shown_path()));
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

QString ReviewView::slice_force_unit(const DisplayUnit& unit) const {
  const analysis::MassBasis basis =
      analysis_ ? analysis::mass_basis(analysis_->campaign) : analysis::MassBasis::Absolute;
  return text(analysis::result_unit(unit.symbol, basis));
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
  const QString force_unit = text(analysis::result_unit("N", basis));
  const QString energy_unit = text(analysis::result_unit("mJ", basis));
  level_table_->set_rows(analysis_ ? level_rows(analysis_->campaign) : std::vector<LevelRow>{},
                         force_unit, energy_unit);
  cycle_plot_->yAxis->setLabel(tr("EDC per cycle [%1]").arg(energy_unit));

  QStringList lines;
  if (analysis_) {
    for (const std::string& error : analysis_->errors) lines << tr("Left out: %1").arg(text(error));
    // Each note once, with the records it concerns.
    const analysis::CampaignAnalysis& campaign = analysis_->campaign;
    for (const analysis::SharedNote& note : analysis::shared_notes(campaign)) {
      lines << text(analysis::note_text(note, campaign.records.size()));
    }
    if (campaign.z_about_mean)
      lines << tr("Restoring force: %1").arg(text(analysis::kZAboutMeanNote));
    if (!analysis_->campaign.rfs_message.empty()) {
      lines << tr("Restoring force: %1").arg(text(analysis_->campaign.rfs_message));
    }
  }
  message_label_->setText(lines.join('\n'));
  message_label_->setVisible(!lines.isEmpty());

  plot_loops({});
  plot_cycles();
  plot_cycle_cursor();
  plot_slices();
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
  plot_loops(keys);
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
      marks.push_back({annotation.t_s, text(annotation.text)});
    }
  }
  record_view_->set_marks(marks);
  for (QCPAbstractItem* item : cycle_marks_) cycle_plot_->removeItem(item);
  cycle_marks_.clear();
  for (const RecordView::Mark& mark : marks) {
    add_time_mark(cycle_plot_, cycle_plot_->axisRect(), mark.t_s, mark.text, cycle_marks_);
  }
  cycle_plot_->replot(QCustomPlot::rpQueuedReplot);
}

void ReviewView::update_annotation_list() {
  annotation_list_->clear();
  for (const Annotation& annotation : annotations_) {
    const QString path = text(annotation.recording);
    auto* item = new QListWidgetItem(tr("%1   t = %2 s   %3")
                                         .arg(QFileInfo(path).fileName())
                                         .arg(annotation.t_s, 0, 'f', 3)
                                         .arg(text(annotation.text)));
    item->setToolTip(path);
    annotation_list_->addItem(item);
  }
  tabs_->setTabText(kAnnotationsTab, annotations_.empty()
                                         ? tr("Annotations")
                                         : tr("Annotations (%1)").arg(annotations_.size()));
}

void ReviewView::plot_loops(const std::vector<LevelKey>& keys) {
  // Curves first (their legend items go with them), then the labels and the extra well rects.
  loop_plot_->clearPlottables();
  for (QCPAbstractItem* item : loop_labels_) loop_plot_->removeItem(item);
  loop_labels_.clear();
  for (int c = loop_grid_->columnCount() - 1; c >= 1; --c) {
    if (loop_grid_->element(0, c)) loop_grid_->remove(loop_grid_->element(0, c));
  }
  loop_grid_->simplify();

  std::vector<LevelLoop> loops;
  std::vector<LevelKey> shown;
  if (analysis_) {
    for (const LevelKey& key : keys) {
      if (loops.size() == kMaxLoops) break;
      const analysis::LevelResult* level = find_level(analysis_->campaign, key);
      if (!level || std::size_t(key.record) >= analysis_->force_n.size()) continue;
      loops.push_back(level_loop(analysis_->campaign.records[std::size_t(key.record)].motion,
                                 analysis_->force_n[std::size_t(key.record)], *level));
      shown.push_back(key);
    }
  }
  loop_plot_->legend->setVisible(!loops.empty());
  if (loops.empty()) {
    set_plot_hint(loop_plot_, analysis_ ? tr("Select levels in the table to draw their loops")
                                        : tr("No analysis yet"));
    loop_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(loop_plot_, {});
  // One entry a row for a few loops, two columns for more (before the entries are added).
  loop_plot_->legend->setWrap(loops.size() <= 3 ? 1 : 2);
  double z_max = 0.0, f_max = 0.0;
  for (const LevelLoop& loop : loops) {
    z_max = std::max(z_max, max_abs({&loop.z_m}));
    f_max = std::max(f_max, max_abs({&loop.f_n}));
  }
  const DisplayUnit z_unit = choose_display_unit("m", z_max);
  const DisplayUnit f_unit = choose_display_unit("N", f_max);
  const bool per_unit_mass =
      analysis_->campaign.records[std::size_t(shown.front().record)].per_unit_mass;
  const QString f_label =
      per_unit_mass ? tr("f / m = \u2212d\u00b2b/dt\u00b2 [%1/kg]").arg(text(f_unit.symbol))
                    : tr("f = \u2212m d\u00b2b/dt\u00b2 [%1]").arg(text(f_unit.symbol));

  // One axis rect per well, in the order positive, negative, other.
  const auto group_of = [](analysis::Well well) {
    return well == analysis::Well::Positive ? 0 : well == analysis::Well::Negative ? 1 : 2;
  };
  bool present[3] = {false, false, false};
  for (const LevelLoop& loop : loops) present[group_of(loop.well)] = true;
  QCPAxisRect* rect_of[3] = {nullptr, nullptr, nullptr};
  std::vector<QCPAxisRect*> rects;
  for (int g = 0; g < 3; ++g) {
    if (!present[g]) continue;
    QCPAxisRect* rect = rects.empty() ? loop_plot_->axisRect() : new QCPAxisRect(loop_plot_);
    if (!rects.empty()) {
      loop_grid_->addElement(0, int(rects.size()), rect);
      for (QCPAxis::AxisType side : {QCPAxis::atTop, QCPAxis::atRight}) {
        rect->axis(side)->setVisible(true);
        rect->axis(side)->setTicks(false);
        rect->axis(side)->setTickLabels(false);
      }
      rect->axis(QCPAxis::atBottom)->setNumberFormat("gb");
      rect->axis(QCPAxis::atLeft)->setNumberFormat("gb");
    }
    rect->axis(QCPAxis::atBottom)->setLabel(tr("z [%1]").arg(text(z_unit.symbol)));
    rect->axis(QCPAxis::atLeft)->setLabel(rects.empty() ? f_label : QString());
    // The well, top left inside the axes.
    auto* label = new QCPItemText(loop_plot_);
    label->setClipAxisRect(rect);
    label->position->setAxisRect(rect);
    label->position->setType(QCPItemPosition::ptAxisRectRatio);
    label->position->setCoords(0.03, 0.03);
    label->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    label->setText(g == 0   ? tr("around z\u208a*")
                   : g == 1 ? tr("around z\u208b*")
                            : tr("cross-well / unknown"));
    label->setColor(well_colour(g == 0   ? analysis::Well::Positive
                                : g == 1 ? analysis::Well::Negative
                                         : analysis::Well::Unknown));
    loop_labels_.push_back(label);
    rect_of[g] = rect;
    rects.push_back(rect);
  }

  int same_well[3] = {0, 0, 0};  // loops drawn so far per well: later ones darker
  double z_lo[3] = {INFINITY, INFINITY, INFINITY}, z_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double f_lo = INFINITY, f_hi = -INFINITY;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const LevelLoop& loop = loops[i];
    const analysis::LevelResult& level = *find_level(analysis_->campaign, shown[i]);
    const int g = group_of(loop.well);
    const QColor colour = well_colour(loop.well).darker(100 + 35 * same_well[g]++).toRgb();
    QCPAxisRect* rect = rect_of[g];
    auto* curve = new QCPCurve(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    QVector<QCPCurveData> data(qsizetype(loop.z_m.size()));
    for (std::size_t k = 0; k < loop.z_m.size(); ++k) {
      const double z = z_unit.to_display(loop.z_m[k]), f = f_unit.to_display(loop.f_n[k]);
      data[qsizetype(k)] = QCPCurveData(double(k), z, f);
      z_lo[g] = std::min(z_lo[g], z);
      z_hi[g] = std::max(z_hi[g], z);
      f_lo = std::min(f_lo, f);
      f_hi = std::max(f_hi, f);
    }
    curve->data()->set(data, true);
    curve->setPen(QPen(colour, 1.2));
    const analysis::RecordAnalysis& record =
        analysis_->campaign.records[std::size_t(shown[i].record)];
    curve->setName(tr("%1, f\u2080 = %2 %5: EDC %3 %6 (%4 steady cycles)")
                       .arg(text(record.name))
                       .arg(level.f0_n, 0, 'f', 2)
                       .arg(1e3 * level.edc_mean_j, 0, 'f', 3)
                       .arg(loop.cycles)
                       .arg(text(analysis::result_unit("N", record.per_unit_mass)))
                       .arg(text(analysis::result_unit("mJ", record.per_unit_mass))));
  }
  // Each rect over its loops' z; one force range for all, so that the rects compare. Room at
  // the top for the well's label.
  for (int g = 0; g < 3; ++g) {
    if (rect_of[g]) fit_axis(rect_of[g]->axis(QCPAxis::atBottom), z_lo[g], z_hi[g]);
  }
  for (QCPAxisRect* rect : rects) {
    fit_axis(rect->axis(QCPAxis::atLeft), f_lo, f_hi + 0.1 * (f_hi - f_lo));
  }
  loop_plot_->replot(QCustomPlot::rpQueuedReplot);
}

void ReviewView::plot_cycles() {
  cycle_plot_->clearGraphs();
  const int r = shown_record();
  if (r < 0) {
    set_plot_hint(cycle_plot_,
                  !analysis_ ? (analysis_running_ ? tr("Analysing\u2026") : tr("No analysis yet"))
                             : tr("The recording shown was not analysed"));
    cycle_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  const analysis::RecordAnalysis& record = analysis_->campaign.records[std::size_t(r)];
  if (record.cycles.empty()) {
    set_plot_hint(cycle_plot_, tr("No stepped-sine cycles in %1").arg(text(record.name)));
    cycle_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(cycle_plot_, {});
  // Which level's steady part holds a cycle (its well), if any.
  const auto steady_well = [&](const analysis::CycleFit& cycle) -> const analysis::Well* {
    for (const analysis::LevelResult& level : record.levels) {
      if (cycle.start_s >= level.start_s - 1e-9 && cycle.end_s <= level.end_s + 1e-9) {
        return &level.well;
      }
    }
    return nullptr;
  };
  QVector<double> other_t, other_e;
  struct WellCycles {
    analysis::Well well;
    QVector<double> t_s, edc_mj;
  };
  std::map<std::string, WellCycles> by_well;  // by the well's name: the legend's order
  for (const analysis::CycleFit& cycle : record.cycles) {
    const double t_s = 0.5 * (cycle.start_s + cycle.end_s);
    if (const analysis::Well* well = steady_well(cycle)) {
      WellCycles& cycles =
          by_well.try_emplace(to_string(*well), WellCycles{*well, {}, {}}).first->second;
      cycles.t_s.push_back(t_s);
      cycles.edc_mj.push_back(1e3 * cycle.edc_j);
    } else {
      other_t.push_back(t_s);
      other_e.push_back(1e3 * cycle.edc_j);
    }
  }
  QCPGraph* other = cycle_plot_->addGraph();
  other->setName(tr("transient or between levels"));
  other->setLineStyle(QCPGraph::lsNone);
  other->setScatterStyle(disc_markers(QColor(160, 160, 160), 3));
  other->setData(other_t, other_e, true);
  for (const auto& [name, cycles] : by_well) {
    QCPGraph* graph = cycle_plot_->addGraph();
    graph->setName(tr("steady cycles, %1 well").arg(text(name)));
    graph->setLineStyle(QCPGraph::lsNone);
    graph->setScatterStyle(disc_markers(well_colour(cycles.well), 4));
    graph->setData(cycles.t_s, cycles.edc_mj, true);
  }
  // Each level's mean as a segment over its steady part; NaN between levels breaks the line.
  QVector<double> mean_t, mean_e;
  for (const analysis::LevelResult& level : record.levels) {
    if (!mean_t.isEmpty()) {
      mean_t.push_back(0.5 * (mean_t.back() + level.start_s));
      mean_e.push_back(std::numeric_limits<double>::quiet_NaN());
    }
    mean_t << level.start_s << level.end_s;
    mean_e << 1e3 * level.edc_mean_j << 1e3 * level.edc_mean_j;
  }
  QCPGraph* means = cycle_plot_->addGraph();
  means->setName(tr("level mean"));
  means->setPen(QPen(Qt::black, 1.5));
  means->setData(mean_t, mean_e, true);
  const TimeWindow window = record_view_->time_window();
  follow_time_window(window.start_s, window.end_s);
}

void ReviewView::follow_time_window(double start_s, double end_s) {
  cycle_plot_->xAxis->setRange(start_s, end_s);
  double lo = INFINITY, hi = -INFINITY;
  for (int g = 0; g < cycle_plot_->graphCount(); ++g) {
    bool found = false;
    const QCPRange range =
        cycle_plot_->graph(g)->getValueRange(found, QCP::sdPositive, QCPRange(start_s, end_s));
    if (!found) continue;
    lo = std::min(lo, range.lower);
    hi = std::max(hi, range.upper);
  }
  // Log axis: a factor 1.3 of room below and above the EDCs in view.
  if (lo <= hi) cycle_plot_->yAxis->setRange(lo / 1.3, hi * 1.3);
  cycle_plot_->replot(QCustomPlot::rpQueuedReplot);
}

void ReviewView::plot_cycle_cursor() {
  const std::optional<double> t_s = cursor_time();
  cycle_cursor_->setVisible(t_s.has_value() && shown_record() >= 0);
  if (t_s) {
    cycle_cursor_->point1->setCoords(*t_s, 0.0);
    cycle_cursor_->point2->setCoords(*t_s, 1.0);
  }
  cycle_plot_->layer("cursor")->replot();
}

void ReviewView::plot_slices() {
  stiffness_plot_->clearPlottables();
  damping_plot_->clearPlottables();
  stiffness_label_->clear();
  const analysis::CampaignAnalysis* campaign = analysis_ ? &analysis_->campaign : nullptr;
  if (!campaign || !campaign->stiffness) {
    const QString why = !analysis_
                            ? (analysis_running_ ? tr("Analysing\u2026") : tr("No analysis yet"))
                            : tr("No restoring force: %1").arg(text(campaign->rfs_message));
    set_plot_hint(stiffness_plot_, why);
    set_plot_hint(damping_plot_, why);
    stiffness_plot_->replot(QCustomPlot::rpQueuedReplot);
    damping_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(stiffness_plot_, {});
  const analysis::StiffnessSlice& slice = *campaign->stiffness;

  // Stiffness slice: the samples, their bin means and the fitted cubic.
  const ScatterPoints samples = stiffness_points(*campaign, kMaxScatterPoints);
  std::vector<double> bin_z, bin_r;
  for (const analysis::SliceBin& bin : slice.bins) {
    bin_z.push_back(bin.x);
    bin_r.push_back(bin.force_n);
  }
  const DisplayUnit z_unit = choose_display_unit("m", max_abs({&samples.x, &bin_z}));
  const DisplayUnit r_unit = choose_display_unit("N", max_abs({&samples.y, &bin_r}));
  const DisplayUnit band_unit = choose_display_unit("m/s", slice.velocity_band_m_s);
  const bool about_mean = analysis_ && analysis_->campaign.z_about_mean;
  stiffness_plot_->xAxis->setLabel(
      (about_mean ? tr("z \u2212 z\u0304 [%1]") : tr("z [%1]")).arg(text(z_unit.symbol)));
  stiffness_plot_->yAxis->setLabel(tr("restoring force R [%1]").arg(slice_force_unit(r_unit)));
  const auto to_display = [](const std::vector<double>& v, const DisplayUnit& unit) {
    QVector<double> out(qsizetype(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) out[qsizetype(i)] = unit.to_display(v[i]);
    return out;
  };
  QCPGraph* cloud = stiffness_plot_->addGraph();
  cloud->setName(tr("samples, |\u017c| < \u03b5_s = %1 %2 (%3)")
                     .arg(band_unit.to_display(slice.velocity_band_m_s), 0, 'g', 3)
                     .arg(text(band_unit.symbol))
                     .arg(samples.selected));
  cloud->setLineStyle(QCPGraph::lsNone);
  cloud->setScatterStyle(disc_markers(kSampleColour, 2));
  cloud->setData(to_display(samples.x, z_unit), to_display(samples.y, r_unit));
  QCPGraph* bins = stiffness_plot_->addGraph();
  bins->setName(tr("bin means (%1 bins)").arg(slice.bins.size()));
  bins->setLineStyle(QCPGraph::lsNone);
  bins->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, QColor(0, 60, 140), 5));
  bins->setData(to_display(bin_z, z_unit), to_display(bin_r, r_unit), true);
  QVector<double> fit_z, fit_r;
  for (int i = 0; i <= kCurvePoints; ++i) {
    const double z = slice.z_min_m + (slice.z_max_m - slice.z_min_m) * i / kCurvePoints;
    fit_z.push_back(z_unit.to_display(z));
    fit_r.push_back(r_unit.to_display(slice.fit.value(z)));
  }
  QCPGraph* fit = stiffness_plot_->addGraph();
  fit->setName(tr("fitted K(z), eq. (2)"));
  fit->setPen(QPen(kFitColour, 2.0));
  fit->setData(fit_z, fit_r, true);
  stiffness_plot_->rescaleAxes();
  const QCPRange r_range = stiffness_plot_->yAxis->range();
  fit_axis(stiffness_plot_->xAxis, stiffness_plot_->xAxis->range().lower,
           stiffness_plot_->xAxis->range().upper);
  // Room above the data for the legend (three entries).
  stiffness_plot_->yAxis->setRange(r_range.lower - kRangeMargin * r_range.size(),
                                   r_range.upper + 0.35 * r_range.size());
  stiffness_label_->setText(text(stiffness_fit_text(
      slice, analysis::mass_basis(analysis_->campaign) == analysis::MassBasis::PerUnitMass)));
  stiffness_plot_->replot(QCustomPlot::rpQueuedReplot);

  // Damping slices: samples and bin means of each, by equilibrium.
  if (campaign->damping.empty()) {
    set_plot_hint(damping_plot_, tr("The fitted K(z) has no stable zero in the travelled range"));
    damping_plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(damping_plot_, {});
  std::vector<ScatterPoints> clouds;
  double v_max = 0.0, d_max = 0.0;
  for (const analysis::DampingSlice& d : campaign->damping) {
    clouds.push_back(damping_points(*campaign, d, kMaxScatterPoints / campaign->damping.size()));
    v_max = std::max(v_max, max_abs({&clouds.back().x}));
    d_max = std::max(d_max, max_abs({&clouds.back().y}));
  }
  const DisplayUnit v_unit = choose_display_unit("m/s", v_max);
  const DisplayUnit d_unit = choose_display_unit("N", d_max);
  damping_plot_->xAxis->setLabel(tr("\u017c [%1]").arg(text(v_unit.symbol)));
  damping_plot_->yAxis->setLabel(tr("D = R \u2212 K(z) [%1]").arg(slice_force_unit(d_unit)));
  for (std::size_t i = 0; i < campaign->damping.size(); ++i) {
    const analysis::DampingSlice& d = campaign->damping[i];
    const QColor colour = kSliceColour[d.z_center_m < 0.0 ? 0 : 1];
    const QString where = tr("z\u0304 = %1 %2")
                              .arg(z_unit.to_display(d.z_center_m), 0, 'f', 2)
                              .arg(text(z_unit.symbol));
    QCPGraph* points = damping_plot_->addGraph();
    points->setName(tr("%1: samples (%2)").arg(where).arg(clouds[i].selected));
    points->setLineStyle(QCPGraph::lsNone);
    points->setScatterStyle(disc_markers(colour.lighter(140), 2));
    points->setData(to_display(clouds[i].x, v_unit), to_display(clouds[i].y, d_unit));
    std::vector<double> bin_v, bin_d;
    for (const analysis::SliceBin& bin : d.bins) {
      bin_v.push_back(bin.x);
      bin_d.push_back(bin.force_n);
    }
    QCPGraph* means = damping_plot_->addGraph();
    means->setName(tr("%1: bin means").arg(where));
    means->setPen(QPen(colour.darker(130), 1.5));
    means->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, colour.darker(130), 5));
    means->setData(to_display(bin_v, v_unit), to_display(bin_d, d_unit), true);
  }
  damping_plot_->rescaleAxes();
  const QCPRange d_range = damping_plot_->yAxis->range();
  fit_axis(damping_plot_->xAxis, damping_plot_->xAxis->range().lower,
           damping_plot_->xAxis->range().upper);
  damping_plot_->yAxis->setRange(
      d_range.lower - kRangeMargin * d_range.size(),
      d_range.upper + 0.12 * double(2 * campaign->damping.size() + 1) * d_range.size());
  damping_plot_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace oscilab::ui
