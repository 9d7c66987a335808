// The headless main job: `hullinspect --demo --out DIR` with no display
// (CTest unsets DISPLAY and WAYLAND_DISPLAY; so does this program for the
// child) runs the whole pipeline and writes the report, the remeshed model
// with its deviation, the objects and zones, and the results; then
// `hullinspect --report DIR --out DIR2` writes the report again from them.
#include <gtest/gtest.h>

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QRegularExpression>

namespace {

const QString kOut = QStringLiteral(HI_REPORT_TEST_DIR);

struct ProcessRun {
  int exit_code = -1;
  bool finished = false;
  QString out, err;
  double seconds = 0;
};

ProcessRun Hullinspect(const QStringList& arguments, int timeout_ms) {
  QProcess p;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  for (const char* v : {"DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"}) env.remove(QString::fromLatin1(v));
  p.setProcessEnvironment(env);
  QElapsedTimer t;
  t.start();
  p.start(QStringLiteral(HI_HULLINSPECT), arguments);
  ProcessRun r;
  r.finished = p.waitForFinished(timeout_ms);
  if (!r.finished) p.kill();
  r.seconds = t.elapsed() / 1000.0;
  r.exit_code = p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
  r.out = QString::fromLocal8Bit(p.readAllStandardOutput());
  r.err = QString::fromLocal8Bit(p.readAllStandardError());
  return r;
}

QByteArray Head(const QString& path, int bytes) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.read(bytes) : QByteArray();
}

TEST(HeadlessDemo, RunsTheMainJobWithoutADisplay) {
  QDir(kOut).removeRecursively();
  const QString out = kOut + QStringLiteral("/demo-output");
  const ProcessRun r = Hullinspect({QStringLiteral("--demo"), QStringLiteral("--out"), out}, 240000);
  ASSERT_TRUE(r.finished) << "no result within 240 s\n" << r.err.toStdString();
  ASSERT_EQ(r.exit_code, 0) << r.err.toStdString();
  std::printf("hullinspect --demo: %.1f s\n%s", r.seconds, qPrintable(r.out));
  const QDir d(out);
  for (const char* f :
       {"report.html", "report.pdf", "figures/heatmap-bottom.png", "figures/cross-section.png", "mapping/model.ply",
        "mapping/model.obj", "mapping/model.stl", "mapping/objects.csv", "mapping/objects.json", "mapping/zones.csv",
        "mapping/zones.json", "alignment.json", "summary.json", "adjustment/adjustment.json",
        "adjustment-naive/adjustment.json", "adjustment-all-on-surface/adjustment.json", "demo-survey/survey.json"}) {
    EXPECT_TRUE(QFile::exists(d.filePath(QString::fromLatin1(f)))) << f;
  }
  // The remeshed model carries its deviation per vertex.
  const QByteArray ply = Head(d.filePath(QStringLiteral("mapping/model.ply")), 4096);
  ASSERT_TRUE(ply.startsWith("ply"));
  const QString header = QString::fromLatin1(ply.left(ply.indexOf("end_header")));
  EXPECT_TRUE(header.contains(QRegularExpression(QStringLiteral("property (float|double|float32|float64) deviation"))))
      << header.toStdString();
  EXPECT_TRUE(Head(d.filePath(QStringLiteral("report.pdf")), 8).startsWith("%PDF-"));
  EXPECT_GT(QFile(d.filePath(QStringLiteral("report.html"))).size(), 100000);
  // Progress on stderr, the paths written on stdout.
  EXPECT_TRUE(r.err.contains(QStringLiteral("pipeline")));
  EXPECT_TRUE(r.out.contains(d.filePath(QStringLiteral("report.pdf"))));
  EXPECT_TRUE(r.out.contains(QStringLiteral("model.ply")));

  // The report again from the results folder.
  const QString again = kOut + QStringLiteral("/again");
  const ProcessRun rr = Hullinspect({QStringLiteral("--report"), out, QStringLiteral("--out"), again}, 120000);
  ASSERT_TRUE(rr.finished);
  ASSERT_EQ(rr.exit_code, 0) << rr.err.toStdString();
  EXPECT_TRUE(Head(again + QStringLiteral("/report.pdf"), 8).startsWith("%PDF-"));
  EXPECT_TRUE(QFile::exists(again + QStringLiteral("/report.html")));
}

TEST(HeadlessDemo, ABadCommandLineIsAUsageError) {
  const ProcessRun r = Hullinspect({QStringLiteral("--demo"), QStringLiteral("--out")}, 30000);
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.err.contains(QStringLiteral("usage: hullinspect --demo")));
  const ProcessRun missing = Hullinspect({QStringLiteral("--report"), kOut + QStringLiteral("/nothing-here"),
                                          QStringLiteral("--out"), kOut + QStringLiteral("/x")},
                                         30000);
  ASSERT_TRUE(missing.finished);
  EXPECT_EQ(missing.exit_code, 3);  // bad input, named
  EXPECT_TRUE(missing.err.contains(QStringLiteral("nothing-here: no such results folder")))
      << missing.err.toStdString();
}

}  // namespace
