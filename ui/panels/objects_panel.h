// The objects and zones dock: sortable tables of the detected objects and
// of the fouling assessment per hull zone (ObjectsTableModel and
// ZonesTableModel behind QSortFilterProxyModels), with a summary line.
// Selecting a row says so (objectSelected, zoneSelected): the main window
// flies the 3-D view there and shows the object's keyframe.
#pragma once

#include <QWidget>
#include <memory>

#include "ui/session/inspection_results.h"

class QCheckBox;
class QLabel;
class QSortFilterProxyModel;
class QTabWidget;
class QTableView;

namespace hull::ui {

class ObjectsTableModel;
class ZonesTableModel;

class ObjectsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit ObjectsPanel(QWidget* parent = nullptr);

  void SetMapping(std::shared_ptr<const MappingRun> mapping);

  QTableView* objectsTable() const { return objects_view_; }
  QTableView* zonesTable() const { return zones_view_; }
  QTabWidget* tabs() const { return tabs_; }
  QCheckBox* onlyInspected() const { return only_inspected_; }
  QString summaryText() const;
  // Selects the object's row (by its index in the result), as a click does.
  void SelectObject(int object_index);

 signals:
  void objectSelected(int object_index);
  void zoneSelected(int zone_index);

 private:
  std::shared_ptr<const MappingRun> mapping_;
  QLabel* summary_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  ObjectsTableModel* objects_ = nullptr;
  ZonesTableModel* zones_ = nullptr;
  QSortFilterProxyModel* objects_proxy_ = nullptr;
  QSortFilterProxyModel* zones_proxy_ = nullptr;
  QTableView* objects_view_ = nullptr;
  QTableView* zones_view_ = nullptr;
  QCheckBox* only_inspected_ = nullptr;
};

}  // namespace hull::ui
