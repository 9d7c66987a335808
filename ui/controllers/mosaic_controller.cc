#include "ui/controllers/mosaic_controller.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "base/error.h"
#include "mosaic/mosaic_io.h"
#include "pipeline/pipeline.h"
#include "results/mosaic_files.h"
#include "results/pipeline_files.h"
#include "simulate/true_scene.h"
#include "ui/session/mosaic_layer.h"

namespace hull::ui {

const QString MosaicController::kMosaicJob = QStringLiteral("mosaic");

namespace {

namespace fs = std::filesystem;

// What the worker needs of the session, shared (nothing is copied on the GUI thread).
struct MosaicJobInput {
  std::shared_ptr<const SurveyBundle> bundle;
  std::string bundle_path, mesh_path, out;
  bool force = false;  // into a folder of other files (the user confirmed)
  std::shared_ptr<const FrontEndResult> front_end;
  std::shared_ptr<const ModelAlignment> alignment;
  std::shared_ptr<const AdjustmentRun> adjustment;
  std::vector<std::shared_ptr<const AdjustmentRun>> baselines;
  std::shared_ptr<const MappingResult> mapping;
  MosaicOptions options;
};

struct MosaicJobResult {
  std::shared_ptr<const MosaicLayer> layer;
  MosaicSummary summary;
  std::size_t views = 0;
  int atlas_width = 0, atlas_height = 0;
};

std::string Native(const QString& path) { return QFile::encodeName(path).toStdString(); }

// Every image the bundle lists must still be on disk (a dropped frame is
// not listed); names the first missing one.
void CheckImagesPresent(const SurveyBundle& bundle) {
  std::size_t listed = 0, missing = 0;
  std::string first;
  std::error_code ec;
  for (const KeyframeImages& f : bundle.images->frames) {
    for (const std::string* name : {&f.top, &f.bottom}) {
      if (name->empty()) continue;
      ++listed;
      const fs::path path = fs::path(bundle.directory) / *name;  // listed relative to the bundle
      if (fs::is_regular_file(path, ec)) continue;
      if (missing++ == 0) first = path.string();
    }
  }
  if (missing > 0) {
    throw InputError({first, 0, 0, ""}, "no such image: " + std::to_string(missing) + " of the " +
                                            std::to_string(listed) +
                                            " images of the survey are missing since it was opened");
  }
}

MosaicJobResult RunMosaicJob(const MosaicJobInput& in, Progress& progress) {
  const fs::path out = [&] {
    fs::path p = fs::absolute(in.out).lexically_normal();
    return p.filename().empty() ? p.parent_path() : p;
  }();
  progress.Update(0.0, "checking the results folder " + out.string());
  // A new or empty folder, or a results folder of this survey.
  CheckResultsFolder(OutputFolder{out.string(), in.force});
  CheckResultsFolderOfSurvey(out.string(), in.bundle_path);
  CheckImagesPresent(*in.bundle);
  std::unique_ptr<TrueScene> truth;
  std::error_code ec;
  if (fs::exists(fs::path(in.bundle->directory) / "truth" / "albedo.json", ec)) {
    progress.Update(0.01, "reading the survey's true albedo");
    truth = TrueScene::Load(*in.bundle);
  }
  progress.ThrowIfCancelled();

  MosaicResult r;
  {
    SubProgress p(progress, 0.02, 0.9);
    r = BuildMosaic(MosaicInputFromAdjustment(*in.adjustment->result, *in.bundle, in.mapping->model), in.options, p,
                    truth.get());
  }
  progress.ThrowIfCancelled();
  r.inputs = {{"adjustment", (out / "adjustment").string()},
              {"model", (out / "mapping" / "model.ply").string()},
              {"bundle", in.bundle_path}};

  progress.Update(0.9, "writing the results and the photomosaic into " + out.string());
  PipelineInputs pin;
  pin.bundle = *in.bundle;
  pin.bundle_path = in.bundle_path;
  pin.mesh_path = in.mesh_path;
  if (in.front_end) pin.front_end = *in.front_end;
  PipelineResult pr;
  pr.alignment = *in.alignment;
  pr.adjustment = *in.adjustment->result;
  pr.evaluation = in.adjustment->evaluation;
  for (const auto& b : in.baselines) {
    pr.baselines.push_back(*b->result);
    if (b->evaluation) pr.baseline_evaluations.push_back(*b->evaluation);
  }
  pr.mapping = *in.mapping;
  // Cancel acts up to here; the write below is short and not interrupted.
  progress.ThrowIfCancelled();
  // One swap for the whole folder: the results and their mosaic together.
  ResultsRun run = NewResultsRun("hullinspect: Build photomosaic");
  run.AddSurvey("bundle", in.bundle_path);
  run.AddFile("mesh", in.mesh_path);
  WriteResultsFolder(OutputFolder{out.string(), in.force}, run, [&](const std::string& tmp) {
    WritePipelineResult(pin, pr, tmp, out.string());
    WriteMosaic(r, (fs::path(tmp) / "mosaic").string());
  });

  progress.Update(0.97, "reading the photomosaic for display");
  auto layer = std::make_shared<MosaicLayer>(LoadMosaicLayer(out.string()));
  layer->adjustment_key = in.adjustment->key;
  MosaicJobResult result;
  result.layer = std::move(layer);
  result.summary = r.summary;
  result.views = r.views.size();
  result.atlas_width = r.atlas.cols;
  result.atlas_height = r.atlas.rows;
  progress.Update(1.0, "photomosaic written");
  return result;
}

}  // namespace

MosaicController::MosaicController(Session* session, JobRunner* jobs, QObject* parent)
    : QObject(parent), session_(session), jobs_(jobs) {
  auto changed = [this] { emit stateChanged(); };
  connect(session_, &Session::surveyChanged, this, [this] {
    ++generation_;
    jobs_->Cancel(kMosaicJob);
    emit stateChanged();
  });
  for (auto signal :
       {&Session::adjustmentChanged, &Session::mappingChanged, &Session::featuresChanged, &Session::meshChanged}) {
    connect(session_, signal, this, changed);
  }
  connect(jobs_, &JobRunner::jobStarted, this, changed);
  connect(jobs_, &JobRunner::jobSucceeded, this, changed);
  connect(jobs_, &JobRunner::jobCancelled, this, changed);
  connect(jobs_, &JobRunner::jobFailed, this, changed);
}

QString MosaicController::Unavailable() const {
  const SurveyBundle* bundle = session_->bundle();
  if (!bundle) return QStringLiteral("Open a survey with camera images (a version 2 bundle) first.");
  if (!bundle->images || bundle->images->present() == 0) {
    return QStringLiteral(
        "The survey has no camera images to texture with (a version 2 bundle has an images/ folder).");
  }
  const auto& run = session_->adjustment();
  if (!session_->mesh() || !session_->alignment() || !run) {
    return QStringLiteral("Run the inspection first (Inspection ▸ Run): the photomosaic needs the adjusted poses.");
  }
  const auto& mapping = session_->mapping();
  if (!mapping || mapping->adjustment_key != run->key) {
    return QStringLiteral(
        "The adjustment on screen is not mapped yet: the photomosaic textures the mapping's remeshed model.");
  }
  return {};
}

bool MosaicController::busy() const { return jobs_->IsBusy(kMosaicJob); }

void MosaicController::Cancel() { jobs_->Cancel(kMosaicJob); }

void MosaicController::Build(const QString& results, bool force) {
  const QString why = Unavailable();
  if (!why.isEmpty()) {
    emit failed(QStringLiteral("Cannot build the photomosaic"), why);
    return;
  }
  if (results.isEmpty()) {
    emit failed(QStringLiteral("Cannot build the photomosaic"), QStringLiteral("No results folder given."));
    return;
  }
  last_folder_ = QDir::cleanPath(QFileInfo(results).absoluteFilePath());
  MosaicJobInput in;
  in.bundle = session_->survey()->bundle;
  in.bundle_path = Native(session_->survey()->path);
  in.mesh_path = Native(session_->mesh()->path);
  in.out = Native(last_folder_);
  in.force = force;
  in.front_end = session_->frontEnd();
  in.alignment = session_->alignment();
  in.adjustment = session_->adjustment();
  for (const auto& [model, run] : session_->modelRuns()) {
    if (model != in.adjustment->model()) in.baselines.push_back(run);
  }
  in.mapping = session_->mapping()->result;
  in.options = options_;
  const quint64 generation = generation_;
  const QString folder = last_folder_;
  jobs_->Run<MosaicJobResult>(
      kMosaicJob, QStringLiteral("Build the photomosaic into %1").arg(QDir::toNativeSeparators(folder)),
      [in](Progress& progress) { return RunMosaicJob(in, progress); },
      [this, generation, folder](MosaicJobResult& r) {
        if (generation == generation_) session_->SetMosaic(r.layer);
        const MosaicSummary& s = r.summary;
        emit message(QStringLiteral("Photomosaic: %1 of %2 faces textured from %3 of %4 images, atlas %5 x %6, "
                                    "%7 s; written to %8")
                         .arg(s.faces_textured)
                         .arg(s.faces)
                         .arg(s.views_used)
                         .arg(r.views)
                         .arg(r.atlas_width)
                         .arg(r.atlas_height)
                         .arg(s.seconds.total, 0, 'f', 1)
                         .arg(QDir::toNativeSeparators(folder + QStringLiteral("/mosaic"))));
        emit stateChanged();
      });
  emit stateChanged();
}

}  // namespace hull::ui
