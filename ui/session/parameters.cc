#include "ui/session/parameters.h"

#include <QLocale>
#include <cmath>

namespace hull::ui {

QVariant ParameterDescriptor::DefaultValue() const {
  switch (type) {
    case Type::kReal:
      return default_value;
    case Type::kInteger:
      return static_cast<int>(default_value);
    case Type::kChoice:
      return choice_keys.value(static_cast<int>(default_value));
  }
  return {};
}

ParameterValues DefaultValues(const ParameterTable& table) {
  ParameterValues v;
  for (const ParameterDescriptor& d : table) v.insert(d.key, d.DefaultValue());
  return v;
}

const ParameterDescriptor* FindParameter(const ParameterTable& table, const QString& key) {
  for (const ParameterDescriptor& d : table) {
    if (d.key == key) return &d;
  }
  return nullptr;
}

bool CoerceValue(const ParameterDescriptor& d, const QVariant& in, QVariant* out) {
  switch (d.type) {
    case ParameterDescriptor::Type::kReal: {
      bool ok = false;
      const double x = in.toDouble(&ok);
      if (!ok || !std::isfinite(x) || in.type() == QVariant::String || in.type() == QVariant::Bool) return false;
      *out = x;
      return true;
    }
    case ParameterDescriptor::Type::kInteger: {
      bool ok = false;
      const double x = in.toDouble(&ok);
      if (!ok || in.type() == QVariant::String || in.type() == QVariant::Bool || x != std::floor(x) ||
          std::abs(x) > 1e9) {
        return false;
      }
      *out = static_cast<int>(x);
      return true;
    }
    case ParameterDescriptor::Type::kChoice:
      if (in.type() != QVariant::String || !d.choice_keys.contains(in.toString())) return false;
      *out = in.toString();
      return true;
  }
  return false;
}

namespace {

QString OutsideRange(const ParameterDescriptor& d, double x) {
  return QStringLiteral("%1 is outside [%2, %3]%4")
      .arg(x)
      .arg(d.minimum)
      .arg(d.maximum)
      .arg(d.unit.isEmpty() ? QString() : QStringLiteral(" ") + d.unit);
}

}  // namespace

std::vector<ParameterError> CheckAgainstTable(const ParameterTable& table, const ParameterValues& values) {
  std::vector<ParameterError> errors;
  for (const ParameterDescriptor& d : table) {
    if (!values.contains(d.key)) {
      errors.push_back({d.key, QStringLiteral("missing")});
      continue;
    }
    QVariant v;
    if (!CoerceValue(d, values.value(d.key), &v)) {
      errors.push_back(
          {d.key, d.type == ParameterDescriptor::Type::kChoice
                      ? QStringLiteral("expected one of: %1").arg(d.choice_keys.join(QStringLiteral(", ")))
                      : (d.type == ParameterDescriptor::Type::kInteger ? QStringLiteral("expected a whole number")
                                                                       : QStringLiteral("expected a number"))});
      continue;
    }
    if (d.type == ParameterDescriptor::Type::kChoice) continue;
    const double x = v.toDouble();
    if (x < d.minimum || x > d.maximum) errors.push_back({d.key, OutsideRange(d, x)});
  }
  return errors;
}

ParameterError RefusedEntry(const ParameterDescriptor& d, const QString& text, const QVariant& in_force) {
  QString number = text.trimmed();
  if (!d.unit.isEmpty() && number.endsWith(d.unit)) number = number.left(number.size() - d.unit.size()).trimmed();
  bool ok = false;
  const double x = QLocale().toDouble(number, &ok);
  const QString kept =
      QStringLiteral("%1 stays %2%3").arg(d.label, in_force.toString(), d.unit.isEmpty() ? QString() : " " + d.unit);
  if (!ok) {
    const QString expected =
        d.type == ParameterDescriptor::Type::kInteger ? QStringLiteral("a whole number") : QStringLiteral("a number");
    return {d.key, QStringLiteral("“%1” is not %2; %3").arg(text.trimmed(), expected, kept)};
  }
  if (x < d.minimum || x > d.maximum) return {d.key, OutsideRange(d, x) + QStringLiteral("; ") + kept};
  return {d.key, QStringLiteral("“%1” was not taken; %2").arg(text.trimmed(), kept)};
}

namespace table {

ParameterDescriptor Real(QString key, QString group, ParameterDescriptor::Stage stage, QString label, double min,
                         double max, double def, int decimals, double step, QString unit, QString tooltip) {
  ParameterDescriptor d;
  d.key = std::move(key);
  d.group = std::move(group);
  d.stage = stage;
  d.label = std::move(label);
  d.type = ParameterDescriptor::Type::kReal;
  d.minimum = min;
  d.maximum = max;
  d.default_value = def;
  d.decimals = decimals;
  d.step = step;
  d.unit = std::move(unit);
  d.tooltip = std::move(tooltip);
  return d;
}

ParameterDescriptor Integer(QString key, QString group, ParameterDescriptor::Stage stage, QString label, int min,
                            int max, int def, QString tooltip) {
  ParameterDescriptor d =
      Real(std::move(key), std::move(group), stage, std::move(label), min, max, def, 0, 1, {}, std::move(tooltip));
  d.type = ParameterDescriptor::Type::kInteger;
  return d;
}

ParameterDescriptor Choice(QString key, QString group, ParameterDescriptor::Stage stage, QString label,
                           QStringList keys, QStringList labels, int def, QString tooltip) {
  ParameterDescriptor d;
  d.key = std::move(key);
  d.group = std::move(group);
  d.stage = stage;
  d.label = std::move(label);
  d.type = ParameterDescriptor::Type::kChoice;
  d.choice_keys = std::move(keys);
  d.choice_labels = std::move(labels);
  d.minimum = 0;
  d.maximum = d.choice_keys.size() - 1;
  d.default_value = def;
  d.tooltip = std::move(tooltip);
  return d;
}

}  // namespace table

}  // namespace hull::ui
