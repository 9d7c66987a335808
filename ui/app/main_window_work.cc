// Unsaved work in the main window: what changed since the project was last
// saved or a document opened (the parameters, by their undo stack, and
// results computed since), the title's modified mark, and the question
// before something would discard it (quit, open another document).
#include <QCloseEvent>
#include <QMessageBox>
#include <QPushButton>
#include <QUndoStack>

#include "ui/app/main_window.h"
#include "ui/app/window_layout.h"
#include "ui/controllers/document_controller.h"
#include "ui/panels/parameter_panel.h"
#include "ui/session/session.h"

namespace hull::ui {

void MainWindow::ConnectWork() {
  connect(parameters_->undoStack(), &QUndoStack::cleanChanged, this, &MainWindow::UpdateModified);
  // Results computed (not cleared) since the last save or open.
  const auto computed = [this](bool present) {
    if (!present) return;
    results_unsaved_ = true;
    UpdateModified();
  };
  connect(session_, &Session::adjustmentChanged, this,
          [this, computed] { computed(session_->adjustment() != nullptr); });
  connect(session_, &Session::mappingChanged, this, [this, computed] { computed(session_->mapping() != nullptr); });
  connect(session_, &Session::comparisonChanged, this,
          [this, computed] { computed(session_->comparison() != nullptr); });
  connect(documents_, &DocumentController::opened, this, &MainWindow::MarkWorkSaved);
}

bool MainWindow::HasUnsavedWork() const { return !parameters_->undoStack()->isClean() || results_unsaved_; }

void MainWindow::MarkWorkSaved() {
  parameters_->undoStack()->setClean();
  results_unsaved_ = false;
  UpdateModified();
}

void MainWindow::UpdateModified() { setWindowModified(HasUnsavedWork()); }

bool MainWindow::MayDiscardWork(const QString& action) {
  if (!HasUnsavedWork()) return true;
  QStringList what;
  if (!parameters_->undoStack()->isClean()) what << QStringLiteral("the parameters were changed");
  if (results_unsaved_) {
    what << QStringLiteral(
        "results were computed (the project keeps the parameters and the view; Inspection ▸ "
        "Run computes the results again)");
  }
  QMessageBox box(QMessageBox::Warning, QStringLiteral("Unsaved work"),
                  QStringLiteral("Since the project was last saved, %1.").arg(what.join(QStringLiteral(", and "))),
                  QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
  box.setInformativeText(QStringLiteral("Save the project before %1?").arg(action));
  box.setDefaultButton(QMessageBox::Save);
  switch (box.exec()) {
    case QMessageBox::Save:
      AskSaveProject();
      return !HasUnsavedWork();  // the save dialog cancelled, or the save failed: stay
    case QMessageBox::Discard:
      return true;
    default:
      return false;
  }
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!MayDiscardWork(QStringLiteral("quitting"))) {
    event->ignore();
    return;
  }
  jobs_->CancelAll();
  if (layout_settings_) SaveWindowLayout(*this, layout_settings_);
  QMainWindow::closeEvent(event);
}

bool MainWindow::RestoreLayout(QSettings* settings) {
  layout_settings_ = settings;
  layout_restored_ = RestoreWindowLayout(this, settings);
  return layout_restored_;
}

}  // namespace hull::ui
