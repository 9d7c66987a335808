// The survey panel: what is open — the mesh, the survey bundle (sensors,
// counts, truth) and how the model is placed — as a read-only summary.
#pragma once

#include <QWidget>

class QTreeWidget;

namespace hull::ui {

class Session;

class SurveySummaryPanel : public QWidget {
  Q_OBJECT

 public:
  explicit SurveySummaryPanel(QWidget* parent = nullptr);

  // Rebuilds the summary from the session.
  void Update(const Session& session);
  // "section / label: value" per row, for tests.
  QStringList rowsText() const;

 private:
  QTreeWidget* tree_ = nullptr;
};

}  // namespace hull::ui
