#include "ui/controllers/inspection_controller.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "ui/session/inspection_parameters.h"

namespace hull::ui {

const QString InspectionController::kAdjustJob = QStringLiteral("adjust");
const QString InspectionController::kCompareJob = QStringLiteral("compare");
const QString InspectionController::kMapJob = QStringLiteral("map");

namespace {

constexpr std::size_t kCacheSize = 24;     // adjustment runs kept (a few MB each at most)
constexpr std::size_t kMapCacheSize = 16;  // mapping runs kept (a fused mesh each)
constexpr std::size_t kMappers = 4;        // Mappers kept (a refined mesh each)

const SurfaceModel kAllModels[] = {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture};

std::shared_ptr<const PipelineInputs> MakeInputs(const LoadedSurvey& survey, const LoadedMesh& mesh) {
  auto in = std::make_shared<PipelineInputs>();
  in->bundle = *survey.bundle;
  in->mesh = *mesh.mesh;
  in->bundle_path = survey.path.toStdString();
  in->mesh_path = mesh.path.toStdString();
  return in;
}

// The run's evaluation and overlays (worker side).
std::shared_ptr<const AdjustmentRun> MakeRun(std::string key, AdjustmentResult result, const PipelineInputs& in,
                                             bool warm) {
  auto run = std::make_shared<AdjustmentRun>();
  run->key = std::move(key);
  auto r = std::make_shared<const AdjustmentResult>(std::move(result));
  if (in.bundle.truth) run->evaluation = EvaluateAdjustment(in.bundle, in.mesh, *r);
  run->overlays = std::make_shared<const AdjustedOverlays>(ComputeAdjustedOverlays(in.bundle, *r));
  run->result = std::move(r);
  run->warm_started = warm;
  return run;
}

QString ModelTitle(SurfaceModel m) {
  switch (m) {
    case SurfaceModel::kNaive:
      return QStringLiteral("naive");
    case SurfaceModel::kAllOnSurface:
      return QStringLiteral("all-on-surface");
    case SurfaceModel::kMaxMixture:
      return QStringLiteral("max-mixture");
  }
  return {};
}

}  // namespace

InspectionController::InspectionController(Session* session, JobRunner* jobs, QObject* parent)
    : QObject(parent), session_(session), jobs_(jobs), values_(DefaultValues(DefaultParameterTable())) {
  connect(session_, &Session::meshChanged, this, [this] { ResetForInputs(); });
  connect(session_, &Session::surveyChanged, this, [this] { ResetForInputs(); });
  connect(session_, &Session::featuresChanged, this, [this] {
    ResetForInputs(true);
    if (active_) Update();
  });
  connect(jobs_, &JobRunner::jobStarted, this, [this] { emit stateChanged(); });
  connect(jobs_, &JobRunner::jobCancelled, this, [this](JobId, const QString& kind) {
    // A run the user cancelled (nothing took its place) leaves the
    // inspection idle: no "Adjusting…" for a run that is not coming, and no
    // run started by the next parameter change until Run.
    if ((kind == kAdjustJob || kind == kMapJob) && !jobs_->IsBusy(kAdjustJob) && !jobs_->IsBusy(kMapJob) &&
        !UpToDate()) {
      active_ = false;
    }
    emit stateChanged();
  });
  connect(jobs_, &JobRunner::jobFailed, this, [this] { emit stateChanged(); });
}

void InspectionController::ResetForInputs(bool keep_active) {
  ++generation_;
  jobs_->Cancel(kAdjustJob);
  jobs_->Cancel(kCompareJob);
  jobs_->Cancel(kMapJob);
  inputs_.reset();
  cache_.clear();
  order_.clear();
  map_cache_.clear();
  map_order_.clear();
  mappers_.clear();
  mapper_order_.clear();
  // New features of the same survey find the same objects: their ids stay.
  if (!keep_active) object_ids_.Clear();
  active_ = active_ && keep_active;
  emit stateChanged();
}

void InspectionController::SetParameters(const ParameterValues& values) {
  if (values == values_) return;
  values_ = values;
  if (active_) {
    Update();
  } else {
    emit stateChanged();
  }
}

bool InspectionController::CanRun() const { return session_->mesh() && session_->survey(); }

bool InspectionController::CanCompare() const { return CanRun() && session_->adjustment() && inputs_; }

void InspectionController::Run() {
  if (!CanRun()) return;
  active_ = true;
  Update();
  emit stateChanged();
}

bool InspectionController::UpToDate() const {
  return session_->adjustment() && session_->adjustment()->key == AdjustmentKey(values_).toStdString() &&
         session_->mapping() && session_->mapping()->key == MappingKey(values_).toStdString();
}

QString InspectionController::StatusText() const {
  const auto& run = session_->adjustment();
  if (!run && active_ && session_->NeedsFeatureExtraction()) return QStringLiteral("Waiting for the image features…");
  if (!run) return active_ ? QStringLiteral("Adjusting…") : QString();
  const AdjustmentResult& r = *run->result;
  QString text = QStringLiteral("%1: %2 iterations, %3 s, %4 % of the features on the hull")
                     .arg(ModelTitle(r.options.model))
                     .arg(r.iterations.empty() ? 0 : r.iterations.back().iteration)
                     .arg(r.seconds, 0, 'f', 1)
                     .arg(100.0 * r.FractionOnSurface(), 0, 'f', 1);
  if (const auto& m = session_->mapping()) {
    text += QStringLiteral("; %1 objects").arg(m->result->objects.size());
  }
  if (!UpToDate()) {
    text += jobs_->IsBusy(kAdjustJob) || jobs_->IsBusy(kMapJob)
                ? QStringLiteral(" — updating for the new parameters…")
                : QStringLiteral(" — for other parameters: Run to update");
  }
  return text;
}

std::shared_ptr<const AdjustmentRun> InspectionController::Cached(const std::string& key) const {
  auto it = cache_.find(key);
  return it == cache_.end() ? nullptr : it->second;
}

void InspectionController::Store(const std::shared_ptr<const AdjustmentRun>& run) {
  if (!cache_.count(run->key)) order_.push_back(run->key);
  cache_[run->key] = run;
  while (cache_.size() > kCacheSize) {
    // Never drop what is on screen.
    auto victim = std::find_if(order_.begin(), order_.end(), [this](const std::string& k) {
      return !session_->adjustment() || session_->adjustment()->key != k;
    });
    if (victim == order_.end()) break;
    cache_.erase(*victim);
    order_.erase(victim);
  }
}

std::shared_ptr<const AdjustmentResult> InspectionController::WarmStart(SurfaceModel model) const {
  if (session_->adjustment() && session_->adjustment()->model() == model) return session_->adjustment()->result;
  for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
    const auto& run = cache_.at(*it);
    if (run->model() == model) return run->result;
  }
  return nullptr;
}

