#include "ui/jobs/job_status_widget.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>

namespace hull::ui {

JobStatusWidget::JobStatusWidget(JobRunner* jobs, QWidget* parent) : QWidget(parent), jobs_(jobs) {
  setObjectName(QStringLiteral("jobStatus"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  label_ = new StatusLabel(520, this);
  label_->setMinimumWidth(200);
  bar_ = new QProgressBar(this);
  bar_->setRange(0, 1000);
  bar_->setMaximumWidth(220);
  bar_->setTextVisible(false);
  cancel_ = new QPushButton(QStringLiteral("Cancel"), this);
  cancel_->setObjectName(QStringLiteral("cancelJob"));
  cancel_->setToolTip(QStringLiteral("Stop the running jobs; what is on screen stays as it is"));
  layout->addWidget(label_);
  layout->addWidget(bar_);
  layout->addWidget(cancel_);
  hide();

  connect(cancel_, &QPushButton::clicked, jobs_, &JobRunner::CancelAll);
  connect(jobs_, &JobRunner::jobStarted, this, [this](JobId id, const QString&, const QString& title) {
    shown_ = id;
    label_->SetStatus(title);
    bar_->setValue(0);
    show();
  });
  connect(jobs_, &JobRunner::jobProgress, this,
          [this](JobId id, const QString&, double fraction, const QString& message) {
            if (id != shown_) return;
            bar_->setValue(static_cast<int>(fraction * 1000));
            if (!message.isEmpty()) label_->SetStatus(message);
          });
  connect(jobs_, &JobRunner::busyChanged, this, [this](bool busy) {
    if (!busy) hide();
  });
}

QString JobStatusWidget::text() const { return label_->fullText(); }

}  // namespace hull::ui
