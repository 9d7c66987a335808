#include "mosaic/mosaic_io.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "base/atomic_directory.h"
#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "image/image_file.h"
#include "survey/survey_images.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

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
  return s;
}

MosaicInput MosaicInputFromAdjustment(const AdjustmentResult& a, const SurveyBundle& bundle, TriangleMesh model) {
  if (!bundle.images || bundle.images->present() == 0) {
    throw InputError({bundle.directory, 0, 0, "images"}, "the survey bundle has no camera images to texture with");
  }
  MosaicInput in;
  in.manifest = bundle.manifest;
  in.keyframes = a.keyframes;
  in.poses = a.poses;
  in.servo = a.servo;
  in.x_gM = a.x_gM;
  in.x_s_cT = a.x_s_cT;
  in.model = std::move(model);
  auto frames = std::make_shared<std::vector<const KeyframeImages*>>();
  std::unordered_map<std::int64_t, const KeyframeImages*> by_id;
  for (const KeyframeImages& f : bundle.images->frames) by_id[f.keyframe] = &f;
  for (std::int64_t k : a.keyframes) {
    const auto it = by_id.find(k);
    frames->push_back(it == by_id.end() ? nullptr : it->second);
  }
  in.has_image = [frames](std::size_t k, bool bottom) {
    const KeyframeImages* f = (*frames)[k];
    return f && !(bottom ? f->bottom : f->top).empty();
  };
  const SurveyBundle* b = &bundle;
  const std::vector<std::int64_t> ids = a.keyframes;
  in.read_image = [b, ids](std::size_t k, bool bottom) { return ReadSurveyImage(*b, ids[k], bottom); };
  return in;
}

void WriteMosaic(const MosaicResult& r, const std::string& dir) {
  WriteDirectoryAtomic(dir, [&](const std::string& tmp) {
    const fs::path t(tmp);
    WriteImageFile((t / kMosaicAtlas).string(), r.atlas);
    WriteFileAtomic((t / kMosaicMtl).string(),
                    std::string("# HullInspect photomosaic\nnewmtl mosaic\nKa 1 1 1\nKd 1 1 1\n"
                                "Ks 0 0 0\nd 1\nillum 1\nmap_Kd ") +
                        kMosaicAtlas + "\n");
    WriteFileAtomic((t / kMosaicObj).string(), ObjText(r));
    WriteFileAtomic((t / kMosaicPly).string(), PlyBytes(r));
    WriteFileAtomic((t / kMosaicFacesCsv).string(), FacesCsv(r));
    WriteFileAtomic((t / kMosaicJson).string(), SummaryJson(r).Dump() + "\n");
  });
}

}  // namespace hull
