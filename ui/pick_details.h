// What the info panel shows about a picked landmark, keyframe or object:
// plain text rows built from the survey (no VTK, no widgets).
#pragma once

#include <QPair>
#include <QString>
#include <QVector>

#include "geometry/pose.h"
#include "survey/survey.h"
#include "ui/survey_overlays.h"

namespace hull::ui {

enum class PickKind { kNone, kLandmark, kKeyframe, kObject };

struct PickInfo {
  PickKind kind = PickKind::kNone;
  QString id;  // landmark or keyframe id, or object id
  QString title;
  QVector<QPair<QString, QString>> rows;  // label, value
};

// `index` is the landmark's position in overlays.landmarks.
PickInfo DescribeLandmark(const SurveyOverlays& overlays, int index);
// `nav_index` is the keyframe's row of nav.csv.
PickInfo DescribeKeyframe(const SurveyBundle& bundle, const SurveyOverlays& overlays, int nav_index);
// `index` is the object's position in overlays.objects; x_gM places it in g.
PickInfo DescribeObject(const SurveyBundle& bundle, const SurveyOverlays& overlays, int index, const Pose& x_gM);

}  // namespace hull::ui
