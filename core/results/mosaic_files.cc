#include "results/mosaic_files.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "geometry/mesh_io.h"
#include "image/image_file.h"
#include "results/adjustment_files.h"

namespace hull {
namespace fs = std::filesystem;
namespace {

Json Count(std::size_t n) { return Json(static_cast<std::int64_t>(n)); }

std::string ObjText(const MosaicResult& r) {
  std::string s = "# HullInspect photomosaic: the remeshed model in M (metres), textured with ";
  s += kMosaicAtlas;
  s += "\nmtllib ";
  s += kMosaicMtl;
  s += "\n";
  for (const Eigen::Vector3d& v : r.model.vertices) {
    s += "v ";
    AppendDouble(s, v.x());
    s += ' ';
    AppendDouble(s, v.y());
    s += ' ';
    AppendDouble(s, v.z());
    s += '\n';
  }
  for (std::size_t f = 0; f < r.model.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2f uv = r.Uv(static_cast<int>(f), c);
      s += "vt ";
      AppendDouble(s, uv.x());
      s += ' ';
      AppendDouble(s, uv.y());
      s += '\n';
    }
  }
  s += "usemtl mosaic\n";
  for (std::size_t f = 0; f < r.model.num_faces(); ++f) {
    const Face& F = r.model.faces[f];
    s += 'f';
    for (int c = 0; c < 3; ++c) {
      s += ' ' + std::to_string(F[c] + 1) + '/' + std::to_string(3 * f + static_cast<std::size_t>(c) + 1);
    }
    s += '\n';
  }
  return s;
}

std::string PlyBytes(const MosaicResult& r) {
  const TriangleMesh& m = r.model;
  std::string s =
      "ply\nformat binary_little_endian 1.0\n"
      "comment HullInspect photomosaic: per-vertex colour = estimated albedo x 255 (area-weighted over the faces)\n"
      "element vertex " +
      std::to_string(m.num_vertices()) +
      "\nproperty double x\nproperty double y\nproperty double z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face " +
      std::to_string(m.num_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  static_assert(sizeof(double) == 8 && sizeof(int) == 4, "PLY types");
  const auto ch = static_cast<std::size_t>(r.channels);
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    char buf[27];
    std::memcpy(buf, m.vertices[v].data(), 24);
    for (std::size_t c = 0; c < 3; ++c) {
      // BGR atlas order for colour images; grey repeats.
      const float x = r.vertex_values[v * ch + (ch == 3 ? 2 - c : 0)];
      buf[24 + c] = static_cast<char>(static_cast<std::uint8_t>(std::clamp(x * 255.0f + 0.5f, 0.0f, 255.0f)));
    }
    s.append(buf, sizeof buf);
  }
  for (const Face& F : m.faces) {
    char buf[13];
    buf[0] = 3;
    for (int c = 0; c < 3; ++c) {
      const std::int32_t i = F[c];
      std::memcpy(buf + 1 + 4 * c, &i, 4);
    }
    s.append(buf, sizeof buf);
  }
  return s;
}

std::string FacesCsv(const MosaicResult& r) {
  CsvWriter w({"face", "keyframe", "camera", "score", "candidates", "value", "truth", "error", "mean_error"});
  auto opt = [](float x) { return std::isnan(x) ? std::optional<double>() : std::optional<double>(x); };
  for (std::size_t f = 0; f < r.faces.size(); ++f) {
    const MosaicFace& F = r.faces[f];
    w.Add(static_cast<std::int64_t>(f));
    if (F.view >= 0) {
      const MosaicView& v = r.views[static_cast<std::size_t>(F.view)];
      w.Add(v.keyframe)
          .Add(v.bottom ? "bottom" : "top")
          .Add(F.score)
          .Add(F.candidates)
          .Add(static_cast<double>(F.albedo));
    } else {
      w.AddEmpty().AddEmpty().AddEmpty().Add(F.candidates).AddEmpty();
    }
    w.AddOptional(opt(F.truth)).AddOptional(opt(F.error)).AddOptional(opt(F.mean_error));
    w.EndRow();
  }
  return w.Take();
}

Json SummaryJson(const MosaicResult& r) {
  const MosaicSummary& s = r.summary;
  const MosaicOptions& o = r.options;
  Json doc = Json::Object();
  doc.Set("format", "hull-mosaic");
  doc.Set("version", 1);
  Json inputs = Json::Object();
  for (const auto& [k, v] : r.inputs) inputs.Set(k, v);
  doc.Set("inputs", inputs);
  Json opts = Json::Object();
  opts.Set("texel_size", o.texel_size);
  opts.Set("max_range", o.max_range);
  opts.Set("max_incidence_deg", o.max_incidence_deg);
  opts.Set("image_margin", o.image_margin);
  opts.Set("seam_weight", o.seam_weight);
  opts.Set("label_iterations", o.label_iterations);
  opts.Set("feather_rings", o.feather_rings);
  opts.Set("normalisation", MosaicNormalisationName(o.normalisation));
  opts.Set("attenuation", o.photometry.attenuation);
  opts.Set("backscatter", o.photometry.backscatter);
  opts.Set("vignetting", o.photometry.vignetting);
  opts.Set("exposure_level", o.photometry.exposure_level);
  opts.Set("exposure_range", o.photometry.exposure_range);
  opts.Set("strobes", static_cast<int>(o.photometry.strobes.size()));
  opts.Set("gain_prior_sigma", o.gain_prior_sigma);
  opts.Set("truth_samples", o.truth_samples);
  doc.Set("options", opts);
  Json sum = Json::Object();
  sum.Set("faces", Count(s.faces));
  sum.Set("faces_textured", Count(s.faces_textured));
  sum.Set("textured_area", s.textured_area);
  sum.Set("views", Count(r.views.size()));
  sum.Set("views_used", Count(s.views_used));
  sum.Set("interior_edges", Count(s.interior_edges));
  sum.Set("seam_edges", Count(s.seam_edges));
  Json atlas = Json::Object();
  atlas.Set("file", kMosaicAtlas);
  atlas.Set("width", r.atlas.cols);
  atlas.Set("height", r.atlas.rows);
  atlas.Set("channels", r.channels);
  atlas.Set("texel_size", s.texel_size);
  atlas.Set("fill", s.atlas_fill);
  sum.Set("atlas", atlas);
  Json gains = Json::Object();
  gains.Set("min", s.gain_min);
  gains.Set("median", s.gain_median);
  gains.Set("max", s.gain_max);
  sum.Set("gains", gains);
  Json secs = Json::Object();
  secs.Set("visibility", s.seconds.visibility);
  secs.Set("labelling", s.seconds.labelling);
  secs.Set("gains", s.seconds.gains);
  secs.Set("texturing", s.seconds.texturing);
  secs.Set("scoring", s.seconds.scoring);
  secs.Set("total", s.seconds.total);
  sum.Set("seconds", secs);
  doc.Set("summary", sum);
  if (s.faces_scored > 0) {
    Json e = Json::Object();
    e.Set("faces", Count(s.faces_scored));
    e.Set("error_median", s.error_median);
    e.Set("error_p95", s.error_p95);
    e.Set("mean_error_median", s.mean_error_median);
    e.Set("mean_error_p95", s.mean_error_p95);
    doc.Set("truth", e);
  } else {
    doc.Set("truth", Json());
  }
  Json views = Json::Array();
  for (const MosaicView& v : r.views) {
    Json j = Json::Object();
    j.Set("keyframe", v.keyframe);
    j.Set("camera", v.bottom ? "bottom" : "top");
    j.Set("gain", v.gain);
    j.Set("faces", v.faces);
    j.Set("candidates", v.candidates);
    views.Push(j);
  }
  doc.Set("views", views);
  doc.Set("files", Json::ArrayOf(std::vector<std::string>{kMosaicObj, kMosaicMtl, kMosaicAtlas, kMosaicPly, kMosaicJson,
                                                          kMosaicFacesCsv}));
  return doc;
}

// The model must have been mapped from the adjustment beside it: one run
// wrote both ('run'), or the mapping's run read that adjustment ('map').
void CheckModelOfAdjustment(const MosaicSources& s, const std::optional<ResultsManifest>& model_run) {
  const std::optional<ResultsManifest>& adj = s.adjustment_run;
  if (!adj && !model_run) return;
  if (adj && model_run) {
    if (adj->run.id == model_run->run.id) return;
    const ResultsInput* from = model_run->run.Input("adjustment");
    if (from && from->run == adj->run.id) return;
    throw InputError({s.model_path, 0, 0, ""},
                     "was mapped from another adjustment (" +
                         (from && !from->run.empty() ? "run " + from->run : std::string("of unknown origin")) +
                         ") than the one beside it in " + s.adjustment_dir + " (run " + adj->run.id +
                         "): the folder mixes results of different runs; run 'hullinspect-cli map' on it again");
  }
  const std::string managed = adj ? s.adjustment_dir : s.model_path;
  const std::string unmanaged = adj ? s.model_path : s.adjustment_dir;
  throw InputError({unmanaged, 0, 0, ""}, "is not listed in any results manifest, while " + managed +
                                              " is: the folder mixes results of different origins");
}

}  // namespace

