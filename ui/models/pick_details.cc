#include "ui/models/pick_details.h"

#include <QStringList>
#include <cmath>

namespace hull::ui {

namespace {

QString Vec3(const Eigen::Vector3d& v, const char* unit = "m") {
  return QStringLiteral("(%1, %2, %3) %4")
      .arg(v.x(), 0, 'f', 3)
      .arg(v.y(), 0, 'f', 3)
      .arg(v.z(), 0, 'f', 3)
      .arg(QLatin1String(unit));
}

QString Degrees(double rad) { return QStringLiteral("%1°").arg(rad * 180.0 / M_PI, 0, 'f', 2); }

QString Metres(double m) { return QStringLiteral("%1 m").arg(m, 0, 'f', 3); }

}  // namespace

PickInfo DescribeLandmark(const SurveyOverlays& overlays, int index) {
  PickInfo info;
  if (index < 0 || index >= static_cast<int>(overlays.landmarks.size())) return info;
  const LandmarkMarker& l = overlays.landmarks[index];
  info.kind = PickKind::kLandmark;
  info.id = QString::number(l.id);
  info.title = QStringLiteral("Landmark %1").arg(l.id);
  info.rows.append({QStringLiteral("Position (g)"), Vec3(l.position)});
  info.rows.append({QStringLiteral("Source"), QString::fromLatin1(LandmarkSourceName(overlays.landmark_source))});
  info.rows.append({QStringLiteral("Observations"), QString::number(l.observations)});
  if (l.has_truth) {
    info.rows.append({QStringLiteral("True deviation"), QStringLiteral("%1 mm").arg(l.deviation * 1000.0, 0, 'f', 1)});
    info.rows.append({QStringLiteral("Label"),
                      l.foreign() ? QStringLiteral("foreign (object %1)").arg(QString::fromStdString(l.object))
                                  : QStringLiteral("on the hull")});
  }
  return info;
}

PickInfo DescribeAdjustedLandmark(const AdjustedOverlays& adjusted, int index) {
  PickInfo info;
  if (index < 0 || index >= static_cast<int>(adjusted.landmarks.size())) return info;
  const AdjustedLandmark& l = adjusted.landmarks[index];
  info.kind = PickKind::kLandmark;
  info.from_results = true;
  info.id = QString::number(l.id);
  info.title = QStringLiteral("Landmark %1 (adjusted)").arg(l.id);
  info.rows.append({QStringLiteral("Position (g)"), Vec3(l.position)});
  info.rows.append({QStringLiteral("Label"), l.label == 1 ? QStringLiteral("on the hull (λ = 1)")
                                                          : QStringLiteral("foreign structure (λ = 0)")});
  info.rows.append({QStringLiteral("Deviation"), QStringLiteral("%1 mm").arg(l.deviation * 1000.0, 0, 'f', 1)});
  info.rows.append({QStringLiteral("Observations"), QString::number(l.observations)});
  if (l.has_truth) {
    info.rows.append(
        {QStringLiteral("True deviation"), QStringLiteral("%1 mm").arg(l.true_deviation * 1000.0, 0, 'f', 1)});
    info.rows.append({QStringLiteral("Truth"),
                      l.object.empty() ? QStringLiteral("on the hull")
                                       : QStringLiteral("on object %1").arg(QString::fromStdString(l.object))});
  }
  return info;
}

PickInfo DescribeAdjustedKeyframe(const SurveyBundle& bundle, const SurveyOverlays& overlays,
                                  const AdjustedOverlays& adjusted, int index) {
  if (index < 0 || index >= static_cast<int>(adjusted.keyframes.size())) return {};
  const auto nav = bundle.KeyframeIndex();
  auto it = nav.find(adjusted.keyframes[index]);
  if (it == nav.end()) return {};
  PickInfo info = DescribeKeyframe(bundle, overlays, it->second);
  info.from_results = true;
  const Eigen::Vector3d& p = adjusted.trajectory[index];
  info.rows.insert(2, {QStringLiteral("Position (adjusted)"), Vec3(p)});
  info.rows.insert(
      3, {QStringLiteral("Moved by the adjustment"), Metres((p - bundle.nav[it->second].x_gv.head<3>()).norm())});
  return info;
}

PickInfo DescribeKeyframe(const SurveyBundle& bundle, const SurveyOverlays& overlays, int nav_index) {
  PickInfo info;
  if (nav_index < 0 || nav_index >= static_cast<int>(bundle.nav.size())) return info;
  const NavRecord& nav = bundle.nav[nav_index];
  info.kind = PickKind::kKeyframe;
  info.id = QString::number(nav.keyframe);
  info.title = QStringLiteral("Keyframe %1").arg(nav.keyframe);
  info.rows.append({QStringLiteral("Time"), QStringLiteral("%1 s").arg(nav.t, 0, 'f', 2)});
  info.rows.append({QStringLiteral("Position (initial)"), Vec3(nav.x_gv.head<3>())});
  info.rows.append({QStringLiteral("Roll, pitch, yaw"),
                    Degrees(nav.x_gv[3]) + ", " + Degrees(nav.x_gv[4]) + ", " + Degrees(nav.x_gv[5])});
  info.rows.append({QStringLiteral("Servo angle"), Degrees(nav.servo)});
  info.rows.append({QStringLiteral("Depth (measured)"), Metres(nav.depth)});
  for (std::size_t i = 0; i < overlays.true_nav_index.size(); ++i) {
    if (overlays.true_nav_index[i] != nav_index) continue;
    const Eigen::Vector3d& truth = overlays.true_trajectory[i];
    info.rows.append({QStringLiteral("Position (truth)"), Vec3(truth)});
    info.rows.append({QStringLiteral("Navigation error"), Metres((truth - nav.x_gv.head<3>()).norm())});
    break;
  }
  for (const DvlRecord& d : bundle.dvl) {
    if (d.keyframe != nav.keyframe) continue;
    QStringList ranges;
    for (double r : d.range) ranges << (DvlRecord::HasReturn(r) ? QString::number(r, 'f', 3) : QStringLiteral("—"));
    info.rows.append({QStringLiteral("DVL ranges (m)"), ranges.join(QStringLiteral(", "))});
    break;
  }
  int features = 0;
  for (const FeatureObservation& f : bundle.features) features += f.keyframe == nav.keyframe;
  info.rows.append({QStringLiteral("Features observed"), QString::number(features)});
  return info;
}

PickInfo WithDistanceFrom(const PickInfo& info, const Eigen::Vector3d& from) {
  if (!info.position) return info;
  PickInfo out = info;
  const Eigen::Vector3d d = *info.position - from;
  out.rows.append({QStringLiteral("Distance from the previous pick"), Metres(d.norm())});
  out.rows.append({QStringLiteral("  along x, y, z (g)"),
                   QStringLiteral("%1, %2, %3 m").arg(d.x(), 0, 'f', 3).arg(d.y(), 0, 'f', 3).arg(d.z(), 0, 'f', 3)});
  return out;
}

int FindDetectedObject(const MappingRun& mapping, const QString& id) {
  const auto& objects = mapping.result->objects;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (QString::fromStdString(objects[i].id) == id) return static_cast<int>(i);
  }
  return -1;
}

