#include "ui/session/inspection_parameters.h"

#include <QStringList>
#include <cmath>
#include <functional>
#include <utility>

#include "base/error.h"
#include "mapping/mapping_options.h"
#include "ui/session/sonar_parameters.h"

namespace hull::ui {

namespace {

using Stage = ParameterDescriptor::Stage;

const QString kAdjust = QStringLiteral("Bundle adjustment");
const QString kSolver = QStringLiteral("Solver limits");
const QString kMap = QStringLiteral("Mapping");
const QString kFront = QStringLiteral("Visual front end");

using table::Choice;
using table::Integer;
using table::Real;

const SurfaceModel kModels[] = {SurfaceModel::kNaive, SurfaceModel::kAllOnSurface, SurfaceModel::kMaxMixture};

// The visual front end (core/vision/vision_options.h): only used for
// surveys whose features come from their images.
void AddFrontEndFields(ParameterTable& t) {
  const FrontEndOptions f;
  const Stage s = Stage::kFrontEnd;
  t.push_back(Integer(QStringLiteral("fe_max_features"), kFront, s, QStringLiteral("SIFT features per image"), 0,
                      100000, f.detection.max_features,
                      QStringLiteral("SIFT keeps the strongest this many features per image (0: all).")));
  t.push_back(Real(QStringLiteral("fe_contrast_threshold"), kFront, s, QStringLiteral("SIFT contrast threshold"), 0.001,
                   0.5, f.detection.contrast_threshold, 3, 0.005, {},
                   QStringLiteral("SIFT's contrast threshold: lower finds more, weaker features.")));
  t.push_back(Choice(QStringLiteral("fe_clahe"), kFront, s, QStringLiteral("CLAHE"),
                     {QStringLiteral("on"), QStringLiteral("off")}, {QStringLiteral("On"), QStringLiteral("Off")},
                     f.detection.clahe ? 0 : 1,
                     QStringLiteral("Contrast-limited adaptive histogram equalisation before SIFT, for the uneven "
                                    "strobe lighting.")));
  t.push_back(Real(QStringLiteral("fe_clahe_clip"), kFront, s, QStringLiteral("CLAHE clip limit"), 0.1, 40.0,
                   f.detection.clahe_clip, 2, 0.5, {},
                   QStringLiteral("CLAHE's cap on the contrast amplification (higher: more contrast and noise).")));
  t.push_back(Real(QStringLiteral("fe_epipolar_tolerance"), kFront, s, QStringLiteral("Stereo epipolar tolerance"), 0.1,
                   50.0, f.stereo.epipolar_tolerance, 2, 0.5, QStringLiteral("px"),
                   QStringLiteral("Greatest distance of a bottom feature from the top feature's epipolar line.")));
  t.push_back(Real(QStringLiteral("fe_stereo_ratio"), kFront, s, QStringLiteral("Stereo ratio test"), 0.05, 1.0,
                   f.stereo.ratio, 2, 0.05, {},
                   QStringLiteral("Lowe's ratio for top↔bottom matches: best / second-best descriptor distance.")));
  t.push_back(Integer(QStringLiteral("fe_neighbours"), kFront, s, QStringLiteral("Keyframes matched ahead"), 1, 50,
                      f.temporal.neighbours,
                      QStringLiteral("Each keyframe is matched with this many following keyframes.")));
  t.push_back(Real(QStringLiteral("fe_window"), kFront, s, QStringLiteral("Search window"), 1.0, 1000.0,
                   f.temporal.window, 1, 5.0, QStringLiteral("px"),
                   QStringLiteral("Radius around the position the navigation prior predicts in which a temporal "
                                  "match is searched (covers the navigation error).")));
  t.push_back(Real(QStringLiteral("fe_temporal_ratio"), kFront, s, QStringLiteral("Temporal ratio test"), 0.05, 1.0,
                   f.temporal.ratio, 2, 0.05, {},
                   QStringLiteral("Lowe's ratio among the candidates in the search window.")));
  t.push_back(Real(QStringLiteral("fe_ransac_threshold"), kFront, s, QStringLiteral("RANSAC threshold"), 0.05, 50.0,
                   f.temporal.ransac_threshold, 2, 0.25, QStringLiteral("px"),
                   QStringLiteral("Inlier reprojection error (stereo) or Sampson distance (mono) in RANSAC.")));
  t.push_back(Integer(QStringLiteral("fe_min_inliers"), kFront, s, QStringLiteral("Min. inliers per pair"), 5, 10000,
                      f.temporal.min_inliers, QStringLiteral("A keyframe pair with fewer RANSAC inliers is dropped.")));
  t.push_back(Integer(QStringLiteral("fe_min_keyframes"), kFront, s, QStringLiteral("Min. keyframes per track"), 2,
                      1000, f.tracks.min_keyframes, QStringLiteral("Tracks seen in fewer keyframes are dropped.")));
  t.push_back(Choice(QStringLiteral("fe_track_check"), kFront, s, QStringLiteral("DVL height check"),
                     {QStringLiteral("on"), QStringLiteral("off")}, {QStringLiteral("On"), QStringLiteral("Off")},
                     f.tracks.check_dvl_height ? 0 : 1,
                     QStringLiteral("Mono tracks of at most three keyframes are checked against the DVL's plane of "
                                    "the hull: a wrong two-view match triangulates far in front of or behind it.")));
  t.push_back(Real(QStringLiteral("fe_track_check_max_height"), kFront, s, QStringLiteral("Check: max. in front"), 0.01,
                   5.0, f.tracks.check_max_height, 3, 0.05, QStringLiteral("m"),
                   QStringLiteral("A checked track standing farther than this in front of every member's DVL plane is "
                                  "dropped (foreign objects stand at most about 0.2 m off the hull).")));
  t.push_back(Real(QStringLiteral("fe_track_check_min_height"), kFront, s, QStringLiteral("Check: max. behind"), -5.0,
                   -0.001, f.tracks.check_min_height, 3, 0.05, QStringLiteral("m"),
                   QStringLiteral("A checked track standing farther than this behind every member's DVL plane (inside "
                                  "the hull) is dropped; negative.")));
  t.push_back(
      Choice(QStringLiteral("fe_refine"), kFront, s, QStringLiteral("Sub-pixel refinement"),
             {QStringLiteral("on"), QStringLiteral("off")}, {QStringLiteral("On"), QStringLiteral("Off")},
             f.tracks.refine ? 0 : 1,
             QStringLiteral("Each track's features are aligned to its first feature's image patch (shift, "
                            "gain, bias): two-view tracks then triangulate millimetres, not centimetres, off.")));
  t.push_back(Real(QStringLiteral("fe_refine_max_shift"), kFront, s, QStringLiteral("Refinement: max. shift"), 0.1,
                   32.0, f.tracks.refine_max_shift, 2, 0.5, QStringLiteral("px"),
                   QStringLiteral("An alignment moving a feature farther than this keeps the detector's pixel.")));
  t.push_back(Real(QStringLiteral("fe_refine_min_ncc"), kFront, s, QStringLiteral("Refinement: min. correlation"), -1.0,
                   1.0, f.tracks.refine_min_ncc, 2, 0.05, {},
                   QStringLiteral("An alignment whose patches correlate less than this (weighted NCC) keeps the "
                                  "detector's pixel.")));
}

// The photomosaic (core/mosaic/photomosaic.h): used by the next Inspection >
// Build photomosaic; a change re-runs nothing.
void AddMosaicFields(ParameterTable& t) {
  const MosaicOptions m;
  const QString g = QStringLiteral("Photomosaic");
  const Stage s = Stage::kNone;
  t.push_back(Real(QStringLiteral("mosaic_texel_size"), g, s, QStringLiteral("Texel size"), 0.0005, 0.1, m.texel_size,
                   4, 0.001, QStringLiteral("m"),
                   QStringLiteral("Surface length of one atlas texel (it grows by 25 % steps when the atlas "
                                  "would exceed 16384 pixels).")));
  t.push_back(Real(QStringLiteral("mosaic_max_incidence_deg"), g, s, QStringLiteral("Max. incidence"), 1.0, 89.0,
                   m.max_incidence_deg, 1, 1.0, QStringLiteral("°"),
                   QStringLiteral("A view seeing a face more obliquely than this (from its normal) cannot texture "
                                  "it.")));
  t.push_back(Real(QStringLiteral("mosaic_seam_weight"), g, s, QStringLiteral("Seam weight"), 0.0, 10.0, m.seam_weight,
                   2, 0.1, {},
                   QStringLiteral("Cost of a seam between neighbouring faces against −ln of their score ratio: "
                                  "higher keeps larger regions on one image (0: the best view per face).")));
  t.push_back(Integer(QStringLiteral("mosaic_feather_rings"), g, s, QStringLiteral("Feathering rings"), 0, 50,
                      m.feather_rings,
                      QStringLiteral("One-rings of faces over which neighbouring images blend at a seam (0: hard "
                                     "seams).")));
  t.push_back(Choice(
      QStringLiteral("mosaic_normalisation"), g, s, QStringLiteral("Normalisation"),
      {QStringLiteral("gains"), QStringLiteral("model"), QStringLiteral("none")},
      {QStringLiteral("Model and gains"), QStringLiteral("Photometric model"), QStringLiteral("None (raw pixels)")},
      m.normalisation == MosaicNormalisation::kModelAndGains ? 0
      : m.normalisation == MosaicNormalisation::kModel       ? 1
                                                             : 2,
      QStringLiteral("How pixel values become albedo: the rig's strobe, water and vignetting undone, "
                     "then each image's gain levelled against its overlaps.")));
}

ParameterTable MakeTable() {
  const AdjustmentOptions a;
  ParameterTable t;
  QStringList model_keys, model_labels;
  int model_default = 0;
  for (int i = 0; i < 3; ++i) {
    model_keys << ModelKey(kModels[i]);
    model_labels << ModelLabel(kModels[i]);
    if (kModels[i] == a.model) model_default = i;
  }
  t.push_back(Choice(QStringLiteral("model"), kAdjust, Stage::kAdjustment, QStringLiteral("Surface model"), model_keys,
                     model_labels, model_default,
                     QStringLiteral("How features relate to the CAD surface: ignored, all constrained to it, or each "
                                    "labelled on/off the surface by a max-mixture of the two Gaussians below.")));
  t.push_back(Real(QStringLiteral("sigma0"), kAdjust, Stage::kAdjustment, QStringLiteral("σ₀ (off surface)"), 0.01,
                   10.0, a.sigma0, 3, 0.05, QStringLiteral("m"),
                   QStringLiteral("Standard deviation of the surface constraint for features off the model "
                                  "(λ = 0). The paper uses 1 m; the value matters little.")));
  t.push_back(Real(QStringLiteral("sigma1"), kAdjust, Stage::kAdjustment, QStringLiteral("σ₁ (on surface)"), 0.001, 1.0,
                   a.sigma1, 3, 0.005, QStringLiteral("m"),
                   QStringLiteral("Standard deviation of the surface constraint for features on the model "
                                  "(λ = 1). With σ₀ = 1 m, σ₁ = 2 cm puts the decision boundary at about ±5.6 cm, "
                                  "the smallest object found; 1–5 cm suits ship hulls.")));
  t.push_back(Choice(QStringLiteral("labels"), kAdjust, Stage::kAdjustment, QStringLiteral("Labels judged by"),
                     {QStringLiteral("cavity"), QStringLiteral("estimate")},
                     {QStringLiteral("Observations alone (cavity)"), QStringLiteral("Current estimate (the paper)")},
                     a.labels == LabelRule::kCavity ? 0 : 1,
                     QStringLiteral("The max-mixture's E-step. The paper labels a feature by its current estimate, "
                                    "which its own on-surface constraint has already pulled toward the hull, so a "
                                    "low object's features can stay labelled on the hull; the cavity rule judges a "
                                    "feature on the surface again by where its observations alone put it.")));
  t.push_back(Choice(QStringLiteral("lookup"), kAdjust, Stage::kAdjustment, QStringLiteral("Closest face by"),
                     {QStringLiteral("closest-face"), QStringLiteral("nearest-vertex")},
                     {QStringLiteral("Exact closest point"), QStringLiteral("Nearest vertex (the paper)")},
                     a.lookup == SurfaceLookup::kClosestFace ? 0 : 1,
                     QStringLiteral("How the signed distance h finds its face: the exact closest point, or the "
                                    "paper's nearest vertex and any adjacent face.")));
  t.push_back(Integer(QStringLiteral("max_iterations"), kSolver, Stage::kAdjustment, QStringLiteral("Iterations"), 1,
                      1000, a.max_iterations,
                      QStringLiteral("Levenberg–Marquardt iterations at most per solve before the solver stops.")));
  t.push_back(Integer(QStringLiteral("rejection_rounds"), kSolver, Stage::kAdjustment, QStringLiteral("Outlier rounds"),
                      0, 10, a.rejection_rounds,
                      QStringLiteral("How many times observations with large reprojection errors (wrong matches) "
                                     "are removed and the problem solved again; 0 keeps every observation.")));
  const MappingOptions m;
  t.push_back(Real(QStringLiteral("tau"), kMap, Stage::kMapping, QStringLiteral("τ (cluster threshold)"), 0.0, 1.0,
                   m.tau, 3, 0.01, QStringLiteral("m"),
                   QStringLiteral("Features whose |deviation| exceeds τ are clustered into shapes. 0 gives the "
                                  "most detail; 0.06 m fewer false positives.")));
  t.push_back(Real(QStringLiteral("shape_grow_height"), kMap, Stage::kMapping, QStringLiteral("Grow clusters above"),
                   0.0, 1.0, m.shape_grow_height, 3, 0.005, QStringLiteral("m"),
                   QStringLiteral("Hysteresis: a cluster grows through features standing above this and is kept "
                                  "when one of them exceeds τ, so a narrow lump whose top exceeds τ is shaped over "
                                  "its whole footprint. At or above τ: off (each feature cut at τ).")));
  t.push_back(Choice(QStringLiteral("peak_fit"), kMap, Stage::kMapping, QStringLiteral("Peak fit"),
                     {QStringLiteral("on"), QStringLiteral("off")}, {QStringLiteral("On"), QStringLiteral("Off")},
                     m.peak_fit ? 0 : 1,
                     QStringLiteral("Estimates each lump's apex beyond its highest feature by a local quadric fit "
                                    "of the features around it, accepted only when concave, inside the features, "
                                    "close to them and the same without any one feature (fusion along normals).")));
  t.push_back(Choice(QStringLiteral("shape_seed_across_views"), kMap, Stage::kMapping,
                     QStringLiteral("Seeds across views"), {QStringLiteral("on"), QStringLiteral("off")},
                     {QStringLiteral("On"), QStringLiteral("Off")}, m.shape_seed_across_views ? 0 : 1,
                     QStringLiteral("With the hysteresis: a keyframe's cluster that holds no feature above τ is "
                                    "still kept when one of its features belongs to another keyframe's cluster "
                                    "that does (a low lump's top seen above τ from one view only).")));
  t.push_back(Real(QStringLiteral("alpha"), kMap, Stage::kMapping, QStringLiteral("α (alpha shapes)"), 0.005, 2.0,
                   m.alpha, 3, 0.01, QStringLiteral("m"),
                   QStringLiteral("Radius of the alpha shapes meshed over each cluster: larger values bridge wider "
                                  "gaps between features.")));
  t.push_back(Real(QStringLiteral("dbscan_eps"), kMap, Stage::kMapping, QStringLiteral("DBSCAN ε"), 0.001, 2.0,
                   m.dbscan_eps, 3, 0.005, QStringLiteral("m"),
                   QStringLiteral("DBSCAN's neighbourhood radius over the features' camera-frame positions.")));
  t.push_back(Integer(QStringLiteral("dbscan_min_points"), kMap, Stage::kMapping, QStringLiteral("DBSCAN min. points"),
                      1, 1000, m.dbscan_min_points,
                      QStringLiteral("Points a cluster needs at least; fewer are noise (the paper uses 3).")));
  t.push_back(Real(QStringLiteral("object_min_height"), kMap, Stage::kMapping, QStringLiteral("Object height h_min"),
                   0.001, 1.0, m.object_min_height, 3, 0.005, QStringLiteral("m"),
                   QStringLiteral("A detected object is where the remeshed model stands more than this far off the "
                                  "CAD surface ...")));
  t.push_back(Real(QStringLiteral("object_min_area"), kMap, Stage::kMapping, QStringLiteral("Object min. area"), 0.0,
                   10.0, m.object_min_area, 3, 0.005, QStringLiteral("m²"),
                   QStringLiteral("... over at least this footprint area, ...")));
  t.push_back(Integer(QStringLiteral("object_min_features"), kMap, Stage::kMapping,
                      QStringLiteral("Object min. features"), 0, 100000, m.object_min_features,
                      QStringLiteral("... or, over a smaller footprint, held up by at least this many shaped features "
                                     "standing above h_min (0: the area test alone) ...")));
  t.push_back(Integer(QStringLiteral("object_min_views"), kMap, Stage::kMapping, QStringLiteral("Object min. views"), 1,
                      100000, m.object_min_views,
                      QStringLiteral("... that the shapes of at least this many keyframes hold.")));
  AddFrontEndFields(t);
  t.push_back(Real(QStringLiteral("significance_k"), kMap, Stage::kNone, QStringLiteral("Significance k"), 0.1, 10.0,
                   m.significance_k, 2, 0.1, {},
                   QStringLiteral("A deviation h is significant where |h| > k·σ, σ being the vertex's standard "
                                  "deviation from the adjustment (1.96: 95 % for a normal error). Changes the "
                                  "significance heatmap at once; nothing is re-run.")));
  AddMosaicFields(t);
  AddSonarFields(t);
  return t;
}

// Fields of one stage as "key=value" in table order; `skip` leaves some out.
QString StageText(const ParameterValues& values, Stage stage, const QStringList& skip = {}) {
  QStringList parts;
  for (const ParameterDescriptor& d : DefaultParameterTable()) {
    if (d.stage != stage || skip.contains(d.key)) continue;
    const QVariant v = values.value(d.key, d.DefaultValue());
    parts << d.key + QLatin1Char('=') +
                 (d.type == ParameterDescriptor::Type::kReal ? QString::number(v.toDouble(), 'g', 12) : v.toString());
  }
  return parts.join(QLatin1Char(';'));
}

}  // namespace

QString ModelKey(SurfaceModel model) { return QString::fromLatin1(SurfaceModelName(model)); }

QString ModelLabel(SurfaceModel model) {
  switch (model) {
    case SurfaceModel::kNaive:
      return QStringLiteral("Naive (no surface constraint)");
    case SurfaceModel::kAllOnSurface:
      return QStringLiteral("All on the surface (Geva et al.)");
    case SurfaceModel::kMaxMixture:
      return QStringLiteral("Max-mixture (Ozog et al.)");
  }
  return {};
}

SurfaceModel ModelFromKey(const QString& key) {
  for (SurfaceModel m : kModels) {
    if (ModelKey(m) == key) return m;
  }
  return SurfaceModel::kMaxMixture;
}

const ParameterTable& DefaultParameterTable() {
  static const ParameterTable table = MakeTable();
  return table;
}

std::vector<ParameterError> CheckDefaultParameters(const ParameterValues& values) {
  std::vector<ParameterError> errors = CheckAgainstTable(DefaultParameterTable(), values);
  if (!errors.empty()) return errors;
  const double sigma0 = values.value(QStringLiteral("sigma0")).toDouble();
  const double sigma1 = values.value(QStringLiteral("sigma1")).toDouble();
  if (!(sigma1 < sigma0)) {
    errors.push_back({QStringLiteral("sigma1"),
                      QStringLiteral("σ₁ must be smaller than σ₀ (%1 m): on-surface features are the tightly "
                                     "constrained ones")
                          .arg(sigma0)});
    return errors;
  }
  try {
    AdjustmentOptionsFrom(values).Check();
    MappingOptionsFrom(values).Check();
  } catch (const OptionError& e) {
    errors.push_back({QString::fromStdString(e.field()), QString::fromStdString(e.what())});
  }
  for (ParameterError& e : CheckSonarParameters(values)) errors.push_back(std::move(e));
  try {
    MosaicOptionsFrom(values).Check();
  } catch (const OptionError& e) {
    errors.push_back({QStringLiteral("mosaic_") + QString::fromStdString(e.field()), QString::fromStdString(e.what())});
  }
  // The front end's structs name their own fields ("ratio" twice): mapped
  // back to the table's keys.
  const FrontEndOptions f = FrontEndOptionsFrom(values);
  const std::pair<std::function<void()>, QString> checks[] = {
      {[&] { f.detection.Check(); }, QStringLiteral("fe_")},
      {[&] { f.stereo.Check(); }, QStringLiteral("fe_stereo_")},
      {[&] { f.temporal.Check(); }, QStringLiteral("fe_temporal_")},
      {[&] { f.tracks.Check(); }, QStringLiteral("fe_")}};
  for (const auto& [check, prefix] : checks) {
    try {
      check();
    } catch (const OptionError& e) {
      QString key = prefix + QString::fromStdString(e.field());
      if (!FindParameter(DefaultParameterTable(), key)) key = QStringLiteral("fe_") + QString::fromStdString(e.field());
      errors.push_back({key, QString::fromStdString(e.what())});
    }
  }
  return errors;
}

MosaicOptions MosaicOptionsFrom(const ParameterValues& values) {
  MosaicOptions o;
  auto real = [&](const char* key, double& field) { field = values.value(QLatin1String(key), field).toDouble(); };
  real("mosaic_texel_size", o.texel_size);
  real("mosaic_max_incidence_deg", o.max_incidence_deg);
  real("mosaic_seam_weight", o.seam_weight);
  o.feather_rings = values.value(QStringLiteral("mosaic_feather_rings"), o.feather_rings).toInt();
  const QString n = values.value(QStringLiteral("mosaic_normalisation"), QStringLiteral("gains")).toString();
  o.normalisation = n == QLatin1String("none")    ? MosaicNormalisation::kNone
                    : n == QLatin1String("model") ? MosaicNormalisation::kModel
                                                  : MosaicNormalisation::kModelAndGains;
  return o;
}

FrontEndOptions FrontEndOptionsFrom(const ParameterValues& values) {
  FrontEndOptions o;
  auto real = [&](const char* key, double& field) { field = values.value(QLatin1String(key), field).toDouble(); };
  auto integer = [&](const char* key, int& field) { field = values.value(QLatin1String(key), field).toInt(); };
  integer("fe_max_features", o.detection.max_features);
  real("fe_contrast_threshold", o.detection.contrast_threshold);
  o.detection.clahe = values.value(QStringLiteral("fe_clahe"), QStringLiteral("on")).toString() != QLatin1String("off");
  real("fe_clahe_clip", o.detection.clahe_clip);
  real("fe_epipolar_tolerance", o.stereo.epipolar_tolerance);
  real("fe_stereo_ratio", o.stereo.ratio);
  integer("fe_neighbours", o.temporal.neighbours);
  real("fe_window", o.temporal.window);
  real("fe_temporal_ratio", o.temporal.ratio);
  real("fe_ransac_threshold", o.temporal.ransac_threshold);
  integer("fe_min_inliers", o.temporal.min_inliers);
  integer("fe_min_keyframes", o.tracks.min_keyframes);
  o.tracks.check_dvl_height =
      values.value(QStringLiteral("fe_track_check"), QStringLiteral("on")).toString() != QLatin1String("off");
  real("fe_track_check_max_height", o.tracks.check_max_height);
  real("fe_track_check_min_height", o.tracks.check_min_height);
  o.tracks.refine = values.value(QStringLiteral("fe_refine"), QStringLiteral("on")).toString() != QLatin1String("off");
  real("fe_refine_max_shift", o.tracks.refine_max_shift);
  real("fe_refine_min_ncc", o.tracks.refine_min_ncc);
  return o;
}

QString FrontEndKey(const ParameterValues& values) { return StageText(values, Stage::kFrontEnd); }

AdjustmentOptions AdjustmentOptionsFrom(const ParameterValues& values) {
  AdjustmentOptions o;
  o.model = ModelFromKey(values.value(QStringLiteral("model")).toString());
  o.sigma0 = values.value(QStringLiteral("sigma0"), o.sigma0).toDouble();
  o.sigma1 = values.value(QStringLiteral("sigma1"), o.sigma1).toDouble();
  o.labels = values.value(QStringLiteral("labels")).toString() == QLatin1String("estimate") ? LabelRule::kEstimate
                                                                                            : LabelRule::kCavity;
  o.lookup = values.value(QStringLiteral("lookup")).toString() == QLatin1String("nearest-vertex")
                 ? SurfaceLookup::kNearestVertex
                 : SurfaceLookup::kClosestFace;
  o.max_iterations = values.value(QStringLiteral("max_iterations"), o.max_iterations).toInt();
  o.rejection_rounds = values.value(QStringLiteral("rejection_rounds"), o.rejection_rounds).toInt();
  return o;
}

MappingOptions MappingOptionsFrom(const ParameterValues& values) {
  MappingOptions o;
  o.tau = values.value(QStringLiteral("tau"), o.tau).toDouble();
  o.shape_grow_height = values.value(QStringLiteral("shape_grow_height"), o.shape_grow_height).toDouble();
  o.peak_fit =
      values.value(QStringLiteral("peak_fit"), o.peak_fit ? QStringLiteral("on") : QStringLiteral("off")).toString() ==
      QLatin1String("on");
  o.shape_seed_across_views = values
                                  .value(QStringLiteral("shape_seed_across_views"),
                                         o.shape_seed_across_views ? QStringLiteral("on") : QStringLiteral("off"))
                                  .toString() == QLatin1String("on");
  o.alpha = values.value(QStringLiteral("alpha"), o.alpha).toDouble();
  o.dbscan_eps = values.value(QStringLiteral("dbscan_eps"), o.dbscan_eps).toDouble();
  o.dbscan_min_points = values.value(QStringLiteral("dbscan_min_points"), o.dbscan_min_points).toInt();
  o.object_min_height = values.value(QStringLiteral("object_min_height"), o.object_min_height).toDouble();
  o.object_min_area = values.value(QStringLiteral("object_min_area"), o.object_min_area).toDouble();
  o.object_min_features = values.value(QStringLiteral("object_min_features"), o.object_min_features).toInt();
  o.object_min_views = values.value(QStringLiteral("object_min_views"), o.object_min_views).toInt();
  o.significance_k = values.value(QStringLiteral("significance_k"), o.significance_k).toDouble();
  return o;
}

QString AdjustmentKey(const ParameterValues& values) {
  QStringList skip;
  switch (ModelFromKey(values.value(QStringLiteral("model")).toString())) {
    case SurfaceModel::kNaive:
      skip << QStringLiteral("sigma0") << QStringLiteral("sigma1");
      break;
    case SurfaceModel::kAllOnSurface:
      skip << QStringLiteral("sigma0");
      break;
    case SurfaceModel::kMaxMixture:
      break;
  }
  return StageText(values, Stage::kAdjustment, skip);
}

QString MappingKey(const ParameterValues& values) {
  return AdjustmentKey(values) + QStringLiteral("|") + StageText(values, Stage::kMapping);
}

ParameterValues WithModel(const ParameterValues& values, SurfaceModel model) {
  ParameterValues v = values;
  v.insert(QStringLiteral("model"), ModelKey(model));
  return v;
}

}  // namespace hull::ui
