#pragma once

#include <string>

#include <QGroupBox>

#include "analysis/identification/edc_fit.h"
#include "analysis/identification/fit_setup.h"

class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QSpinBox;

namespace oscilab::ui {

/// The choices of a fit, as `oscilab-cli fit` offers them: the base model (paper, illustrative or
/// a model JSON), the stiffness source, the search (CMA-ES with its evaluations, or the paper's GA
/// with its population and generations) and how the levels are weighed (harmonics H; the σ
/// budget or a fixed model-error floor). It only holds the choices; the fit panel runs them.
/// Its widgets carry object names for tests: base_model, stiffness, method, evaluations,
/// population, generations, harmonics, model_error.
class FitSettingsForm : public QGroupBox {
 public:
  explicit FitSettingsForm(QWidget* parent = nullptr);

  /// The base model, stiffness source and cost settings shown (throws InputError for a model
  /// file that cannot be read).
  analysis::FitSetup fit_setup() const;
  /// The search shown: method, budget, GA population and generations with the default elite;
  /// the rest as analysis::FitOptions' defaults. Check it with analysis::validate.
  analysis::FitOptions fit_options() const;
  /// Method "cmaes" or "ga"; evaluations of CMA-ES; the GA's population and generations.
  void set_search(const std::string& method, int evaluations, int population, int generations);

 private:
  QLineEdit* model_edit_ = nullptr;
  QComboBox* stiffness_box_ = nullptr;
  QComboBox* method_box_ = nullptr;
  QSpinBox* evaluations_box_ = nullptr;
  QSpinBox* population_box_ = nullptr;
  QSpinBox* generations_box_ = nullptr;
  QSpinBox* harmonics_box_ = nullptr;
  QDoubleSpinBox* model_error_box_ = nullptr;
};

}  // namespace oscilab::ui