void InspectionController::Update() {
  const std::string key = AdjustmentKey(values_).toStdString();
  if (auto run = Cached(key)) {
    jobs_->Cancel(kAdjustJob);  // a run for other values is no longer wanted
    session_->SetAdjustment(run);
    UpdateModelRuns();
    UpdateMapping();
    emit stateChanged();
    return;
  }
  StartAdjustment();
}

void InspectionController::StartAdjustment() {
  if (!CanRun() || session_->NeedsFeatureExtraction()) return;  // featuresChanged starts it
  const std::string key = AdjustmentKey(values_).toStdString();
  const AdjustmentOptions options = AdjustmentOptionsFrom(values_);
  std::shared_ptr<const PipelineInputs> inputs = inputs_;
  std::shared_ptr<const ModelAlignment> alignment = session_->alignment();
  std::shared_ptr<const AdjustmentResult> warm = alignment ? WarmStart(options.model) : nullptr;
  const LoadedSurvey survey = *session_->survey();
  const LoadedMesh mesh = *session_->mesh();
  const quint64 generation = generation_;

  struct Output {
    std::shared_ptr<const PipelineInputs> inputs;
    std::shared_ptr<const ModelAlignment> alignment;
    std::shared_ptr<const AdjustmentRun> run;
  };
  const QString title = warm ? QStringLiteral("Re-adjust (%1, from the last result)").arg(ModelTitle(options.model))
                             : QStringLiteral("Adjust (%1)").arg(ModelTitle(options.model));
  jobs_->Run<Output>(
      kAdjustJob, title,
      [=](Progress& progress) {
        Output out;
        out.inputs = inputs ? inputs : MakeInputs(survey, mesh);
        out.alignment = alignment;
        double begin = 0.0;
        if (!out.alignment) {
          progress.Update(0.0, "aligning the DVL returns to the model");
          SubProgress p(progress, 0.0, 0.2);
          out.alignment = std::make_shared<const ModelAlignment>(RunAlignment(*out.inputs, PipelineOptions(), p));
          begin = 0.2;
        }
        AdjustmentResult result;
        {
          SubProgress p(progress, begin, 0.95);
          result = RunAdjustmentStep(*out.inputs, out.alignment->x_gM, options, p, warm.get());
        }
        progress.Update(0.96, "evaluating the adjustment");
        out.run = MakeRun(key, std::move(result), *out.inputs, warm != nullptr);
        progress.Update(1.0, "adjusted");
        return out;
      },
      [this, generation](Output& out) {
        if (generation != generation_) return;  // other inputs since
        inputs_ = out.inputs;
        session_->SetAlignment(out.alignment);
        Store(out.run);
        if (out.run->key == AdjustmentKey(values_).toStdString()) {
          session_->SetAdjustment(out.run);
          UpdateModelRuns();
          UpdateMapping();
        }
        emit stateChanged();
      });
  emit stateChanged();
}

