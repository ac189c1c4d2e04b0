#include "ui/review/channel_mapping_dialog.h"
#include "ui/qt_text.h"

#include <utility>

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>
#include <QVBoxLayout>

#include "analysis/common/input_error.h"

namespace oscilab::ui {
namespace {

const char* const kQuantities[] = {"acceleration", "velocity", "displacement"};

// The units the sidecar knows for a quantity, and "V" (scale = sensitivity in SI per volt).
QStringList units_for(const QString& quantity) {
  if (quantity == "acceleration") return {"m/s^2", "mm/s^2", "g", "V"};
  if (quantity == "velocity") return {"m/s", "mm/s", "um/s", "V"};
  return {"m", "mm", "um", "V"};
}

}  // namespace

ChannelMappingDialog::ChannelMappingDialog(const QString& path, const daq::FileContents& contents,
                                           QWidget* parent)
    : QDialog(parent), contents_(contents) {
  setWindowTitle(
      tr("Which signals are the base and the mass? \u2014 %1").arg(QFileInfo(path).fileName()));
  auto* intro = new QLabel(
      tr("%1 has no sidecar (%2), so Oscilab does not know what its signals measure. Choose "
         "them below; the answer is saved as that sidecar.")
          .arg(QFileInfo(path).fileName(),
               QFileInfo(QString::fromStdString(daq::sidecar_path_for(path.toStdString())))
                   .fileName()));
  intro->setWordWrap(true);

  auto* grid = new QGridLayout;
  const QStringList headers = {tr("channel"), tr("signal in the file"),
                               tr("column"),  tr("quantity"),
                               tr("unit"),    tr("scale"),
                               tr("offset")};
  for (int c = 0; c < headers.size(); ++c) grid->addWidget(new QLabel(headers[c]), 0, c);
  const QString names[2] = {tr("base (table)"), tr("mass")};
  const char* object_names[2] = {"base", "mass"};
  for (int i = 0; i < 2; ++i) {
    ChannelRow& row = rows_[i];
    row.signal = new QComboBox;
    for (const daq::FileSignal& signal : contents_.file_signals) {
      QString label = qtext(signal.name) + tr(" (%1 samples").arg(signal.sample_count);
      if (signal.columns > 1) label += tr(" \u00d7 %1").arg(signal.columns);
      if (!signal.unit.empty()) label += ", " + qtext(signal.unit);
      row.signal->addItem(label + ")", qtext(signal.name));
    }
    row.column = new QSpinBox;
    row.column->setRange(-1, 0);
    row.column->setSpecialValueText(tr("\u2014"));
    row.quantity = new QComboBox;
    for (const char* quantity : kQuantities) row.quantity->addItem(quantity);
    row.unit = new QComboBox;
    row.unit->setEditable(true);
    row.scale = new QLineEdit("1");
    row.offset = new QLineEdit("0");
    row.scale->setToolTip(tr("value in the unit = scale \u00d7 stored + offset"));
    for (QWidget* widget : std::initializer_list<QWidget*>{row.signal, row.column, row.quantity,
                                                           row.unit, row.scale, row.offset}) {
      widget->setObjectName(QString("%1_%2")
                                .arg(object_names[i])
                                .arg(widget == row.signal     ? "signal"
                                     : widget == row.column   ? "column"
                                     : widget == row.quantity ? "quantity"
                                     : widget == row.unit     ? "unit"
                                     : widget == row.scale    ? "scale"
                                                              : "offset"));
    }
    grid->addWidget(new QLabel(names[i]), i + 1, 0);
    grid->addWidget(row.signal, i + 1, 1);
    grid->addWidget(row.column, i + 1, 2);
    grid->addWidget(row.quantity, i + 1, 3);
    grid->addWidget(row.unit, i + 1, 4);
    grid->addWidget(row.scale, i + 1, 5);
    grid->addWidget(row.offset, i + 1, 6);
    connect(row.quantity, &QComboBox::currentTextChanged, this, [&row](const QString& quantity) {
      const QString unit = row.unit->currentText();
      row.unit->clear();
      row.unit->addItems(units_for(quantity));
      if (units_for(quantity).contains(unit)) row.unit->setCurrentText(unit);
    });
    connect(row.signal, &QComboBox::currentIndexChanged, this,
            [this, &row] { update_column_range(row); });
    row.unit->addItems(units_for(row.quantity->currentText()));
  }

  rate_edit_ = new QLineEdit;
  rate_edit_->setObjectName("rate");
  mass_edit_ = new QLineEdit;
  mass_edit_->setObjectName("mass");
  mass_edit_->setPlaceholderText(tr("unknown: forces and energies per unit mass"));
  auto* form = new QFormLayout;
  form->addRow(tr("sample rate [Hz]"), rate_edit_);
  form->addRow(tr("moving mass [kg]"), mass_edit_);

  notes_label_ = new QLabel;
  notes_label_->setWordWrap(true);
  notes_label_->setObjectName("notes");
  problem_label_ = new QLabel;
  problem_label_->setWordWrap(true);
  problem_label_->setObjectName("problem");
  problem_label_->setStyleSheet("color: #b00020");
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  connect(buttons, &QDialogButtonBox::accepted, this, &ChannelMappingDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(intro);
  layout->addLayout(grid);
  layout->addLayout(form);
  layout->addWidget(notes_label_);
  layout->addWidget(problem_label_);
  layout->addWidget(buttons);
  fill_from_draft(daq::draft_sidecar(contents_));
}

void ChannelMappingDialog::update_column_range(const ChannelRow& row) {
  const int index = row.signal->currentIndex();
  const std::int64_t columns =
      index >= 0 ? contents_.file_signals[static_cast<std::size_t>(index)].columns : 1;
  row.column->setRange(columns > 1 ? 0 : -1, columns > 1 ? int(columns - 1) : -1);
  row.column->setEnabled(columns > 1);
}

void ChannelMappingDialog::fill_from_draft(const daq::SidecarDraft& draft) {
  const auto& sidecar = draft.sidecar;
  if (sidecar.contains("sample_rate_hz") && sidecar["sample_rate_hz"].is_number()) {
    rate_edit_->setText(QString::number(sidecar["sample_rate_hz"].get<double>(), 'g', 17));
  }
  const auto& channels = sidecar["channels"];
  for (std::size_t i = 0; i < 2 && i < channels.size(); ++i) {
    const auto& channel = channels[i];
    ChannelRow& row = rows_[i];
    const QString source = qtext(channel.value("source", channel.value("name", std::string())));
    row.signal->setCurrentIndex(std::max(0, row.signal->findData(source)));
    update_column_range(row);
    if (channel.contains("column")) row.column->setValue(channel["column"].get<int>());
    row.quantity->setCurrentText(qtext(channel["quantity"].get<std::string>()));
    row.unit->setCurrentText(qtext(channel["unit"].get<std::string>()));
  }
  QStringList notes;
  for (const std::string& note : draft.notes) notes << qtext(note);
  notes_label_->setText(tr("Guessed from the file:\n%1").arg(notes.join('\n')));
}

std::optional<daq::Sidecar> ChannelMappingDialog::sidecar() const {
  nlohmann::json json;
  json["format"] = daq::kSidecarFormat;
  bool ok = false;
  const double rate_hz = rate_edit_->text().trimmed().toDouble(&ok);
  json["sample_rate_hz"] = ok ? nlohmann::json(rate_hz) : nlohmann::json(nullptr);
  if (!mass_edit_->text().trimmed().isEmpty()) {
    const double mass_kg = mass_edit_->text().trimmed().toDouble(&ok);
    json["mass_kg"] =
        ok ? nlohmann::json(mass_kg) : nlohmann::json(mass_edit_->text().toStdString());
  }
  json["channels"] = nlohmann::json::array();
  const char* roles[2] = {"base", "mass"};
  for (int i = 0; i < 2; ++i) {
    const ChannelRow& row = rows_[i];
    const std::string source = row.signal->currentData().toString().toStdString();
    nlohmann::json channel;
    // A file of named signals is mapped by "source"; a sound file or a CSV by name and order.
    channel["name"] = contents_.picked_by_source ? std::string(roles[i]) : source;
    channel["role"] = roles[i];
    channel["quantity"] = row.quantity->currentText().toStdString();
    channel["unit"] = row.unit->currentText().trimmed().toStdString();
    const double scale = row.scale->text().trimmed().toDouble(&ok);
    channel["scale"] = ok ? nlohmann::json(scale) : nlohmann::json(row.scale->text().toStdString());
    const double offset = row.offset->text().trimmed().toDouble(&ok);
    channel["offset"] =
        ok ? nlohmann::json(offset) : nlohmann::json(row.offset->text().toStdString());
    if (contents_.picked_by_source) {
      channel["source"] = source;
      if (row.column->isEnabled()) channel["column"] = row.column->value();
    }
    json["channels"].push_back(channel);
  }
  // A sound file's sidecar lists its channels in the file's order.
  if (!contents_.picked_by_source &&
      rows_[0].signal->currentIndex() > rows_[1].signal->currentIndex()) {
    std::swap(json["channels"][0], json["channels"][1]);
  }
  try {
    problem_.clear();
    return daq::parse_sidecar(json, tr("the form").toStdString());
  } catch (const InputError& error) {
    problem_ = QString::fromStdString(error.what());
    return std::nullopt;
  }
}

void ChannelMappingDialog::accept() {
  if (!sidecar()) {
    problem_label_->setText(problem_);
    return;
  }
  QDialog::accept();
}

}  // namespace oscilab::ui
