// The matched objects of a comparison of two surveys, one row per object
// change (mapping/survey_compare.h): how it changed (new, grown, shrunk,
// unchanged, removed), its ids in surveys A and B, its max height in each
// and the change (mm). Qt::DisplayRole gives text, kSortRole numbers,
// kIndexRole the row's index into SurveyComparison::objects.
#pragma once

#include <QAbstractTableModel>
#include <QString>
#include <array>
#include <memory>

#include "results/compare_files.h"

namespace hull::ui {

// How many objects of each kind (indexed by ObjectChangeKind).
std::array<int, 5> CountChanges(const SurveyComparison& comparison);
// "2 new, 3 grown, 0 shrunk, 1 removed, 4 unchanged"
QString ChangeCountsText(const SurveyComparison& comparison);

class ChangeTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  explicit ChangeTableModel(QObject* parent = nullptr);
  void SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison);

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;

 private:
  std::shared_ptr<const SurveyComparisonRun> comparison_;
};

}  // namespace hull::ui
