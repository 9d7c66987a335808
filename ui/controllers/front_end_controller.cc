#include "ui/controllers/front_end_controller.h"

#include <utility>

#include "simulate/image_track_truth.h"
#include "ui/session/inspection_parameters.h"

namespace hull::ui {

const QString FrontEndController::kFeaturesJob = QStringLiteral("features");

namespace {
constexpr std::size_t kCacheSize = 4;  // front-end results kept (features of every keyframe each)
}

FrontEndController::FrontEndController(Session* session, JobRunner* jobs, QObject* parent)
    : QObject(parent), session_(session), jobs_(jobs), values_(DefaultValues(DefaultParameterTable())) {
  connect(session_, &Session::surveyChanged, this, &FrontEndController::OnSurveyChanged);
  connect(jobs_, &JobRunner::jobStarted, this, [this] { emit stateChanged(); });
  connect(jobs_, &JobRunner::jobCancelled, this, [this] { emit stateChanged(); });
  connect(jobs_, &JobRunner::jobFailed, this, [this] { emit stateChanged(); });
}

void FrontEndController::OnSurveyChanged() {
  ++generation_;
  jobs_->Cancel(kFeaturesJob);
  cache_.clear();
  order_.clear();
  source_ = session_->survey() ? session_->survey()->bundle : nullptr;
  if (automatic_ && session_->NeedsFeatureExtraction()) Extract();
  emit stateChanged();
}

void FrontEndController::SetParameters(const ParameterValues& values) {
  const bool changed = FrontEndKey(values) != FrontEndKey(values_);
  values_ = values;
  if (!changed || !session_->frontEnd()) return;  // features not from the images: nothing to redo
  Extract();
}

bool FrontEndController::CanExtract() const { return source_ && source_->images && source_->images->present() > 0; }

bool FrontEndController::busy() const { return jobs_->IsBusy(kFeaturesJob); }

void FrontEndController::Cancel() { jobs_->Cancel(kFeaturesJob); }

void FrontEndController::Apply(const Entry& entry) {
  session_->SetExtractedFeatures(entry.bundle, entry.overlays, entry.result);
  emit stateChanged();
}

void FrontEndController::Extract() {
  if (!CanExtract()) return;
  const std::string key = FrontEndKey(values_).toStdString();
  if (auto it = cache_.find(key); it != cache_.end()) {
    jobs_->Cancel(kFeaturesJob);
    Apply(it->second);
    return;
  }
  const FrontEndOptions options = FrontEndOptionsFrom(values_);
  const std::shared_ptr<const SurveyBundle> source = source_;
  const quint64 generation = generation_;
  jobs_->Run<Entry>(
      kFeaturesJob, QStringLiteral("Extract features from %1 images").arg(source->images->present()),
      [source, options](Progress& progress) {
        auto bundle = std::make_shared<SurveyBundle>(*source);
        bundle->features.clear();
        SubProgress p(progress, 0.0, 0.95);
        auto result = std::make_shared<const FrontEndResult>(RunFrontEnd(*bundle, options, p));
        progress.Update(0.96, "preparing the features for display");
        bundle->AdoptImageFeatureTracks(result->features);
        if (bundle->truth) {
          try {
            AttachImageTrackTruth(*bundle);  // a simulated survey: the new tracks' truth from its scene
          } catch (const InputError&) {
            // an unreadable truth/scene.ply: the tracks simply have no truth to show
          }
        }
        Entry e;
        e.overlays = std::make_shared<const SurveyOverlays>(ComputeSurveyOverlays(*bundle));
        e.bundle = std::move(bundle);
        e.result = std::move(result);
        progress.Update(1.0, "features extracted");
        return e;
      },
      [this, generation, key](Entry& e) {
        if (generation != generation_) return;  // another survey since
        if (!cache_.count(key)) order_.push_back(key);
        cache_[key] = e;
        while (cache_.size() > kCacheSize) {
          cache_.erase(order_.front());
          order_.pop_front();
        }
        if (key == FrontEndKey(values_).toStdString()) Apply(e);
      });
  emit stateChanged();
}

}  // namespace hull::ui
