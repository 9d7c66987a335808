#include "ui/models/objects_table_model.h"

#include <cmath>

#include <QColor>
#include <QStringList>

#include "mapping/object_identity.h"

namespace hull::ui {

namespace {

enum ObjectColumn { kId, kFromBow, kStation, kSide, kArea, kMean, kMax, kP95, kFeatures, kViews, kObjectColumns };
// The rating first after the zone: what an inspector looks for.
enum ZoneColumn {
  kZStation,
  kZSide,
  kZExtent,
  kZRating,
  kZCover,
  kZInspected,
  kZCovered,
  kZHull,
  kZObjects,
  kZMaxHeight,
  kZoneColumns
};

QString SideText(HullSide side) { return QString::fromLatin1(HullSideName(side)); }

QColor RatingColour(FoulingRating r) {
  switch (r) {
    case FoulingRating::kUninspected:
      return QColor(200, 200, 200);
    case FoulingRating::kZeroToOne:
      return QColor(190, 235, 190);
    case FoulingRating::kLight:
      return QColor(255, 240, 170);
    case FoulingRating::kMedium:
      return QColor(255, 200, 140);
    case FoulingRating::kHeavy:
      return QColor(250, 150, 150);
  }
  return {};
}

}  // namespace

ObjectsTableModel::ObjectsTableModel(QObject* parent) : QAbstractTableModel(parent) {}

void ObjectsTableModel::SetMapping(std::shared_ptr<const MappingRun> mapping) {
  beginResetModel();
  mapping_ = std::move(mapping);
  endResetModel();
}

int ObjectsTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() || !mapping_ ? 0 : static_cast<int>(mapping_->result->objects.size());
}

int ObjectsTableModel::columnCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : kObjectColumns; }

QVariant ObjectsTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
  static const QStringList headers = {QStringLiteral("Object"),
                                      QStringLiteral("From bow (m)"),
                                      QStringLiteral("Station"),
                                      QStringLiteral("Side"),
                                      QStringLiteral("Area (m²)"),
                                      QStringLiteral("Mean height (mm)"),
                                      QStringLiteral("Max height ± σ (mm)"),
                                      QStringLiteral("95th pct. height (mm)"),
                                      QStringLiteral("Features"),
                                      QStringLiteral("Views")};
  return headers.value(section);
}

QVariant ObjectsTableModel::data(const QModelIndex& index, int role) const {
  if (!mapping_ || !index.isValid()) return {};
  const DetectedObject& o = mapping_->result->objects[index.row()];
  if (role == kIndexRole) return index.row();
  if (role == Qt::TextAlignmentRole) {
    return index.column() == kId || index.column() == kSide ? int(Qt::AlignLeft | Qt::AlignVCenter)
                                                            : int(Qt::AlignRight | Qt::AlignVCenter);
  }
  if (role != Qt::DisplayRole && role != kSortRole) return {};
  const bool sort = role == kSortRole;
  switch (index.column()) {
    case kId:
      return sort ? QVariant(ObjectIdNumber(o.id)) : QVariant(QString::fromStdString(o.id));
    case kFromBow:
      return sort ? QVariant(o.distance_from_bow) : QVariant(QString::number(o.distance_from_bow, 'f', 2));
    case kStation:
      return o.station;
    case kSide:
      return SideText(o.side);
    case kArea:
      return sort ? QVariant(o.area) : QVariant(QString::number(o.area, 'f', 3));
    case kMean:
      return sort ? QVariant(o.mean_height) : QVariant(QString::number(o.mean_height * 1000.0, 'f', 1));
    case kMax:
      return sort ? QVariant(o.max_height) : QVariant(HeightWithSigma(o.max_height, o.max_height_sigma));
    case kP95:
      return sort ? QVariant(o.p95_height) : QVariant(QString::number(o.p95_height * 1000.0, 'f', 1));
    case kFeatures:
      return o.num_features;
    case kViews:
      return o.num_views;
  }
  return {};
}

QString HeightWithSigma(double height, double sigma) {
  const QString h = QString::number(height * 1000.0, 'f', 1);
  return std::isfinite(sigma) ? h + QStringLiteral(" ± ") + QString::number(sigma * 1000.0, 'f', 1) : h;
}

ZonesTableModel::ZonesTableModel(QObject* parent) : QAbstractTableModel(parent) {}

void ZonesTableModel::SetMapping(std::shared_ptr<const MappingRun> mapping) {
  beginResetModel();
  mapping_ = std::move(mapping);
  Rebuild();
  endResetModel();
}

void ZonesTableModel::SetOnlyInspected(bool only) {
  if (only == only_inspected_) return;
  beginResetModel();
  only_inspected_ = only;
  Rebuild();
  endResetModel();
}

void ZonesTableModel::Rebuild() {
  rows_.clear();
  if (!mapping_) return;
  const auto& zones = mapping_->result->zones;
  for (int i = 0; i < static_cast<int>(zones.size()); ++i) {
    if (!only_inspected_ || zones[i].rating != FoulingRating::kUninspected) rows_.push_back(i);
  }
}

int ZonesTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(rows_.size());
}

int ZonesTableModel::columnCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : kZoneColumns; }

QVariant ZonesTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
  static const QStringList headers = {QStringLiteral("Station"),         QStringLiteral("Side"),
                                      QStringLiteral("From–to bow (m)"), QStringLiteral("Rating"),
                                      QStringLiteral("Cover (%)"),       QStringLiteral("Inspected (m²)"),
                                      QStringLiteral("Covered (m²)"),    QStringLiteral("Hull (m²)"),
                                      QStringLiteral("Objects"),         QStringLiteral("Max height (mm)")};
  return headers.value(section);
}

QVariant ZonesTableModel::data(const QModelIndex& index, int role) const {
  if (!mapping_ || !index.isValid()) return {};
  const int zone_index = rows_[index.row()];
  const ZoneAssessment& z = mapping_->result->zones[zone_index];
  if (role == kIndexRole) return zone_index;
  if (role == Qt::ToolTipRole) return QString::fromStdString(z.note);
  if (role == Qt::BackgroundRole && index.column() == kZRating) return RatingColour(z.rating);
  if (role == Qt::ForegroundRole && index.column() == kZRating) return QColor(Qt::black);
  if (role == Qt::TextAlignmentRole) {
    return index.column() == kZSide || index.column() == kZRating ? int(Qt::AlignLeft | Qt::AlignVCenter)
                                                                  : int(Qt::AlignRight | Qt::AlignVCenter);
  }
  if (role != Qt::DisplayRole && role != kSortRole) return {};
  const bool sort = role == kSortRole;
  auto number = [sort](double v, int decimals) {
    return sort ? QVariant(v) : QVariant(QString::number(v, 'f', decimals));
  };
  switch (index.column()) {
    case kZStation:
      return z.station;
    case kZSide:
      return SideText(z.side);
    case kZExtent:
      return sort ? QVariant(z.from_bow)
                  : QVariant(QStringLiteral("%1–%2").arg(z.from_bow, 0, 'f', 1).arg(z.to_bow, 0, 'f', 1));
    case kZHull:
      return number(z.hull_area, 1);
    case kZInspected:
      return number(z.inspected_area, 2);
    case kZCovered:
      return number(z.covered_area, 3);
    case kZCover:
      return number(z.cover_percent, 1);
    case kZObjects:
      return z.objects;
    case kZMaxHeight:
      return number(z.max_height * 1000.0, 1);
    case kZRating:
      return sort ? QVariant(static_cast<int>(z.rating)) : QVariant(QString::fromLatin1(FoulingRatingName(z.rating)));
  }
  return {};
}

}  // namespace hull::ui
