// The parameter panel: one field per descriptor of a ParameterTable (spin
// boxes and combo boxes in a QFormLayout per group), validated on every edit
// with errors shown inline under the field at fault. A valid edit becomes a
// command on the panel's QUndoStack (consecutive edits of one field merge)
// and emits parametersChanged; an invalid one changes nothing until fixed.
#pragma once

#include <QMap>
#include <QString>
#include <QWidget>

#include "ui/session/parameters.h"

class QLabel;
class QUndoStack;

namespace hull::ui {

class ParameterPanel : public QWidget {
  Q_OBJECT

 public:
  ParameterPanel(ParameterTable table, ParameterValidator validator, QWidget* parent = nullptr);
  ~ParameterPanel() override;

  const ParameterTable& table() const { return table_; }
  const ParameterValidator& validator() const { return validator_; }
  // The values in force (the last valid edit, undo or SetValues).
  const ParameterValues& values() const { return values_; }
  QUndoStack* undoStack() const { return undo_; }

  // Replaces the values without an undo step and clears the undo history
  // (opening a project); values are assumed valid. Emits parametersChanged.
  void ResetValues(const ParameterValues& values);
  // Sets the defaults as one undoable step.
  void RestoreDefaults();

  // The field's editor widget (QDoubleSpinBox, QSpinBox or QComboBox) and
  // its inline error ("" when valid): for the tests and for later wiring.
  // errorText("") gives the errors that name no field of the table.
  QWidget* editor(const QString& key) const;
  QString errorText(const QString& key) const;

 signals:
  void parametersChanged(const hull::ui::ParameterValues& values);

 private:
  friend class SetParametersCommand;
  // Applies values (from the undo stack): widgets, errors, signal.
  void Apply(const ParameterValues& values);
  void OnEdited(const QString& key);
  ParameterValues ReadEditors() const;
  void WriteEditors(const ParameterValues& values);
  void ShowErrors(const std::vector<ParameterError>& errors);
  // Why an editor refused what was typed (RefusedEntry), under the field.
  void ShowRefused(const QString& key, const QString& text);

  ParameterTable table_;
  ParameterValidator validator_;
  ParameterValues values_;
  QUndoStack* undo_ = nullptr;
  QMap<QString, QWidget*> editors_;
  QMap<QString, QLabel*> errors_;
  QLabel* other_errors_ = nullptr;  // errors naming no field of the table
};

}  // namespace hull::ui
