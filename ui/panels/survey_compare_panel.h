// The "Change between surveys" dock: what was compared (the two results
// folders), how many vertices changed significantly, and the matched
// objects (new, grown, shrunk, removed, unchanged) in a sortable table. The
// per-vertex height change itself is the 3-D view's "Change between
// surveys" layer. "Compare with…" asks the main window for the folders.
#pragma once

#include <QWidget>
#include <memory>

#include "results/compare_files.h"

class QLabel;
class QPushButton;
class QSortFilterProxyModel;
class QTableView;

namespace hull::ui {

class ChangeTableModel;

class SurveyComparePanel : public QWidget {
  Q_OBJECT

 public:
  explicit SurveyComparePanel(QWidget* parent = nullptr);
  void SetComparison(std::shared_ptr<const SurveyComparisonRun> comparison);

  QString summaryText() const;
  QTableView* table() const { return view_; }
  QPushButton* compareButton() const { return compare_; }

 signals:
  void compareRequested();
  // A row was selected: the index into SurveyComparison::objects.
  void objectSelected(int index);

 private:
  std::shared_ptr<const SurveyComparisonRun> comparison_;
  QLabel* summary_ = nullptr;
  QPushButton* compare_ = nullptr;
  ChangeTableModel* model_ = nullptr;
  QSortFilterProxyModel* proxy_ = nullptr;
  QTableView* view_ = nullptr;
};

}  // namespace hull::ui
