#include "ui/parameters.h"

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

namespace {

ParameterDescriptor Real(QString key, QString group, QString label, double min, double max, double def, int decimals,
                         double step, QString unit, QString tooltip) {
  ParameterDescriptor d;
  d.key = std::move(key);
  d.group = std::move(group);
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

ParameterDescriptor Integer(QString key, QString group, QString label, int min, int max, int def, QString tooltip) {
  ParameterDescriptor d =
      Real(std::move(key), std::move(group), std::move(label), min, max, def, 0, 1, {}, std::move(tooltip));
  d.type = ParameterDescriptor::Type::kInteger;
  return d;
}

ParameterTable MakeDefaultTable() {
  const QString adjust = QStringLiteral("Bundle adjustment");
  const QString map = QStringLiteral("Mapping");
  ParameterTable t;
  t.push_back(Real(QStringLiteral("sigma0"), adjust, QStringLiteral("σ₀ (off surface)"), 0.01, 10.0, 1.0, 3, 0.05,
                   QStringLiteral("m"),
                   QStringLiteral("Standard deviation of the surface constraint for features off the model "
                                  "(λ = 0). The paper uses 1 m; the value matters little.")));
  t.push_back(Real(QStringLiteral("sigma1"), adjust, QStringLiteral("σ₁ (on surface)"), 0.001, 1.0, 0.02, 3, 0.005,
                   QStringLiteral("m"),
                   QStringLiteral("Standard deviation of the surface constraint for features on the model "
                                  "(λ = 1). With σ₀ = 1 m, σ₁ = 2 cm puts the decision boundary at about ±5 cm, "
                                  "the smallest object found; 1–5 cm suits ship hulls.")));
  ParameterDescriptor model;
  model.key = QStringLiteral("model");
  model.group = adjust;
  model.label = QStringLiteral("Surface model");
  model.type = ParameterDescriptor::Type::kChoice;
  model.choice_keys =
      QStringList{QStringLiteral("naive"), QStringLiteral("all_on_surface"), QStringLiteral("max_mixture")};
  model.choice_labels =
      QStringList{QStringLiteral("Naive (no surface constraint)"), QStringLiteral("All on the surface (Geva et al.)"),
                  QStringLiteral("Max-mixture (Ozog et al.)")};
  model.minimum = 0;
  model.maximum = 2;
  model.default_value = 2;
  model.tooltip = QStringLiteral(
      "How features relate to the CAD surface: ignored, all constrained to it, or each labelled on/off the "
      "surface by a max-mixture of the two Gaussians above.");
  t.push_back(model);
  t.push_back(Integer(QStringLiteral("max_iterations"), adjust, QStringLiteral("Solver iterations"), 1, 1000, 100,
                      QStringLiteral("Levenberg–Marquardt iterations at most before the solver stops.")));
  t.push_back(Real(QStringLiteral("tau"), map, QStringLiteral("τ (cluster threshold)"), 0.0, 1.0, 0.0, 3, 0.01,
                   QStringLiteral("m"),
                   QStringLiteral("Features whose |deviation| exceeds τ are clustered into shapes. 0 gives the "
                                  "most detail; raise it where false positives matter.")));
  t.push_back(Real(QStringLiteral("alpha"), map, QStringLiteral("α (alpha shapes)"), 0.005, 2.0, 0.12, 3, 0.01,
                   QStringLiteral("m"), QStringLiteral("Radius of the alpha shapes meshed over each cluster.")));
  t.push_back(Real(QStringLiteral("dbscan_eps"), map, QStringLiteral("DBSCAN ε"), 0.001, 2.0, 0.05, 3, 0.005,
                   QStringLiteral("m"),
                   QStringLiteral("DBSCAN's neighbourhood radius over the features' camera-frame positions.")));
  t.push_back(Integer(QStringLiteral("dbscan_min_points"), map, QStringLiteral("DBSCAN min. points"), 1, 1000, 3,
                      QStringLiteral("Points a cluster needs at least; fewer are noise (the paper uses 3).")));
  return t;
}

}  // namespace

const ParameterTable& DefaultParameterTable() {
  static const ParameterTable table = MakeDefaultTable();
  return table;
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
    if (x < d.minimum || x > d.maximum) {
      errors.push_back({d.key, QStringLiteral("%1 is outside [%2, %3]%4")
                                   .arg(x)
                                   .arg(d.minimum)
                                   .arg(d.maximum)
                                   .arg(d.unit.isEmpty() ? QString() : QStringLiteral(" ") + d.unit)});
    }
  }
  return errors;
}

std::vector<ParameterError> CheckDefaultParameters(const ParameterValues& values) {
  std::vector<ParameterError> errors = CheckAgainstTable(DefaultParameterTable(), values);
  if (!errors.empty()) return errors;
  const double sigma0 = values.value(QStringLiteral("sigma0")).toDouble();
  const double sigma1 = values.value(QStringLiteral("sigma1")).toDouble();
  if (!(sigma1 < sigma0)) {
    errors.push_back({QStringLiteral("sigma1"),
                      QStringLiteral("σ₁ must be smaller than σ₀ (%1 m): on-surface features are the tightly "
                                     "constrained ones")
                          .arg(sigma0)});
  }
  return errors;
}

}  // namespace hull::ui
