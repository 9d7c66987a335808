#include "ui/models/surface_pick.h"

#include <cmath>
#include <limits>

#include "mapping/hull_zones.h"

namespace hull::ui {

namespace {

QString Millimetres(double m, bool sign) {
  return QStringLiteral("%1 mm").arg(sign ? QString::asprintf("%+.1f", m * 1000.0)
                                          : QString::asprintf("%.1f", m * 1000.0));
}

QString Position(const Eigen::Vector3d& v) { return QString::asprintf("(%.3f, %.3f, %.3f) m", v.x(), v.y(), v.z()); }

double ScalarAt(const TriangleMesh& m, const char* name, int vertex) {
  const std::vector<double>* s = m.FindScalar(name);
  return s && vertex >= 0 && static_cast<std::size_t>(vertex) < s->size() ? (*s)[static_cast<std::size_t>(vertex)]
                                                                          : std::numeric_limits<double>::quiet_NaN();
}

// "12.41 m from the bow, station 7, bottom" on the mapping's hull frame.
void AddHullPosition(const HullFrame& hull, const Eigen::Vector3d& p_m, const Eigen::Vector3d& normal_m,
                     QVector<QPair<QString, QString>>& rows) {
  rows.append({QStringLiteral("Where"), QStringLiteral("%1 m from the bow, station %2, %3")
                                            .arg(hull.DistanceFromBow(p_m), 0, 'f', 2)
                                            .arg(hull.Station(p_m))
                                            .arg(QString::fromLatin1(HullSideName(hull.Side(normal_m))))});
}

// The detected object the vertex belongs to, else the nearest one (by its
// centroid) and how far it is.
void AddNearestObject(const MappingResult& r, int vertex, const Eigen::Vector3d& p_m,
                      QVector<QPair<QString, QString>>& rows) {
  const DetectedObject* nearest = nullptr;
  double best = std::numeric_limits<double>::infinity();
  for (const DetectedObject& o : r.objects) {
    for (const int v : o.vertices) {
      if (v == vertex) {
        rows.append({QStringLiteral("Object"), QStringLiteral("%1 (on it)").arg(QString::fromStdString(o.id))});
        return;
      }
    }
    const double d = (o.centroid_m - p_m).norm();
    if (d < best) {
      best = d;
      nearest = &o;
    }
  }
  rows.append({QStringLiteral("Nearest object"),
               nearest ? QStringLiteral("%1, %2 m away").arg(QString::fromStdString(nearest->id)).arg(best, 0, 'f', 2)
                       : QStringLiteral("none detected")});
}

Eigen::Vector3d VertexNormal(const TriangleMesh& m, int vertex) {
  return static_cast<std::size_t>(vertex) < m.vertex_normals.size() ? m.vertex_normals[static_cast<std::size_t>(vertex)]
                                                                    : Eigen::Vector3d::Zero();
}

}  // namespace

int NearestCorner(const TriangleMesh& mesh, int face, const Eigen::Vector3d& p) {
  if (face < 0 || static_cast<std::size_t>(face) >= mesh.num_faces()) return -1;
  const Face& f = mesh.faces[static_cast<std::size_t>(face)];
  int best = f[0];
  for (int k = 1; k < 3; ++k) {
    if ((mesh.vertices[static_cast<std::size_t>(f[k])] - p).squaredNorm() <
        (mesh.vertices[static_cast<std::size_t>(best)] - p).squaredNorm()) {
      best = f[k];
    }
  }
  return best;
}

PickInfo DescribeModelPoint(const MappingRun& mapping, int vertex, double significance_k) {
  PickInfo info;
  const TriangleMesh& m = mapping.result->model;
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= m.num_vertices()) return info;
  const Eigen::Vector3d& p = m.vertices[static_cast<std::size_t>(vertex)];
  info.kind = PickKind::kSurface;
  info.from_results = true;
  info.id = QStringLiteral("model vertex %1").arg(vertex);
  info.title = QStringLiteral("Remeshed model, vertex %1").arg(vertex);
  const double h = ScalarAt(m, "deviation", vertex), sigma = ScalarAt(m, "sigma", vertex);
  info.rows.append({QStringLiteral("Deviation"), Millimetres(h, true)});
  if (std::isfinite(sigma)) {
    info.rows.append({QStringLiteral("σ"), Millimetres(sigma, false)});
    info.rows.append({QStringLiteral("Significant"),
                      std::abs(h) > significance_k * sigma
                          ? QStringLiteral("yes: |h| > %1 σ").arg(QString::number(significance_k, 'g', 3))
                          : QStringLiteral("no: |h| ≤ %1 σ").arg(QString::number(significance_k, 'g', 3))});
  }
  const double fusions = ScalarAt(m, "fusions", vertex);
  if (std::isfinite(fusions)) info.rows.append({QStringLiteral("Fused views"), QString::number(fusions, 'f', 0)});
  AddHullPosition(mapping.result->hull, p, VertexNormal(m, vertex), info.rows);
  AddNearestObject(*mapping.result, vertex, p, info.rows);
  info.rows.append({QStringLiteral("Position (model M)"), Position(p)});
  info.rows.append({QStringLiteral("Position (g)"), Position(mapping.x_gM() * p)});
  info.position = mapping.x_gM() * p;
  return info;
}

