#pragma once

#include <optional>

#include <QDialog>

#include "daq/recording/format_reader.h"
#include "daq/recording/sidecar.h"
#include "daq/recording/sidecar_draft.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QSpinBox;

namespace oscilab::ui {

/// Asks which of a file's signals are the base and the mass, with their quantity, unit and
/// calibration, the rate and the mass, for a file that has no sidecar (File ▸ Open of a file
/// another program wrote). Starts from daq::draft_sidecar; OK validates the answer with the
/// sidecar's own rules and says what is wrong in the dialog instead of closing.
class ChannelMappingDialog : public QDialog {
  Q_OBJECT

 public:
  ChannelMappingDialog(const QString& path, const daq::FileContents& contents,
                       QWidget* parent = nullptr);

  /// The sidecar the form describes, or nothing (with problem() saying why) when it is not
  /// valid yet.
  std::optional<daq::Sidecar> sidecar() const;
  QString problem() const { return problem_; }

  /// One channel's row of the form (public for tests).
  struct ChannelRow {
    QComboBox* signal = nullptr;
    QSpinBox* column = nullptr;  // the column of a matrix signal; -1 (blank) for a vector
    QComboBox* quantity = nullptr;
    QComboBox* unit = nullptr;   // editable
    QLineEdit* scale = nullptr;  // text, so that 1e-7 stays exact
    QLineEdit* offset = nullptr;
  };
  const ChannelRow& base_row() const { return rows_[0]; }
  const ChannelRow& mass_row() const { return rows_[1]; }
  QLineEdit* rate_edit() const { return rate_edit_; }
  QLineEdit* mass_edit() const { return mass_edit_; }

  void accept() override;

 private:
  void fill_from_draft(const daq::SidecarDraft& draft);
  void update_column_range(const ChannelRow& row);

  daq::FileContents contents_;
  ChannelRow rows_[2];
  QLineEdit* rate_edit_ = nullptr;
  QLineEdit* mass_edit_ = nullptr;
  QLabel* notes_label_ = nullptr;
  QLabel* problem_label_ = nullptr;
  mutable QString problem_;
};

}  // namespace oscilab::ui
