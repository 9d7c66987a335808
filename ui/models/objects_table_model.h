// Table models of a mapping result for the objects and zones dock: the
// detected objects (where on the hull, footprint, heights, features, views)
// and the fouling assessment per hull zone (areas, coverage, IMO rating).
// Qt::DisplayRole gives text; kSortRole gives numbers for sorting.
#pragma once

#include <QAbstractTableModel>
#include <memory>
#include <vector>

#include "ui/session/inspection_results.h"

namespace hull::ui {

constexpr int kSortRole = Qt::UserRole + 1;
// The row's index into MappingResult::objects or ::zones.
constexpr int kIndexRole = Qt::UserRole + 2;

// "123.4 ± 5.6" (mm) from metres; the height alone when sigma is NaN.
QString HeightWithSigma(double height, double sigma);

class ObjectsTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  explicit ObjectsTableModel(QObject* parent = nullptr);
  void SetMapping(std::shared_ptr<const MappingRun> mapping);

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;

 private:
  std::shared_ptr<const MappingRun> mapping_;
};

class ZonesTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  explicit ZonesTableModel(QObject* parent = nullptr);
  void SetMapping(std::shared_ptr<const MappingRun> mapping);
  // Only the zones a camera saw (default), or every zone of the hull.
  void SetOnlyInspected(bool only);
  bool onlyInspected() const { return only_inspected_; }

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;

 private:
  void Rebuild();

  std::shared_ptr<const MappingRun> mapping_;
  bool only_inspected_ = true;
  std::vector<int> rows_;  // indices into result->zones
};

}  // namespace hull::ui
