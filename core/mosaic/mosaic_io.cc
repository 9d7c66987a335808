#include "mosaic/mosaic_io.h"

#include <memory>
#include <unordered_map>

#include "base/error.h"
#include "survey/survey_images.h"

namespace hull {

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
  in.image_name = [b, ids](std::size_t k, bool bottom) { return b->ImagePath(ids[k], bottom); };
  return in;
}

}  // namespace hull
