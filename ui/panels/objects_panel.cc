#include "ui/panels/objects_panel.h"

#include <QCheckBox>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QSortFilterProxyModel>
#include <QTabWidget>
#include <QTableView>
#include <QVBoxLayout>

#include "ui/models/objects_table_model.h"

namespace hull::ui {

namespace {

QTableView* MakeTable(QWidget* parent, QSortFilterProxyModel* proxy, const QString& name) {
  auto* view = new QTableView(parent);
  view->setObjectName(name);
  view->setModel(proxy);
  view->setSortingEnabled(true);
  view->setSelectionBehavior(QAbstractItemView::SelectRows);
  view->setSelectionMode(QAbstractItemView::SingleSelection);
  view->setEditTriggers(QAbstractItemView::NoEditTriggers);
  view->setAlternatingRowColors(true);
  view->verticalHeader()->hide();
  view->verticalHeader()->setDefaultSectionSize(view->fontMetrics().height() + 6);
  view->horizontalHeader()->setStretchLastSection(true);
  view->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  return view;
}

}  // namespace

ObjectsPanel::ObjectsPanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("objectsPanel"));
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  summary_ = new QLabel(this);
  summary_->setObjectName(QStringLiteral("objectsSummary"));
  summary_->setWordWrap(true);
  outer->addWidget(summary_);
  tabs_ = new QTabWidget(this);
  outer->addWidget(tabs_, 1);

  objects_ = new ObjectsTableModel(this);
  objects_proxy_ = new QSortFilterProxyModel(this);
  objects_proxy_->setSourceModel(objects_);
  objects_proxy_->setSortRole(kSortRole);
  objects_view_ = MakeTable(tabs_, objects_proxy_, QStringLiteral("objectsTable"));
  objects_view_->sortByColumn(1, Qt::AscendingOrder);  // from the bow aft
  tabs_->addTab(objects_view_, QStringLiteral("Detected objects"));

  auto* zones_page = new QWidget(tabs_);
  auto* zones_layout = new QVBoxLayout(zones_page);
  zones_layout->setContentsMargins(0, 0, 0, 0);
  only_inspected_ = new QCheckBox(QStringLiteral("Only zones the survey saw"), zones_page);
  only_inspected_->setObjectName(QStringLiteral("onlyInspected"));
  only_inspected_->setChecked(true);
  zones_ = new ZonesTableModel(this);
  zones_proxy_ = new QSortFilterProxyModel(this);
  zones_proxy_->setSourceModel(zones_);
  zones_proxy_->setSortRole(kSortRole);
  zones_view_ = MakeTable(zones_page, zones_proxy_, QStringLiteral("zonesTable"));
  zones_view_->sortByColumn(0, Qt::AscendingOrder);
  zones_layout->addWidget(only_inspected_);
  zones_layout->addWidget(zones_view_, 1);
  tabs_->addTab(zones_page, QStringLiteral("Zones and ratings"));

  connect(only_inspected_, &QCheckBox::toggled, zones_, &ZonesTableModel::SetOnlyInspected);
  connect(objects_view_->selectionModel(), &QItemSelectionModel::currentRowChanged, this,
          [this](const QModelIndex& current) {
            if (current.isValid()) emit objectSelected(current.data(kIndexRole).toInt());
          });
  connect(zones_view_->selectionModel(), &QItemSelectionModel::currentRowChanged, this,
          [this](const QModelIndex& current) {
            if (current.isValid()) emit zoneSelected(current.data(kIndexRole).toInt());
          });
  SetMapping(nullptr);
}

void ObjectsPanel::SetMapping(std::shared_ptr<const MappingRun> mapping) {
  mapping_ = std::move(mapping);
  objects_->SetMapping(mapping_);
  zones_->SetMapping(mapping_);
  objects_view_->resizeColumnsToContents();
  zones_view_->resizeColumnsToContents();
  if (!mapping_) {
    summary_->setText(QStringLiteral("No map yet: Inspection ▸ Run (F5) adjusts the survey, then maps it."));
    return;
  }
  const MappingSummary& s = mapping_->result->summary;
  int inspected = 0;
  for (const ZoneAssessment& z : mapping_->result->zones) inspected += z.rating != FoulingRating::kUninspected;
  const double cover = s.inspected_area > 0 ? 100.0 * s.covered_area / s.inspected_area : 0.0;
  summary_->setText(QStringLiteral("%1 objects over %2 m² of the %3 m² inspected (%4 %); %5 of %6 zones inspected, "
                                   "the others are uninspected, not clean. Ratings follow MEPC.378(80) from "
                                   "geometry alone: \"0-1\" cannot tell slime from a clean hull.")
                        .arg(mapping_->result->objects.size())
                        .arg(s.covered_area, 0, 'f', 2)
                        .arg(s.inspected_area, 0, 'f', 1)
                        .arg(cover, 0, 'f', 1)
                        .arg(inspected)
                        .arg(mapping_->result->zones.size()));
}

QString ObjectsPanel::summaryText() const { return summary_->text(); }

void ObjectsPanel::SelectObject(int object_index) {
  for (int row = 0; row < objects_proxy_->rowCount(); ++row) {
    const QModelIndex index = objects_proxy_->index(row, 0);
    if (index.data(kIndexRole).toInt() == object_index) {
      objects_view_->setCurrentIndex(index);
      return;
    }
  }
}

}  // namespace hull::ui
