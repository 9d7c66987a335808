#include "images_survey.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <filesystem>

#include "gui_test_support.h"
#include "simulate/survey_simulator.h"

namespace hull::ui::testing {

QString ImagesSurveyDir() {
  static const QString dir = [] {
    const QString d = OutputDir() + QStringLiteral("/images_survey_%1").arg(QCoreApplication::applicationPid());
    QDir(d).removeRecursively();
    SurveySimulationOptions o = SurveyPreset("demo");
    o.camera_scale = 0.5;
    o.plan.start = 84.0;
    o.plan.end = 87.0;
    o.plan.half_width = 0.4;
    o.images = true;
    NullProgress progress;
    const SimulatedSurvey s = SimulateSurvey(o, progress);
    WriteSimulatedSurvey(s, QFile::encodeName(d).toStdString());
    std::filesystem::remove(QFile::encodeName(d + QStringLiteral("/features.csv")).toStdString());
    return d;
  }();
  return dir;
}

}  // namespace hull::ui::testing
