// File > Export > Report in the main window (issue 24, part 2): with the
// synthetic survey's results on screen the action writes report.pdf,
// report.html and figures/ into the folder chosen in its dialog, in a job;
// "Open the last report's PDF" is then enabled and the status bar names
// the PDF. A second export cancelled at once leaves the first report byte
// for byte; a folder of the user's files is written only when the user
// agrees, and then none of theirs is replaced. Without results the action
// is disabled.
#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QCryptographicHash>
#include <QDialog>
#include <QDirIterator>
#include <QFileDialog>
#include <QMessageBox>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTimer>
#include <QtTest>
#include <map>
#include <memory>

#include "gui_test_support.h"
#include "inspection_window.h"
#include "synthetic_results.h"
#include "synthetic_survey.h"
#include "ui/controllers/report_export_controller.h"

namespace hull::ui {
namespace {

using testing::OutputDir;
using testing::Window;

// Every file under dir (hidden ones too) with its SHA-1.
std::map<QString, QByteArray> Hashes(const QString& dir) {
  std::map<QString, QByteArray> out;
  QDirIterator it(dir, QDir::Files | QDir::Hidden, QDirIterator::Subdirectories);
  while (it.hasNext()) {
    const QString path = it.next();
    QFile f(path);
    if (f.open(QIODevice::ReadOnly)) {
      out[QDir(dir).relativeFilePath(path)] = QCryptographicHash::hash(f.readAll(), QCryptographicHash::Sha1);
    }
  }
  return out;
}

// The synthetic survey on disk and its results (made from its truth) on screen.
void PutResults(Window& win) {
  static const QString dir = [] {
    const QString d = OutputDir() + QStringLiteral("/report_export_survey");
    QDir(d).removeRecursively();
    return testing::WriteSyntheticSurvey(d);
  }();
  const testing::SyntheticSurvey& survey = testing::MakeSyntheticSurvey();
  Session& s = *win.w.session();
  s.SetMesh({QDir(dir).filePath(QStringLiteral("hull.ply")), survey.mesh});
  s.SetSurvey({dir, survey.bundle, std::make_shared<SurveyOverlays>(ComputeSurveyOverlays(*survey.bundle))});
  auto alignment = std::make_shared<ModelAlignment>();
  alignment->x_gM = alignment->initial_x_gM = Pose::FromVector(survey.bundle->truth->x_gM);
  s.SetAlignment(alignment);
  s.SetModelRuns(testing::SyntheticRuns());
  s.SetAdjustment(testing::SyntheticRuns().at(SurfaceModel::kMaxMixture));
  s.SetMapping(testing::SyntheticMapping());
}

// Triggers File > Export > Report and answers its dialogs: Yes to every
// question (its text appended to `asked`, unless `answer_no`), `folder` in
// the folder dialog.
void TriggerExport(Window& win, const QString& folder, QStringList* asked, bool answer_no = false) {
  QTimer answer;
  answer.setInterval(200);
  QObject::connect(&answer, &QTimer::timeout, [&] {
    QWidget* modal = QApplication::activeModalWidget();
    if (auto* box = qobject_cast<QMessageBox*>(modal)) {
      if (asked) *asked << box->text();
      box->button(answer_no ? QMessageBox::No : QMessageBox::Yes)->click();
    } else if (auto* dialog = qobject_cast<QFileDialog*>(modal)) {
      dialog->setDirectory(folder);
      static_cast<QDialog*>(dialog)->accept();
    }
  });
  answer.start();
  win.w.action(QStringLiteral("exportReport"))->trigger();
}

}  // namespace

class ReportExportTest : public QObject {
  Q_OBJECT

 private slots:
  void exportsCancelsAndKeepsTheUsersFiles() {
    Window win;
    QVERIFY(QTest::qWaitForWindowExposed(&win.w));
    QVERIFY(!win.w.action(QStringLiteral("exportReport"))->isEnabled());  // nothing to report yet
    PutResults(win);
    QVERIFY(win.w.action(QStringLiteral("exportReport"))->isEnabled());
    QVERIFY(!win.w.action(QStringLiteral("openLastReport"))->isEnabled());

    const QString folder = OutputDir() + QStringLiteral("/report_export");
    QDir(folder).removeRecursively();
    QVERIFY(QDir().mkpath(folder));
    QSignalSpy progress(win.w.jobs(), &JobRunner::jobProgress);
    QStringList asked;
    TriggerExport(win, folder, &asked);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join(QLatin1Char('\n'))));
    QFile pdf(folder + QStringLiteral("/report.pdf"));
    QVERIFY(pdf.open(QIODevice::ReadOnly));
    QVERIFY(pdf.read(5) == "%PDF-");
    QVERIFY(QFile::exists(folder + QStringLiteral("/report.html")));
    QVERIFY(QDir(folder + QStringLiteral("/figures")).entryList(QDir::Files).size() >= 3);
    QVERIFY(progress.count() > 0);
    QCOMPARE(win.w.reportExporter()->lastPdf(), folder + QStringLiteral("/report.pdf"));
    QVERIFY(win.w.action(QStringLiteral("openLastReport"))->isEnabled());
    QVERIFY2(win.w.statusBar()->currentMessage().contains(QStringLiteral("report.pdf")),
             qPrintable(win.w.statusBar()->currentMessage()));
    win.w.grab().save(OutputDir() + QStringLiteral("/report_export_window.png"));

    // Exported again and cancelled at once: the first report stays byte for byte.
    const auto before = Hashes(folder);
    QSignalSpy cancelled(win.w.jobs(), &JobRunner::jobCancelled);
    win.w.reportExporter()->Export(ReportInputsOf(*win.w.CollectReport()), folder);
    win.w.reportExporter()->Cancel();
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QCOMPARE(cancelled.count(), 1);
    QVERIFY(Hashes(folder) == before);

    // A folder of the user's: refused when the user says no; with yes, the
    // report goes in beside their file, which is kept.
    const QString mine = OutputDir() + QStringLiteral("/report_export_mine");
    QDir(mine).removeRecursively();
    QVERIFY(QDir().mkpath(mine));
    QFile notes(mine + QStringLiteral("/notes.txt"));
    QVERIFY(notes.open(QIODevice::WriteOnly) && notes.write("mine") == 4);
    notes.close();
    TriggerExport(win, mine, nullptr, true);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY(!QFile::exists(mine + QStringLiteral("/report.pdf")));
    asked.clear();
    TriggerExport(win, mine, &asked);
    HI_WAIT_IDLE(win.w.jobs(), 60000);
    QVERIFY2(asked.join(QLatin1Char(' ')).contains(QStringLiteral("holds files HullInspect did not write")),
             qPrintable(asked.join(QLatin1Char('\n'))));
    QVERIFY(QFile::exists(mine + QStringLiteral("/report.pdf")));
    QVERIFY(notes.open(QIODevice::ReadOnly));
    QCOMPARE(notes.readAll(), QByteArray("mine"));
    QVERIFY2(win.errors.isEmpty(), qPrintable(win.errors.join(QLatin1Char('\n'))));
  }
};

}  // namespace hull::ui

HI_GUI_TEST_MAIN(hull::ui::ReportExportTest)
#include "report_export_test.moc"
