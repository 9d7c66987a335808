#include "ui/panels/survey_compare_panel.h"

#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QPushButton>
#include <QSortFilterProxyModel>
#include <QTableView>
#include <QVBoxLayout>

#include "ui/models/change_table_model.h"
#include "ui/models/objects_table_model.h"

namespace hull::ui {

SurveyComparePanel::SurveyComparePanel(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("surveyComparePanel"));
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(4, 4, 4, 4);
  auto* top = new QHBoxLayout;
  summary_ = new QLabel(this);
  summary_->setObjectName(QStringLiteral("compareSummary"));
  summary_->setWordWrap(true);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  compare_ = new QPushButton(QStringLiteral("Compare with…"), this);
  compare_->setObjectName(QStringLiteral("compareWithButton"));
  top->addWidget(summary_, 1);
  top->addWidget(compare_, 0, Qt::AlignTop);
  outer->addLayout(top);

  model_ = new ChangeTableModel(this);
  proxy_ = new QSortFilterProxyModel(this);
  proxy_->setSourceModel(model_);
  proxy_->setSortRole(kSortRole);
  view_ = new QTableView(this);
  view_->setObjectName(QStringLiteral("changeTable"));
  view_->setModel(proxy_);
  view_->setSortingEnabled(true);
  view_->sortByColumn(0, Qt::AscendingOrder);
  view_->setSelectionBehavior(QAbstractItemView::SelectRows);
  view_->setSelectionMode(QAbstractItemView::SingleSelection);
  view_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  view_->setAlternatingRowColors(true);
  view_->verticalHeader()->hide();
  view_->verticalHeader()->setDefaultSectionSize(view_->fontMetrics().height() + 6);
  view_->horizontalHeader()->setStretchLastSection(true);
  view_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  outer->addWidget(view_, 1);

  connect(compare_, &QPushButton::clicked, this, &SurveyComparePanel::compareRequested);
  connect(view_->selectionModel(), &QItemSelectionModel::currentRowChanged, this, [this](const QModelIndex& current) {
    if (current.isValid()) emit objectSelected(current.data(kIndexRole).toInt());
  });
  SetComparison(nullptr);
}

void SurveyComparePanel::SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison) {
  comparison_ = std::move(comparison);
  model_->SetComparison(comparison_);
  view_->resizeColumnsToContents();
  if (!comparison_) {
    summary_->setText(
        QStringLiteral("No comparison yet. Compare with… opens the results of an earlier survey of this hull (and, "
                       "without a map on screen, those of the later one too): the change in height per vertex "
                       "shows in the 3-D view, the matched objects below."));
    return;
  }
  const SurveyComparison& c = comparison_->comparison;
  summary_->setText(
      QStringLiteral("A: %1\nB: %2\n%3 of %4 vertices changed significantly (|Δh| > k·σ); objects: %5.")
          .arg(QString::fromStdString(comparison_->folder_a), QString::fromStdString(comparison_->folder_b))
          .arg(c.significant_vertices)
          .arg(c.model.num_vertices())
          .arg(ChangeCountsText(c)));
}

QString SurveyComparePanel::summaryText() const { return summary_->text(); }

}  // namespace hull::ui