MosaicSources LocateMosaicSources(const std::string& results) {
  const fs::path dir(results);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError({results, 0, 0, ""}, "not a results folder (no such folder)");
  MosaicSources s;
  if (fs::exists(dir / "adjustment" / "adjustment.json", ec)) {
    s.adjustment_dir = (dir / "adjustment").string();
  } else if (fs::exists(dir / "adjustment.json", ec)) {
    s.adjustment_dir = dir.string();
  } else {
    throw InputError({results, 0, 0, ""},
                     "holds neither adjustment/adjustment.json nor adjustment.json: not the results of 'run' or "
                     "'adjust'");
  }
  const fs::path model = dir / "mapping" / "model.ply";
  if (!fs::exists(model, ec)) {
    throw InputError({results, 0, 0, ""},
                     "holds no mapping/model.ply (the remeshed model): run 'hullinspect-cli map' on it first");
  }
  s.model_path = model.string();
  std::vector<std::string> adjustment_files;
  for (const std::string& name : AdjustmentFileNames())
    adjustment_files.push_back((fs::path(s.adjustment_dir) / name).string());
  s.adjustment_run = CheckResultsFiles(adjustment_files, "the adjustment in " + s.adjustment_dir);
  CheckModelOfAdjustment(s, CheckResultsFiles({s.model_path}, "the mapping in " + (dir / "mapping").string()));
  return s;
}

