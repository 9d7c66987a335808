// Builds the 3-D photomosaic (docs/mosaic.md) of the results on screen in a
// worker (job kind "mosaic", with progress and cancel): the adjustment on
// screen, its mapping's remeshed model and the open survey's camera images
// (a version 2 bundle), with core's BuildMosaic and the default
// MosaicOptions ('hullinspect-cli mosaic' without options).
//
// The application holds its results in memory; the mosaic goes to disk in a
// results folder the user chooses, laid out as 'hullinspect-cli run' and
// 'hullinspect-cli mosaic' write it: the session's results (alignment.json,
// adjustment/, mapping/, summary.json, ... : results/pipeline_files.h) and
// the mosaic in RESULTS/mosaic/ (mosaic.obj, .mtl, _atlas.png, .ply, .json,
// _faces.csv: results/mosaic_files.h), so that 'hullinspect-cli report',
// 'hullinspect-cli export' and File > Open photomosaic read it. The folder
// is replaced in one atomic swap after the mosaic is built, with its
// manifest (results/results_folder.h; the user's own files in it are
// kept): a cancelled or failed build leaves it as it was, a previous mosaic
// included (Cancel acts until that write starts, the last few per cent). A
// folder holding files HullInspect did not write, or the results of another
// survey bundle, is refused before the build. On success the
// mosaic goes into the Session: the 3-D view's textured layer, and the
// report hook's Photomosaic (models/report_source.h).
#pragma once

#include <QObject>
#include <QString>

#include "mosaic/photomosaic.h"
#include "ui/jobs/job_runner.h"
#include "ui/session/session.h"

namespace hull::ui {

class MosaicController : public QObject {
  Q_OBJECT

 public:
  static const QString kMosaicJob;

  MosaicController(Session* session, JobRunner* jobs, QObject* parent = nullptr);

  // Why no mosaic can be built now, as a sentence for the user ("" : it can).
  QString Unavailable() const;
  bool CanBuild() const { return Unavailable().isEmpty(); }
  // Builds the mosaic into `results` (created when it does not exist).
  // A folder holding files HullInspect did not write is refused unless
  // `force` (the user confirmed: their files are kept, none replaced).
  // Refusals (Unavailable) go through failed(); errors of the job through
  // the JobRunner's jobFailed.
  void Build(const QString& results, bool force = false);
  void Cancel();
  bool busy() const;
  // The results folder of the last build asked for ("" : none yet).
  const QString& lastFolder() const { return last_folder_; }
  // The options of the next build (defaults: MosaicOptions()).
  const MosaicOptions& options() const { return options_; }
  void SetOptions(const MosaicOptions& options) { options_ = options; }

 signals:
  void failed(const QString& title, const QString& message);
  void message(const QString& text);  // for the status bar
  void stateChanged();

 private:
  Session* session_;
  JobRunner* jobs_;
  MosaicOptions options_;
  QString last_folder_;
  quint64 generation_ = 0;  // bumped when another survey is opened
};

}  // namespace hull::ui
