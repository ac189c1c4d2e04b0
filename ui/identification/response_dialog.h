#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QDialog>
#include <QString>

#include "analysis/hbm/branch.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model.h"
#include "analysis/simulation/bifurcation_map.h"

class QCustomPlot;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace oscilab::ui {

class BifurcationMapJob;
class BranchJob;

/// The response of a model (the fitted one, from the fit panel) in a window of its own:
///
/// - Kind::Branch: one harmonic-balance branch per well by pseudo-arclength continuation in the
///   forcing amplitude f0 at the test frequency (analysis::continue_branch, as `oscilab-cli
///   hbm`), drawn as Fig. 11 (amplitude and EDC against f0, stable parts solid, unstable dashed,
///   folds and period doublings marked; ui/hbm_figures);
/// - Kind::Map: the bifurcation map by time simulation (analysis::bifurcation_map, Fig. 17): z
///   once per forcing period at each level, over the HBM orbit of the same branches.
///
/// The settings (f0 range, harmonics, step; for the map: level step, periods per level, periods
/// sampled) sit above the plot; Compute runs the work on a worker thread with progress and cancel
/// (ui/identification/branch_job, ui/identification/bifurcation_map_job),
/// "Export CSV…" writes the branch CSV (docs/contracts.md §3, a `well` column with two wells) or
/// the map CSV. The dialog shows; the computing is the analysis core's. UI thread only.
class ResponseDialog : public QDialog {
  Q_OBJECT

 public:
  enum class Kind { Branch, Map };
  /// A well to follow and the frequency of its test.
  struct Well {
    bool positive = true;
    double freq_hz = 9.0;
  };
  struct Setup {
    std::shared_ptr<const analysis::Model> model;
    std::string model_name = "model";  // in the figure's title
    std::vector<Well> wells;
    double start_n = 0.1;  // f0 range, N
    double end_n = 3.7;
    int harmonics = 7;  // H of the harmonic balance
  };

  ResponseDialog(Kind kind, Setup setup, QWidget* parent = nullptr);
  ~ResponseDialog() override;

  Kind kind() const { return kind_; }
  void set_f0_range(double start_n, double end_n);
  void set_harmonics(int harmonics);
  /// Map only: level step [N], forcing periods per level, periods sampled at the end of each.
  void set_map_settings(double step_n, int hold_periods, int sampled_periods);
  /// The continuation of one well as Compute runs it (the settings shown).
  analysis::ContinuationOptions continuation_options(const Well& well) const;
  /// The map as Compute runs it (Kind::Map).
  analysis::BifurcationMapOptions map_options() const;

  /// Starts the computation with the settings shown (does nothing while one runs).
  void start();
  void cancel();
  bool busy() const;

  /// The last computation's branches, one per well in Setup order (empty before), and map.
  const std::vector<analysis::Branch>& branches() const { return branches_; }
  const analysis::BifurcationMap& map() const { return map_; }
  /// Writes the branch CSV (Kind::Branch) or the map CSV (Kind::Map) of the last computation.
  /// Returns false with the reason in the status label when there is none or the file cannot be
  /// written.
  bool export_csv(const QString& path);

  QCustomPlot* plot() const { return plot_; }
  QLabel* status_label() const { return status_label_; }
  QPushButton* compute_button() const { return compute_button_; }
  QPushButton* cancel_button() const { return cancel_button_; }
  QPushButton* export_button() const { return export_button_; }

 Q_SIGNALS:
  /// A computation ended (finished, cancelled or failed); `message` says how.
  void computed(const QString& message);

 private:
  /// Shows how a computation ended: the branches (and the map) when it finished.
  void show_outcome(const std::string& error, bool cancelled,
                    const std::vector<analysis::Branch>& branches,
                    const analysis::BifurcationMap& map);
  void set_busy(bool busy);
  void draw();
  std::string title() const;

  Kind kind_;
  Setup setup_;
  BranchJob* branch_job_ = nullptr;       // Kind::Branch
  BifurcationMapJob* map_job_ = nullptr;  // Kind::Map
  std::vector<analysis::Branch> branches_;
  analysis::BifurcationMap map_;
  int harmonics_computing_ = 7;  // of the computation that runs
  int harmonics_shown_ = 7;      // of the branches shown (the title names it)

  QDoubleSpinBox* start_box_ = nullptr;
  QDoubleSpinBox* end_box_ = nullptr;
  QSpinBox* harmonics_box_ = nullptr;
  QDoubleSpinBox* max_step_box_ = nullptr;
  QDoubleSpinBox* map_step_box_ = nullptr;
  QSpinBox* hold_box_ = nullptr;
  QSpinBox* sampled_box_ = nullptr;
  QPushButton* compute_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
  QPushButton* export_button_ = nullptr;
  QPushButton* figure_button_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* status_label_ = nullptr;
  QCustomPlot* plot_ = nullptr;
};

}  // namespace oscilab::ui