void WriteMosaic(const MosaicResult& r, const std::string& dir) {
  const fs::path t(dir);
  fs::create_directories(t);
  WriteImageFile((t / kMosaicAtlas).string(), r.atlas);
  WriteFileAtomic((t / kMosaicMtl).string(),
                  std::string("# HullInspect photomosaic\nnewmtl mosaic\nKa 1 1 1\nKd 1 1 1\n"
                              "Ks 0 0 0\nd 1\nillum 1\nmap_Kd ") +
                      kMosaicAtlas + "\n");
  WriteFileAtomic((t / kMosaicObj).string(), ObjText(r));
  WriteFileAtomic((t / kMosaicPly).string(), PlyBytes(r));
  WriteFileAtomic((t / kMosaicFacesCsv).string(), FacesCsv(r));
  WriteFileAtomic((t / kMosaicJson).string(), SummaryJson(r).Dump() + "\n");
}

void SaveMosaicResults(const MosaicResult& r, const OutputFolder& out, ResultsRun run) {
  for (const auto& [role, path] : r.inputs) {
    if (role == "bundle") {
      run.AddSurvey(role, path);
    } else if (role == "adjustment") {
      run.AddResults(role, path);
    } else if (role == "model") {
      run.AddFile(role, path);
    }
  }
  WriteResultsFolder(out, run, [&](const std::string& tmp) { WriteMosaic(r, tmp); });
}

std::optional<std::string> FindMosaicResults(const std::string& folder) {
  std::error_code ec;
  if (fs::is_regular_file(fs::path(folder) / kMosaicObj, ec)) return folder;
  const fs::path sub = fs::path(folder) / "mosaic";
  if (fs::is_regular_file(sub / kMosaicObj, ec)) return sub.string();
  return std::nullopt;
}

std::shared_ptr<const TriangleMesh> ReadMosaicColours(const std::string& mosaic_dir) {
  const fs::path ply = fs::path(mosaic_dir) / kMosaicPly;
  std::error_code ec;
  if (!fs::is_regular_file(ply, ec)) return nullptr;
  MeshLoadOptions read;  // the colours stay with their vertices
  read.weld = false;
  read.orient_outward = false;
  auto coloured = std::make_shared<TriangleMesh>(LoadMesh(ply.string(), read));
  for (const char* c : {"red", "green", "blue"}) {
    if (!coloured->FindScalar(c)) {
      throw InputError({ply.string(), 0, 0, c}, "a photomosaic needs per-vertex " + std::string(c));
    }
  }
  return coloured;
}

MosaicOnDisk ReadMosaicResults(const std::string& folder) {
  const std::optional<std::string> dir = FindMosaicResults(folder);
  if (!dir) {
    throw InputError({folder, 0, 0, ""}, std::string("holds no photomosaic: neither ") + kMosaicObj + " nor mosaic/" +
                                             kMosaicObj + " (write one with 'hullinspect-cli mosaic RESULTS')");
  }
  MosaicOnDisk m;
  m.dir = *dir;
  m.obj = (fs::path(*dir) / kMosaicObj).string();
  m.atlas = (fs::path(*dir) / kMosaicAtlas).string();
  std::error_code ec;
  if (!fs::is_regular_file(m.atlas, ec)) {
    throw InputError({*dir, 0, 0, ""}, std::string("has mosaic.obj but not its texture ") + kMosaicAtlas);
  }
  CheckResultsFiles({m.obj, m.atlas, (fs::path(*dir) / kMosaicPly).string(), (fs::path(*dir) / kMosaicJson).string()},
                    "the photomosaic in " + *dir);
  MeshLoadOptions read;
  read.weld = false;
  read.orient_outward = false;
  const TriangleMesh mesh = LoadMesh(m.obj, read);
  m.vertices = mesh.vertices.size();
  m.faces = mesh.faces.size();
  // The mosaic's model is in M: placed by the adjusted x_gM of the results
  // folder it was written into (RESULTS/mosaic by default).
  const std::string results = fs::absolute(fs::path(*dir), ec).parent_path().string();
  const MosaicSources sources = LocateMosaicSources(results);
  m.x_gM = Pose::FromVector(ReadAdjustmentResult(sources.adjustment_dir).x_gM);
  m.coloured = ReadMosaicColours(*dir);
  if (m.coloured) m.ply = (fs::path(*dir) / kMosaicPly).string();
  return m;
}

}  // namespace hull