void InspectionController::CompareModels() {
  if (!CanCompare()) return;
  std::vector<std::pair<std::string, AdjustmentOptions>> todo;
  const SurfaceModel current = ModelFromKey(values_.value(QStringLiteral("model")).toString());
  for (SurfaceModel m : kAllModels) {
    if (m == current) continue;
    const ParameterValues v = WithModel(values_, m);
    const std::string key = AdjustmentKey(v).toStdString();
    if (!Cached(key)) todo.emplace_back(key, AdjustmentOptionsFrom(v));
  }
  if (todo.empty()) {
    UpdateModelRuns();
    return;
  }
  const std::shared_ptr<const PipelineInputs> inputs = inputs_;
  const std::shared_ptr<const ModelAlignment> alignment = session_->alignment();
  const quint64 generation = generation_;
  using Runs = std::vector<std::shared_ptr<const AdjustmentRun>>;
  jobs_->Run<Runs>(
      kCompareJob, QStringLiteral("Compare the surface models"),
      [=](Progress& progress) {
        Runs runs;
        for (std::size_t i = 0; i < todo.size(); ++i) {
          SubProgress p(progress, static_cast<double>(i) / todo.size(), (i + 0.95) / todo.size());
          AdjustmentResult r = RunAdjustmentStep(*inputs, alignment->x_gM, todo[i].second, p);
          runs.push_back(MakeRun(todo[i].first, std::move(r), *inputs, false));
        }
        progress.Update(1.0, "compared");
        return runs;
      },
      [this, generation](Runs& runs) {
        if (generation != generation_) return;
        for (const auto& run : runs) Store(run);
        UpdateModelRuns();
        emit stateChanged();
      });
  emit stateChanged();
}

void InspectionController::UpdateModelRuns() {
  Session::ModelRuns runs;
  for (SurfaceModel m : kAllModels) {
    if (auto run = Cached(AdjustmentKey(WithModel(values_, m)).toStdString())) runs[m] = run;
  }
  session_->SetModelRuns(std::move(runs));
}

void InspectionController::UpdateMapping() {
  const auto& adjustment = session_->adjustment();
  if (!adjustment || !CanRun() || adjustment->key != AdjustmentKey(values_).toStdString()) return;
  const std::string key = MappingKey(values_).toStdString();
  if (auto it = map_cache_.find(key); it != map_cache_.end()) {
    jobs_->Cancel(kMapJob);
    session_->SetMapping(it->second);
    emit stateChanged();
    return;
  }
  const std::string adjustment_key = adjustment->key;
  std::shared_ptr<Mapper> mapper;
  if (auto it = mappers_.find(adjustment_key); it != mappers_.end()) mapper = it->second;
  const MappingOptions options = MappingOptionsFrom(values_);
  const std::shared_ptr<const AdjustmentResult> result = adjustment->result;
  const std::shared_ptr<const SurveyBundle> bundle = session_->survey()->bundle;
  const std::shared_ptr<const TriangleMesh> cad = session_->mesh()->mesh;
  const quint64 generation = generation_;
  struct Output {
    std::shared_ptr<Mapper> mapper;
    std::shared_ptr<MappingResult> result;  // its objects named by object_ids_ when it arrives
    std::shared_ptr<MappingRun> run;
  };
  jobs_->Run<Output>(
      kMapJob, QStringLiteral("Map the shapes (τ %1 m, α %2 m)").arg(options.tau).arg(options.alpha),
      [=](Progress& progress) {
        Output out;
        out.mapper = mapper;
        if (!out.mapper) {
          progress.Update(0.0, "preparing the mapping input");
          out.mapper = std::make_shared<Mapper>(MappingInputFromAdjustment(*result, *bundle), *cad);
        }
        out.result = std::make_shared<MappingResult>(out.mapper->Run(options, progress));
        progress.Update(0.98, "outlining the detected objects");
        out.run = std::make_shared<MappingRun>();
        out.run->key = key;
        out.run->adjustment_key = adjustment_key;
        out.run->input = std::make_shared<const MappingInput>(out.mapper->input());
        out.run->overlays = std::make_shared<const MappingOverlays>(ComputeMappingOverlays(*out.result, *cad));
        return out;
      },
      [this, generation, adjustment_key](Output& out) {
        if (generation != generation_) return;
        // The ids of the objects seen before (here, so that runs finishing
        // in any order name them from one record).
        object_ids_.Assign(&out.result->objects, out.result->model);
        out.run->result = std::move(out.result);
        if (!mappers_.count(adjustment_key)) {
          mappers_[adjustment_key] = out.mapper;
          mapper_order_.push_back(adjustment_key);
          while (mappers_.size() > kMappers) {
            mappers_.erase(mapper_order_.front());
            mapper_order_.pop_front();
          }
        }
        if (!map_cache_.count(out.run->key)) map_order_.push_back(out.run->key);
        map_cache_[out.run->key] = out.run;
        while (map_cache_.size() > kMapCacheSize) {
          auto victim = std::find_if(map_order_.begin(), map_order_.end(), [this](const std::string& k) {
            return !session_->mapping() || session_->mapping()->key != k;
          });
          if (victim == map_order_.end()) break;
          map_cache_.erase(*victim);
          map_order_.erase(victim);
        }
        if (out.run->key == MappingKey(values_).toStdString()) session_->SetMapping(out.run);
        emit stateChanged();
      });
  emit stateChanged();
}

}  // namespace hull::ui