PickInfo RefreshPick(const PickInfo& shown, const MappingRun* mapping) {
  if (!shown.from_results) return shown;
  if (shown.kind != PickKind::kDetectedObject) return {};
  const int index = mapping ? FindDetectedObject(*mapping, shown.id) : -1;
  if (index >= 0) return DescribeDetectedObject(*mapping, index);
  PickInfo gone;
  gone.kind = PickKind::kDetectedObject;
  gone.from_results = true;
  gone.id = shown.id;
  gone.title = QStringLiteral("Detected object %1").arg(shown.id);
  gone.rows.append({QStringLiteral("Status"), mapping ? QStringLiteral("not detected with the parameters on screen")
                                                      : QStringLiteral("no mapping on screen")});
  gone.position = shown.position;
  return gone;
}

PickInfo DescribeDetectedObject(const MappingRun& mapping, int index) {
  PickInfo info;
  const auto& objects = mapping.result->objects;
  if (index < 0 || index >= static_cast<int>(objects.size())) return info;
  const DetectedObject& o = objects[index];
  info.kind = PickKind::kDetectedObject;
  info.from_results = true;
  info.id = QString::fromStdString(o.id);
  info.title = QStringLiteral("Detected object %1").arg(info.id);
  info.position = mapping.x_gM() * o.centroid_m;
  info.rows.append({QStringLiteral("Where"), QStringLiteral("%1 m from the bow, station %2, %3")
                                                 .arg(o.distance_from_bow, 0, 'f', 2)
                                                 .arg(o.station)
                                                 .arg(QString::fromLatin1(HullSideName(o.side)))});
  info.rows.append({QStringLiteral("Footprint area"), QStringLiteral("%1 m²").arg(o.area, 0, 'f', 3)});
  info.rows.append({QStringLiteral("Mean height"), QStringLiteral("%1 mm").arg(o.mean_height * 1000.0, 0, 'f', 1)});
  info.rows.append({QStringLiteral("Max. height"), QStringLiteral("%1 mm").arg(o.max_height * 1000.0, 0, 'f', 1)});
  info.rows.append({QStringLiteral("Features"), QString::number(o.num_features)});
  info.rows.append({QStringLiteral("Views"), QString::number(o.num_views)});
  QStringList keyframes;
  for (std::size_t i = 0; i < o.keyframes.size() && i < 8; ++i) keyframes << QString::number(o.keyframes[i]);
  if (o.keyframes.size() > 8) keyframes << QStringLiteral("…");
  info.rows.append({QStringLiteral("Keyframes"), keyframes.join(QStringLiteral(", "))});
  info.rows.append({QStringLiteral("Centroid (model M)"), Vec3(o.centroid_m)});
  info.rows.append({QStringLiteral("Centroid (g)"), Vec3(mapping.x_gM() * o.centroid_m)});
  return info;
}

PickInfo DescribeObject(const SurveyBundle& bundle, const SurveyOverlays& overlays, int index, const Pose& x_gM) {
  PickInfo info;
  if (!bundle.truth || index < 0 || index >= static_cast<int>(bundle.truth->objects.size())) return info;
  const TrueObject& o = bundle.truth->objects[index];
  info.kind = PickKind::kObject;
  info.id = QString::fromStdString(o.id);
  info.title = QStringLiteral("Object %1").arg(info.id);
  info.rows.append({QStringLiteral("Kind"), QString::fromLatin1(ObjectKindName(o.kind))});
  if (o.kind == ObjectKind::kBox) {
    info.rows.append({QStringLiteral("Size"), Vec3(o.size)});
  } else {
    info.rows.append({QStringLiteral("Radius"), Metres(o.radius)});
    info.rows.append({QStringLiteral("Height"), Metres(o.height)});
  }
  info.rows.append({QStringLiteral("Centre (model M)"), Vec3(o.center)});
  info.rows.append({QStringLiteral("Centre (g, as placed)"), Vec3(x_gM * o.center)});
  int landmarks = 0;
  for (const LandmarkMarker& l : overlays.landmarks) landmarks += l.object == o.id;
  info.rows.append({QStringLiteral("Landmarks on it"), QString::number(landmarks)});
  return info;
}

}  // namespace hull::ui
