#include "results/alignment_file.h"

#include <cmath>

#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"

namespace hull {
namespace {

Json NumberOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(); }

Json VectorJson(const Vector6d& v) {
  Json a = Json::Array();
  for (int i = 0; i < 6; ++i) a.Push(Json(v[i]));
  return a;
}

Json Count(std::size_t n) { return Json(static_cast<std::int64_t>(n)); }

Json GicpJson(const GicpResult& g) {
  Json j = Json::Object();
  j.Set("status", GicpStatusName(g.status));
  j.Set("converged", g.converged);
  j.Set("iterations", g.iterations);
  j.Set("fitness", g.fitness);
  j.Set("correspondences", Count(g.correspondences));
  j.Set("source_points", Count(g.source_points));
  j.Set("target_points", Count(g.target_points));
  return j;
}

Json DvlJson(const ModelAlignment& a) {
  Json d = Json::Object();
  d.Set("returns", Count(a.dvl_points));
  d.Set("mesh_samples", Count(a.target_points));
  d.Set("residual_beams", Count(a.residual_beams));
  d.Set("residual_rms_before", a.residual_rms_before);
  d.Set("residual_rms_after", a.residual_rms_after);
  d.Set("surface_rms_before", a.surface_rms_before);
  d.Set("surface_rms_after", a.surface_rms_after);
  return d;
}

Json CoarseJson(const CoarseSearchReport& c) {
  Json j = Json::Object();
  j.Set("hypotheses", Count(c.hypotheses));
  j.Set("refined", Count(c.refined));
  j.Set("tied", Count(c.tied));
  j.Set("tied_position_spread", c.tied_position_spread);
  j.Set("tied_heading_spread_deg", c.tied_heading_spread_deg);
  j.Set("best_score", c.best_score);
  j.Set("start", VectorJson(c.start.ToVector()));
  return j;
}

// One row per beam with a return: keyframe, beam (1..4 as in dvl.csv),
// measured range, residual before, residual after (null: no hit).
Json ResidualRows(const ModelAlignment& a) {
  Json rows = Json::Array();
  for (const DvlBeamResidual& r : a.residuals) {
    Json row = Json::Array();
    row.Push(Json(r.keyframe));
    row.Push(Json(r.beam + 1));
    row.Push(Json(r.measured));
    row.Push(NumberOrNull(r.before));
    row.Push(NumberOrNull(r.after));
    rows.Push(row);
  }
  return rows;
}

Pose PoseOf(const JsonReader& r, const char* key) {
  const std::vector<double> v = r.Numbers(key, 6);
  return Pose::FromArray(v.data());
}

GicpStatus StatusOf(const JsonReader& g) {
  const std::string s = g.String("status");
  for (GicpStatus x :
       {GicpStatus::kConverged, GicpStatus::kMaxIterations, GicpStatus::kTooFewPoints, GicpStatus::kSolverFailed}) {
    if (s == GicpStatusName(x)) return x;
  }
  g.Fail(g.Required("status"), "status", "not a GICP status");
}

bool Bool(const JsonReader& r, const char* key) {
  const Json& v = r.Required(key);
  if (!v.is_bool()) r.Fail(v, key, "expected true or false");
  return v.as_bool();
}

void ReadResiduals(const JsonReader& root, ModelAlignment& a) {
  if (!root.Has("residuals")) return;
  const Json& rows = root.Required("residuals");
  if (!rows.is_array()) root.Fail(rows, "residuals", "expected an array");
  for (std::size_t i = 0; i < rows.items().size(); ++i) {
    const Json& row = rows.items()[i];
    const std::string key = "residuals[" + std::to_string(i) + "]";
    if (!row.is_array() || row.items().size() != 5)
      root.Fail(row, key, "expected [keyframe, beam, measured, before, after]");
    const auto number = [&](int k) {
      const Json& v = row.items()[static_cast<std::size_t>(k)];
      if (v.is_null() && k >= 3) return std::nan("");
      if (!v.is_number()) root.Fail(v, key, "expected numbers (null for a beam that misses the mesh)");
      return v.as_number();
    };
    a.residuals.push_back(
        {static_cast<std::int64_t>(number(0)), static_cast<int>(number(1)) - 1, number(2), number(3), number(4)});
  }
}

// Version 1 as the pipeline wrote it: flat keys.
void ReadFlat(const JsonReader& r, const Json& doc, ModelAlignment& a) {
  if (const Json* c = doc.Get("gicp_converged")) a.gicp.converged = c->as_bool();
  a.gicp.fitness = r.NumberOr("gicp_fitness", 0);
  a.dvl_points = static_cast<std::size_t>(r.NumberOr("dvl_points", 0));
  a.residual_rms_before = r.NumberOr("residual_rms_before", 0);
  a.residual_rms_after = r.NumberOr("residual_rms_after", 0);
}

void ReadNested(const JsonReader& r, ModelAlignment& a) {
  const JsonReader g = r.Object("gicp");
  a.gicp.status = StatusOf(g);
  a.gicp.converged = Bool(g, "converged");
  a.gicp.iterations = static_cast<int>(g.Integer("iterations"));
  a.gicp.fitness = g.Number("fitness");
  a.gicp.correspondences = static_cast<std::size_t>(g.Integer("correspondences"));
  a.gicp.source_points = static_cast<std::size_t>(g.Integer("source_points"));
  a.gicp.target_points = static_cast<std::size_t>(g.Integer("target_points"));
  const std::vector<double> o = r.Numbers("observability", 6);
  a.observability = Eigen::Map<const Vector6d>(o.data());
  const JsonReader d = r.Object("dvl");
  a.dvl_points = static_cast<std::size_t>(d.Integer("returns"));
  a.target_points = static_cast<std::size_t>(d.Integer("mesh_samples"));
  a.residual_beams = static_cast<std::size_t>(d.Integer("residual_beams"));
  a.residual_rms_before = d.Number("residual_rms_before");
  a.residual_rms_after = d.Number("residual_rms_after");
  a.surface_rms_before = d.Number("surface_rms_before");
  a.surface_rms_after = d.Number("surface_rms_after");
  if (const auto c = r.OptionalObject("coarse_search")) {
    a.coarse.ran = true;
    a.coarse.hypotheses = static_cast<std::size_t>(c->Integer("hypotheses"));
    a.coarse.refined = static_cast<std::size_t>(c->Integer("refined"));
    a.coarse.tied = static_cast<std::size_t>(c->Integer("tied"));
    a.coarse.tied_position_spread = c->Number("tied_position_spread");
    a.coarse.tied_heading_spread_deg = c->Number("tied_heading_spread_deg");
    a.coarse.best_score = c->Number("best_score");
    a.coarse.start = PoseOf(*c, "start");
  }
  ReadResiduals(r, a);
}

}  // namespace

