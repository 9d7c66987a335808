#include "ui/session/sonar_parameters.h"

#include <QStringList>
#include <map>
#include <string>

#include "base/error.h"

namespace hull::ui {
namespace {

using Stage = ParameterDescriptor::Stage;
using table::Choice;
using table::Integer;
using table::Real;

const QString kSonar = QStringLiteral("Sonar");

// The core's field names (OptionError::field) and the rows that set them.
const std::map<std::string, QString>& RowOfField() {
  static const std::map<std::string, QString> rows = {
      {"hypotheses", QStringLiteral("sonar_hypotheses")},
      {"collapse_probability", QStringLiteral("sonar_collapse")},
      {"max_delay_steps", QStringLiteral("sonar_max_delay")},
      {"paper_elevation_sigma_fraction", QStringLiteral("sonar_paper_sigma")},
      {"confirm_views", QStringLiteral("sonar_confirm_views")},
      {"gate_probability", QStringLiteral("sonar_gate")},
      {"drop_misses", QStringLiteral("sonar_drop_misses")},
      {"min_contrast", QStringLiteral("sonar_min_contrast")},
      {"max_iterations", QStringLiteral("sonar_smoother_iterations")}};
  return rows;
}

}  // namespace

void AddSonarFields(ParameterTable& t) {
  const SonarPipelineOptions o;
  const SonarEkfOptions& e = o.images.run.ekf;
  const Stage s = Stage::kNone;  // the hull inspection does not depend on them
  t.push_back(Integer(QStringLiteral("sonar_hypotheses"), kSonar, s, QStringLiteral("Elevation hypotheses"), 3, 1000,
                      e.hypotheses,
                      QStringLiteral("Hypotheses tiling the fan's elevation when a feature is first seen (the "
                                     "hypotheses initialisation).")));
  t.push_back(Real(QStringLiteral("sonar_collapse"), kSonar, s, QStringLiteral("Collapse probability"), 0.51, 0.9999,
                   e.collapse_probability, 4, 0.01, {},
                   QStringLiteral("A feature enters the state once its best hypothesis and neighbours hold this "
                                  "share of the weight.")));
  t.push_back(Integer(QStringLiteral("sonar_max_delay"), kSonar, s, QStringLiteral("Max. delay"), 1, 1000,
                      e.max_delay_steps,
                      QStringLiteral("Steps after its first view when a feature enters with the whole fan as its "
                                     "elevation prior.")));
  t.push_back(Real(QStringLiteral("sonar_paper_sigma"), kSonar, s, QStringLiteral("Paper: elevation σ"), 0.01, 1.0,
                   e.paper_elevation_sigma_fraction, 3, 0.05, QStringLiteral("of the fan"),
                   QStringLiteral("Mai et al.'s initialisation: the elevation's σ as a fraction of the fan.")));
  t.push_back(Integer(QStringLiteral("sonar_confirm_views"), kSonar, s, QStringLiteral("Views to confirm"), 1, 1000,
                      e.confirm_views,
                      QStringLiteral("From the images: views a tentative feature needs before it enters the state "
                                     "(one-off false detections never do).")));
  t.push_back(Real(QStringLiteral("sonar_gate"), kSonar, s, QStringLiteral("Association gate"), 0.5, 0.99999,
                   o.images.tracker.gate_probability, 5, 0.005, {},
                   QStringLiteral("From the images: the χ² gate probability of a detection's pairing.")));
  t.push_back(Integer(QStringLiteral("sonar_drop_misses"), kSonar, s, QStringLiteral("Drop after misses"), 1, 1000,
                      o.images.tracker.drop_misses,
                      QStringLiteral("From the images: a feature predicted in view but missed this many times is "
                                     "dropped.")));
  t.push_back(Real(QStringLiteral("sonar_min_contrast"), kSonar, s, QStringLiteral("Detector contrast"), 1, 255,
                   o.images.detector.min_contrast, 0, 5, QStringLiteral("levels"),
                   QStringLiteral("From the images: grey levels a point return must stand above the background.")));
  t.push_back(Integer(QStringLiteral("sonar_smoother_iterations"), kSonar, s, QStringLiteral("Smoother iterations"), 1,
                      1000, o.smoother_options.max_iterations,
                      QStringLiteral("The batch smoother's Levenberg–Marquardt iterations at most.")));
  t.push_back(Choice(QStringLiteral("sonar_smoother_covariances"), kSonar, s, QStringLiteral("Smoother covariances"),
                     {QStringLiteral("yes"), QStringLiteral("no")}, {QStringLiteral("Computed"), QStringLiteral("Off")},
                     o.smoother_options.covariances ? 0 : 1,
                     QStringLiteral("Every smoothed pose's and feature's covariance (ceres::Covariance).")));
}

SonarPipelineOptions SonarTuningFrom(const ParameterValues& v) {
  SonarPipelineOptions o;
  const auto real = [&](const char* key, double& field) { field = v.value(QLatin1String(key), field).toDouble(); };
  const auto integer = [&](const char* key, int& field) { field = v.value(QLatin1String(key), field).toInt(); };
  for (SonarEkfOptions* e : {&o.run.ekf, &o.images.run.ekf}) {
    integer("sonar_hypotheses", e->hypotheses);
    real("sonar_collapse", e->collapse_probability);
    integer("sonar_max_delay", e->max_delay_steps);
    real("sonar_paper_sigma", e->paper_elevation_sigma_fraction);
  }
  integer("sonar_confirm_views", o.images.run.ekf.confirm_views);  // given correspondences confirm at once
  real("sonar_gate", o.images.tracker.gate_probability);
  integer("sonar_drop_misses", o.images.tracker.drop_misses);
  real("sonar_min_contrast", o.images.detector.min_contrast);
  integer("sonar_smoother_iterations", o.smoother_options.max_iterations);
  o.smoother_options.covariances =
      v.value(QStringLiteral("sonar_smoother_covariances"), QStringLiteral("yes")).toString() != QLatin1String("no");
  return o;
}

QString SonarKey(const ParameterValues& values) {
  QStringList parts;
  for (auto it = values.begin(); it != values.end(); ++it) {  // QVariantMap: in key order
    if (it.key().startsWith(QLatin1String("sonar_"))) parts << it.key() + QLatin1Char('=') + it.value().toString();
  }
  return parts.join(QLatin1Char(';'));
}

std::vector<ParameterError> CheckSonarParameters(const ParameterValues& values) {
  SonarPipelineOptions o = SonarTuningFrom(values);
  o.smoother = true;  // its options checked too
  try {
    o.Check();
  } catch (const OptionError& e) {
    const auto it = RowOfField().find(e.field());
    return {
        {it == RowOfField().end() ? QStringLiteral("sonar_hypotheses") : it->second, QString::fromStdString(e.what())}};
  }
  return {};
}

}  // namespace hull::ui
