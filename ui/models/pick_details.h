// What the info panel shows about a picked landmark, keyframe or object:
// plain text rows built from the survey (no VTK, no widgets). Points of
// surfaces: surface_pick.h.
#pragma once

#include <QPair>
#include <QString>
#include <QVector>
#include <optional>

#include "geometry/pose.h"
#include "survey/survey.h"
#include "ui/session/inspection_results.h"
#include "ui/session/survey_overlays.h"

namespace hull::ui {

// kSurface: a point of a surface layer (remeshed model, change map, CAD;
// ui/models/surface_pick.h).
enum class PickKind { kNone, kLandmark, kKeyframe, kObject, kDetectedObject, kSurface };

struct PickInfo {
  PickKind kind = PickKind::kNone;
  QString id;  // landmark or keyframe id, or object id
  QString title;
  QVector<QPair<QString, QString>> rows;    // label, value
  std::optional<Eigen::Vector3d> position;  // where it is in g (set by the scene's pick)
  // The values come from the results on screen (an adjusted landmark or
  // keyframe, a detected object, a point of the remeshed model or of the
  // change map), not from the survey or the CAD alone: they go when the
  // results change (RefreshPick).
  bool from_results = false;
};

// `index` is the landmark's position in overlays.landmarks.
PickInfo DescribeLandmark(const SurveyOverlays& overlays, int index);
// `index` is the landmark's position in adjusted.landmarks: id, label,
// estimated deviation, observations and, with truth, the true deviation and
// object.
PickInfo DescribeAdjustedLandmark(const AdjustedOverlays& adjusted, int index);
// `index` is the keyframe's position in adjusted.keyframes: as
// DescribeKeyframe, with the adjusted position and how far it moved.
PickInfo DescribeAdjustedKeyframe(const SurveyBundle& bundle, const SurveyOverlays& overlays,
                                  const AdjustedOverlays& adjusted, int index);
// `nav_index` is the keyframe's row of nav.csv.
PickInfo DescribeKeyframe(const SurveyBundle& bundle, const SurveyOverlays& overlays, int nav_index);
// `index` is the object's position in mapping.result->objects: where it is
// on the hull, its footprint, heights, features and views.
PickInfo DescribeDetectedObject(const MappingRun& mapping, int index);
// The position of the detected object `id` in mapping.result->objects; -1
// when that run did not find it.
int FindDetectedObject(const MappingRun& mapping, const QString& id);
// What Details shows for `shown` once the results on screen changed
// (mapping: the new mapping, nullptr for none), so that it never shows
// values of an earlier run: a detected object again by its id (ids stay with
// the objects across runs: mapping/object_identity.h), or a line saying the
// run did not find it; any other pick whose values came from the results is
// dropped (kNone: pick again); picks of the survey or the CAD stay.
PickInfo RefreshPick(const PickInfo& shown, const MappingRun* mapping);
// The distance tool (issue 25.1): `info` (a pick with a position) with the
// straight distance from the previous pick `from` (g) and its components in
// g appended; unchanged without a position.
PickInfo WithDistanceFrom(const PickInfo& info, const Eigen::Vector3d& from);
// `index` is the object's position in overlays.objects; x_gM places it in g.
PickInfo DescribeObject(const SurveyBundle& bundle, const SurveyOverlays& overlays, int index, const Pose& x_gM);

}  // namespace hull::ui
