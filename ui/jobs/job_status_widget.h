// The status bar's job indicator: the running job's title and message, a
// progress bar and a Cancel button, bound to a JobRunner. Hidden when idle.
#pragma once

#include <QWidget>

#include "ui/jobs/job_runner.h"
#include "ui/jobs/status_label.h"

class QProgressBar;
class QPushButton;

namespace hull::ui {

class JobStatusWidget : public QWidget {
  Q_OBJECT

 public:
  explicit JobStatusWidget(JobRunner* jobs, QWidget* parent = nullptr);

  QPushButton* cancelButton() const { return cancel_; }
  QProgressBar* progressBar() const { return bar_; }
  QString text() const;

 private:
  JobRunner* jobs_;
  JobId shown_ = 0;  // the job whose progress is on display (the latest started)
  StatusLabel* label_ = nullptr;
  QProgressBar* bar_ = nullptr;
  QPushButton* cancel_ = nullptr;
};

}  // namespace hull::ui
