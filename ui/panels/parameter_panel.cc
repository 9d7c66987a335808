#include "ui/panels/parameter_panel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QUndoCommand>
#include <QUndoStack>
#include <QVBoxLayout>
#include <functional>
#include <utility>

namespace hull::ui {

namespace {

// A spin box that tells what it refused: Qt's spin boxes drop a keystroke
// that would take the value out of their range (σ₁ = 2 with σ₁ at most
// 1 m) without a word; this one hands the text it would have become to
// `refused`, which shows why.
template <typename Base>
class RefusingSpinBox : public Base {
 public:
  using Base::Base;
  std::function<void(const QString&)> refused;

  QValidator::State validate(QString& text, int& pos) const override {
    const QValidator::State state = Base::validate(text, pos);
    if (state == QValidator::Invalid && refused) refused(text);
    return state;
  }
};

}  // namespace

// One valid change of the parameters; consecutive changes of the same field
// merge into one step (dragging a spin box's arrows is one undo).
class SetParametersCommand : public QUndoCommand {
 public:
  SetParametersCommand(ParameterPanel* panel, ParameterValues before, ParameterValues after, const QString& key,
                       const QString& text)
      : QUndoCommand(text), panel_(panel), before_(std::move(before)), after_(std::move(after)), key_(key) {}

  void undo() override { panel_->Apply(before_); }
  void redo() override { panel_->Apply(after_); }
  int id() const override { return 0x4850; }
  bool mergeWith(const QUndoCommand* other) override {
    const auto* o = static_cast<const SetParametersCommand*>(other);
    if (o->key_ != key_ || key_.isEmpty()) return false;
    after_ = o->after_;
    return true;
  }

 private:
  ParameterPanel* panel_;
  ParameterValues before_, after_;
  QString key_;  // "" for a change of several fields (never merged)
};

ParameterPanel::ParameterPanel(ParameterTable table, ParameterValidator validator, QWidget* parent)
    : QWidget(parent), table_(std::move(table)), validator_(std::move(validator)), values_(DefaultValues(table_)) {
  setObjectName(QStringLiteral("parameterPanel"));
  qRegisterMetaType<ParameterValues>("hull::ui::ParameterValues");
  undo_ = new QUndoStack(this);
  // The fields scroll when the dock is short.
  auto* root = new QVBoxLayout(this);
  root->setContentsMargins(0, 0, 0, 0);
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* content = new QWidget(scroll);
  auto* outer = new QVBoxLayout(content);
  QMap<QString, QFormLayout*> forms;
  for (const ParameterDescriptor& d : table_) {
    QFormLayout*& form = forms[d.group];
    if (!form) {
      auto* box = new QGroupBox(d.group, content);
      form = new QFormLayout(box);
      form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
      // A narrow dock puts a field under its label rather than cutting the
      // rows (and the error messages under them) at the dock's edge.
      form->setRowWrapPolicy(QFormLayout::WrapLongRows);
      outer->addWidget(box);
    }
    QWidget* editor = nullptr;
    const QString key = d.key;
    switch (d.type) {
      case ParameterDescriptor::Type::kReal: {
        auto* spin = new RefusingSpinBox<QDoubleSpinBox>(this);
        spin->refused = [this, key](const QString& text) { ShowRefused(key, text); };
        spin->setDecimals(d.decimals);
        spin->setRange(d.minimum, d.maximum);
        spin->setSingleStep(d.step);
        if (!d.unit.isEmpty()) spin->setSuffix(QStringLiteral(" ") + d.unit);
        spin->setKeyboardTracking(false);
        connect(spin, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this, key] { OnEdited(key); });
        editor = spin;
        break;
      }
      case ParameterDescriptor::Type::kInteger: {
        auto* spin = new RefusingSpinBox<QSpinBox>(this);
        spin->refused = [this, key](const QString& text) { ShowRefused(key, text); };
        spin->setRange(static_cast<int>(d.minimum), static_cast<int>(d.maximum));
        spin->setSingleStep(static_cast<int>(d.step));
        spin->setKeyboardTracking(false);
        connect(spin, qOverload<int>(&QSpinBox::valueChanged), this, [this, key] { OnEdited(key); });
        editor = spin;
        break;
      }
      case ParameterDescriptor::Type::kChoice: {
        auto* combo = new QComboBox(this);
        combo->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
        combo->setMinimumContentsLength(12);
        for (int i = 0; i < d.choice_keys.size(); ++i) combo->addItem(d.choice_labels.value(i), d.choice_keys[i]);
        connect(combo, qOverload<int>(&QComboBox::currentIndexChanged), this, [this, key] { OnEdited(key); });
        editor = combo;
        break;
      }
    }
    editor->setObjectName(d.key);
    editor->setToolTip(d.tooltip);
    auto* label = new QLabel(d.label, this);
    label->setToolTip(d.tooltip);
    form->addRow(label, editor);
    auto* error = new QLabel(this);
    error->setObjectName(d.key + QStringLiteral("_error"));
    error->setWordWrap(true);
    error->setStyleSheet(QStringLiteral("color: #c0392b;"));
    error->hide();
    form->addRow(error);
    editors_.insert(d.key, editor);
    errors_.insert(d.key, error);
  }
  other_errors_ = new QLabel(this);
  other_errors_->setObjectName(QStringLiteral("otherErrors"));
  other_errors_->setWordWrap(true);
  other_errors_->setStyleSheet(QStringLiteral("color: #c0392b;"));
  other_errors_->hide();
  outer->addWidget(other_errors_);
  auto* defaults = new QPushButton(QStringLiteral("Restore defaults"), this);
  defaults->setObjectName(QStringLiteral("restoreDefaults"));
  connect(defaults, &QPushButton::clicked, this, &ParameterPanel::RestoreDefaults);
  outer->addWidget(defaults, 0, Qt::AlignRight);
  outer->addStretch(1);
  scroll->setWidget(content);
  root->addWidget(scroll);
  WriteEditors(values_);
}