std::string AlignmentJson(const ModelAlignment& a, const AlignmentSources& s) {
  Json j = Json::Object();
  j.Set("format", "hull-alignment");
  j.Set("version", 2);
  j.Set("bundle", s.bundle);
  j.Set("mesh", s.mesh);
  j.Set("mesh_scale", s.mesh_scale);
  j.Set("x_gM", VectorJson(a.x_gM.ToVector()));
  j.Set("initial_x_gM", VectorJson(a.initial_x_gM.ToVector()));
  j.Set("initial_from", a.coarse.ran ? "coarse_search" : "model_pose_guess");
  j.Set("gicp", GicpJson(a.gicp));
  j.Set("constrained_directions", a.constrained_directions);
  j.Set("observability", VectorJson(a.observability));
  j.Set("dvl", DvlJson(a));
  if (a.coarse.ran) j.Set("coarse_search", CoarseJson(a.coarse));
  j.Set("residual_columns", Json::ArrayOf(std::vector<std::string>{"keyframe", "beam", "measured", "before", "after"}));
  j.Set("residuals", ResidualRows(a));
  return j.Dump() + "\n";
}

void WriteAlignment(const ModelAlignment& a, const AlignmentSources& s, const std::string& path) {
  WriteFileAtomic(path, AlignmentJson(a, s));
}

ModelAlignment ReadAlignment(const std::string& path, AlignmentSources* sources) {
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader r(doc, path);
  if (r.String("format") != "hull-alignment") r.Fail(r.Required("format"), "format", "expected \"hull-alignment\"");
  const std::int64_t version = r.Integer("version");
  if (version != 1 && version != 2) r.Fail(r.Required("version"), "version", "unsupported; this reader knows 1 and 2");
  ModelAlignment a;
  a.x_gM = PoseOf(r, "x_gM");
  a.initial_x_gM = PoseOf(r, "initial_x_gM");
  a.constrained_directions = static_cast<int>(r.NumberOr("constrained_directions", 0));
  // Version 1 had two shapes: the pipeline's flat keys and align's nested ones.
  if (r.Has("gicp")) {
    ReadNested(r, a);
  } else {
    ReadFlat(r, doc, a);
  }
  if (sources) {
    sources->bundle = r.OptionalString("bundle").value_or("");
    sources->mesh = r.OptionalString("mesh").value_or("");
    sources->mesh_scale = r.NumberOr("mesh_scale", 1.0);
  }
  return a;
}

}  // namespace hull
