#include "ui/identification/fit_settings_form.h"

#include <algorithm>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>

#include "analysis/model/model_json.h"

namespace oscilab::ui {

FitSettingsForm::FitSettingsForm(QWidget* parent)
    : QGroupBox(tr("Fit of \u03b8 = [f_d(z\u208b*), f_d(z\u208a*), f_d(0), v_t, k_s, c]"), parent) {
  method_box_ = new QComboBox;
  method_box_->setObjectName("method");
  method_box_->addItem(tr("CMA-ES + BOBYQA polish"), "cmaes");
  method_box_->addItem(tr("genetic algorithm (paper)"), "ga");
  // The defaults and lower limits are the analysis core's (as `oscilab-cli fit` and Python).
  const analysis::FitOptions defaults;
  method_box_->setCurrentIndex(std::max(0, method_box_->findData(QString::fromStdString(
                                               analysis::fit_method_name(defaults.method)))));
  evaluations_box_ = new QSpinBox;
  evaluations_box_->setObjectName("evaluations");
  evaluations_box_->setRange(static_cast<int>(analysis::kMinFitEvaluations), 100000);
  evaluations_box_->setValue(static_cast<int>(defaults.max_evaluations));
  population_box_ = new QSpinBox;
  population_box_->setObjectName("population");
  population_box_->setRange(analysis::kMinGeneticPopulation, 10000);
  population_box_->setValue(defaults.genetic.population);
  generations_box_ = new QSpinBox;
  generations_box_->setObjectName("generations");
  generations_box_->setRange(0, 10000);
  generations_box_->setValue(defaults.genetic.generations);
  // The GA's budget, population × (generations + 1), stays within the evaluations a fit accepts
  // (analysis::validate, as `oscilab-cli fit` refuses more): each box's maximum follows the other.
  const auto bound_budget = [this] {
    const long population = population_box_->value();
    const long generations = generations_box_->value();
    generations_box_->setMaximum(
        static_cast<int>(std::min(10000L, analysis::kMaxFitEvaluations / population - 1)));
    population_box_->setMaximum(
        static_cast<int>(std::min(10000L, analysis::kMaxFitEvaluations / (generations + 1))));
  };
  bound_budget();
  connect(population_box_, &QSpinBox::valueChanged, this, bound_budget);
  connect(generations_box_, &QSpinBox::valueChanged, this, bound_budget);
  // What `oscilab-cli fit` offers besides the search: the base model, the stiffness source and
  // how the levels are weighed (analysis::FitSetup).
  model_edit_ = new QLineEdit(QStringLiteral("paper"));
  model_edit_->setObjectName("base_model");
  model_edit_->setToolTip(
      tr("Mass, stiffness and starting friction: \"paper\" (Tables 1 and "
         "3), \"illustrative\" (Table 2) or a model JSON file"));
  auto* model_browse = new QPushButton(tr("\u2026"));
  model_browse->setToolTip(tr("Choose a model JSON file"));
  connect(model_browse, &QPushButton::clicked, this, [this] {
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Base model"), QString(), tr("Model (*.json)"));
    if (!path.isEmpty()) model_edit_->setText(path);
  });
  auto* model_row = new QHBoxLayout;
  model_row->addWidget(model_edit_, 1);
  model_row->addWidget(model_browse);
  stiffness_box_ = new QComboBox;
  stiffness_box_->setObjectName("stiffness");
  stiffness_box_->addItem(tr("the model's K(z)"), "model");
  stiffness_box_->addItem(tr("cubic fit of the restoring-force slice"), "rfs");
  stiffness_box_->addItem(tr("identified with the friction (from the slice)"), "identified");
  // As `oscilab-cli diagnose` does by default: a lab's K(z) is measured, with its errors, and a
  // stiffness held at such an estimate reads as a missing effect.
  stiffness_box_->setCurrentIndex(stiffness_box_->findData("identified"));
  stiffness_box_->setToolTip(
      tr("Where K(z) comes from: identified with the friction, starting from the random record's "
         "restoring-force slice (the default); that slice's cubic held fixed; or the base "
         "model's K(z) held fixed"));
  harmonics_box_ = new QSpinBox;
  harmonics_box_->setObjectName("harmonics");
  harmonics_box_->setRange(1, 63);
  harmonics_box_->setValue(analysis::EdcCostSettings{}.hbm.harmonics);
  harmonics_box_->setToolTip(tr("Harmonics H of the model's harmonic balance in every evaluation"));
  model_error_box_ = new QDoubleSpinBox;
  model_error_box_->setObjectName("model_error");
  model_error_box_->setRange(-0.1, 50.0);
  model_error_box_->setDecimals(1);
  model_error_box_->setSingleStep(0.1);
  model_error_box_->setSuffix(tr(" %"));
  model_error_box_->setSpecialValueText(tr("\u03c3 budget"));
  model_error_box_->setValue(model_error_box_->minimum());
  model_error_box_->setToolTip(
      tr("Each level's \u03c3: the \u03c3 budget (cycles, estimator bias, the model's truncation "
         "error, H corrected to a converged reference), or a fixed relative model-error floor"));
  // Long choices elide in the closed box (the list shows them in full), so that the form fits a
  // panel a third of a laptop screen wide.
  for (QComboBox* box : {method_box_, stiffness_box_}) {
    box->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    box->setMinimumContentsLength(14);
  }
  auto* form = new QFormLayout(this);
  form->addRow(tr("Base model"), model_row);
  form->addRow(tr("Stiffness"), stiffness_box_);
  form->addRow(tr("Method"), method_box_);
  form->addRow(tr("Evaluations (CMA-ES)"), evaluations_box_);
  form->addRow(tr("Population (GA)"), population_box_);
  form->addRow(tr("Generations (GA)"), generations_box_);
  form->addRow(tr("Harmonics (H)"), harmonics_box_);
  form->addRow(tr("Model error"), model_error_box_);
}

analysis::FitSetup FitSettingsForm::fit_setup() const {
  analysis::FitSetup setup;
  setup.base_model = analysis::model_from_spec(model_edit_->text().trimmed().toStdString());
  setup.stiffness = analysis::parse_stiffness_source(
      stiffness_box_->currentData().toString().toStdString(), "Stiffness");
  // The spin box's minimum reads "σ budget" (a negative floor, as --model-error takes it).
  setup.cost = analysis::cost_settings(
      harmonics_box_->value(), analysis::EdcCostSettings().max_harmonics,
      model_error_box_->value() <= model_error_box_->minimum() ? -1.0
                                                               : 0.01 * model_error_box_->value(),
      "Harmonics (H)", "reference H");
  return setup;
}

analysis::FitOptions FitSettingsForm::fit_options() const {
  analysis::FitOptions options;
  options.method = analysis::parse_fit_method(method_box_->currentData().toString().toStdString());
  options.max_evaluations = evaluations_box_->value();
  options.genetic.population = population_box_->value();
  options.genetic.generations = generations_box_->value();
  options.genetic.elite = analysis::default_elite(population_box_->value());
  return options;
}

void FitSettingsForm::set_search(const std::string& method, int evaluations, int population,
                                 int generations) {
  method_box_->setCurrentIndex(std::max(0, method_box_->findData(QString::fromStdString(method))));
  evaluations_box_->setValue(evaluations);
  population_box_->setValue(population);
  generations_box_->setValue(generations);
}

}  // namespace oscilab::ui