ParameterPanel::~ParameterPanel() = default;

void ParameterPanel::ResetValues(const ParameterValues& values) {
  undo_->clear();
  Apply(values);
}

void ParameterPanel::RestoreDefaults() {
  const ParameterValues defaults = DefaultValues(table_);
  if (defaults == values_ && ReadEditors() == values_) return;
  undo_->push(new SetParametersCommand(this, values_, defaults, QString(), QStringLiteral("restore defaults")));
}

QWidget* ParameterPanel::editor(const QString& key) const { return editors_.value(key); }

QString ParameterPanel::errorText(const QString& key) const {
  QLabel* label = key.isEmpty() ? other_errors_ : errors_.value(key);
  return label && !label->isHidden() ? label->text() : QString();
}

void ParameterPanel::Apply(const ParameterValues& values) {
  values_ = values;
  WriteEditors(values_);
  ShowErrors({});
  emit parametersChanged(values_);
}

void ParameterPanel::OnEdited(const QString& key) {
  const ParameterValues candidate = ReadEditors();
  const std::vector<ParameterError> errors = validator_ ? validator_(candidate) : std::vector<ParameterError>{};
  ShowErrors(errors);
  if (!errors.empty() || candidate == values_) return;
  const ParameterDescriptor* d = FindParameter(table_, key);
  const QString text = QStringLiteral("change %1").arg(d ? d->label : key);
  // Several fields differ when an earlier invalid edit is completed by this
  // one: then the step is not merged with the next edit of this field.
  int changed = 0;
  for (auto it = candidate.begin(); it != candidate.end(); ++it) changed += values_.value(it.key()) != it.value();
  undo_->push(new SetParametersCommand(this, values_, candidate, changed == 1 ? key : QString(), text));
}

ParameterValues ParameterPanel::ReadEditors() const {
  ParameterValues v;
  for (const ParameterDescriptor& d : table_) {
    QWidget* w = editors_.value(d.key);
    switch (d.type) {
      case ParameterDescriptor::Type::kReal:
        v.insert(d.key, static_cast<QDoubleSpinBox*>(w)->value());
        break;
      case ParameterDescriptor::Type::kInteger:
        v.insert(d.key, static_cast<QSpinBox*>(w)->value());
        break;
      case ParameterDescriptor::Type::kChoice:
        v.insert(d.key, static_cast<QComboBox*>(w)->currentData().toString());
        break;
    }
  }
  return v;
}

void ParameterPanel::WriteEditors(const ParameterValues& values) {
  for (const ParameterDescriptor& d : table_) {
    QWidget* w = editors_.value(d.key);
    const QSignalBlocker block(w);
    const QVariant v = values.value(d.key, d.DefaultValue());
    switch (d.type) {
      case ParameterDescriptor::Type::kReal:
        static_cast<QDoubleSpinBox*>(w)->setValue(v.toDouble());
        break;
      case ParameterDescriptor::Type::kInteger:
        static_cast<QSpinBox*>(w)->setValue(v.toInt());
        break;
      case ParameterDescriptor::Type::kChoice: {
        auto* combo = static_cast<QComboBox*>(w);
        combo->setCurrentIndex(std::max(0, combo->findData(v.toString())));
        break;
      }
    }
  }
}

void ParameterPanel::ShowRefused(const QString& key, const QString& text) {
  const ParameterDescriptor* d = FindParameter(table_, key);
  QLabel* label = errors_.value(key);
  if (!d || !label) return;
  label->setText(RefusedEntry(*d, text, values_.value(key)).message);
  label->setVisible(true);
}

void ParameterPanel::ShowErrors(const std::vector<ParameterError>& errors) {
  for (auto it = errors_.begin(); it != errors_.end(); ++it) {
    QString text;
    for (const ParameterError& e : errors) {
      if (e.key == it.key()) text += (text.isEmpty() ? QString() : QStringLiteral("\n")) + e.message;
    }
    it.value()->setText(text);
    it.value()->setVisible(!text.isEmpty());
    QWidget* editor = editors_.value(it.key());
    editor->setStyleSheet(text.isEmpty() ? QString() : QStringLiteral("border: 1px solid #c0392b;"));
  }
  QString other;
  for (const ParameterError& e : errors) {
    if (errors_.contains(e.key)) continue;
    other += (other.isEmpty() ? QString() : QStringLiteral("\n")) + e.key + QStringLiteral(": ") + e.message;
  }
  other_errors_->setText(other);
  other_errors_->setVisible(!other.isEmpty());
}

}  // namespace hull::ui