PickInfo DescribeChangePoint(const SurveyComparisonRun& comparison, int vertex, const Pose& x_gM) {
  PickInfo info;
  const TriangleMesh& m = comparison.comparison.model;
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= m.num_vertices()) return info;
  const Eigen::Vector3d& p = m.vertices[static_cast<std::size_t>(vertex)];
  info.kind = PickKind::kSurface;
  info.from_results = true;
  info.id = QStringLiteral("change vertex %1").arg(vertex);
  info.title = QStringLiteral("Change between surveys, vertex %1").arg(vertex);
  info.rows.append({QStringLiteral("Change in height"), Millimetres(ScalarAt(m, "change", vertex), true)});
  const double sigma = ScalarAt(m, "change_sigma", vertex);
  if (std::isfinite(sigma)) info.rows.append({QStringLiteral("σ of the change"), Millimetres(sigma, false)});
  const double significant = ScalarAt(m, "change_significant", vertex);
  if (std::isfinite(significant)) {
    info.rows.append({QStringLiteral("Significant"), significant > 0 ? QStringLiteral("yes") : QStringLiteral("no")});
  }
  info.rows.append({QStringLiteral("Deviation (survey B)"), Millimetres(ScalarAt(m, "deviation", vertex), true)});
  info.rows.append({QStringLiteral("Position (model M)"), Position(p)});
  info.rows.append({QStringLiteral("Position (g)"), Position(x_gM * p)});
  info.position = x_gM * p;
  return info;
}

PickInfo DescribeCadPoint(const TriangleMesh& cad, int face, int vertex, const Pose& x_gM, const MappingRun* mapping) {
  PickInfo info;
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= cad.num_vertices()) return info;
  if (face < 0 || static_cast<std::size_t>(face) >= cad.num_faces()) return info;
  const Eigen::Vector3d& p = cad.vertices[static_cast<std::size_t>(vertex)];
  info.kind = PickKind::kSurface;
  info.id = QStringLiteral("CAD vertex %1").arg(vertex);
  info.title = QStringLiteral("CAD surface, vertex %1").arg(vertex);
  info.rows.append({QStringLiteral("Deviation"), QStringLiteral("0 mm (the CAD itself)")});
  if (mapping) {
    const Face& f = cad.faces[static_cast<std::size_t>(face)];
    const Eigen::Vector3d& a = cad.vertices[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d normal =
        (cad.vertices[static_cast<std::size_t>(f[1])] - a).cross(cad.vertices[static_cast<std::size_t>(f[2])] - a);
    AddHullPosition(mapping->result->hull, p, normal.normalized(), info.rows);
  }
  info.rows.append({QStringLiteral("Position (model M)"), Position(p)});
  info.rows.append({QStringLiteral("Position (g)"), Position(x_gM * p)});
  info.position = x_gM * p;
  return info;
}

}  // namespace hull::ui
