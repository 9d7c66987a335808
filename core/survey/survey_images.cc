#include "survey/survey_images.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <regex>

#include "base/file_io.h"

namespace hull {
namespace {
namespace fs = std::filesystem;

constexpr int kNamedDrops = 20;  // dropped frames listed one by one; the rest are counted
const char kNamingRule[] = "expected <keyframe>_top.png or <keyframe>_bottom.png (or .jpg), the keyframe as in nav.csv";

}  // namespace

std::string SurveyImageName(std::int64_t keyframe, bool bottom_camera, const std::string& extension) {
  return std::to_string(keyframe) + (bottom_camera ? "_bottom" : "_top") + extension;
}

SurveyImages ListSurveyImages(const std::string& bundle_dir, const SurveyManifest& manifest,
                              const std::vector<NavRecord>& nav, const std::unordered_set<std::int64_t>& unreadable,
                              std::vector<Problem>& problems) {
  const fs::path folder = fs::path(bundle_dir) / "images";
  const std::string folder_name = folder.string();
  const bool stereo = manifest.camera.stereo();
  auto error = [&](const std::string& file, const std::string& message) {
    problems.push_back({{(folder / file).string(), 0, 0, ""}, message, Severity::kError});
  };
  auto warning = [&](const SourceLocation& where, const std::string& message) {
    problems.push_back({where, message, Severity::kWarning});
  };

  std::unordered_set<std::int64_t> keyframes;
  for (const NavRecord& n : nav) keyframes.insert(n.keyframe);
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code type_ec;
    if (!it->is_regular_file(type_ec)) {
      warning({it->path().string(), 0, 0, ""}, "ignored: not a regular file (" + std::string(kNamingRule) + ")");
      continue;
    }
    names.push_back(it->path().filename().string());
  }
  if (ec) problems.push_back({{folder_name, 0, 0, ""}, "cannot list the folder: " + ec.message(), Severity::kError});
  std::sort(names.begin(), names.end());  // reports in a stable order

  static const std::regex pattern(R"(^([+-]?[0-9]+)_(top|bottom)\.(png|jpg)$)");
  std::unordered_map<std::int64_t, KeyframeImages> found;
  for (const std::string& name : names) {
    std::smatch m;
    if (!std::regex_match(name, m, pattern)) {
      const std::string ext = AsciiLower(fs::path(name).extension().string());
      if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") {
        error(name, std::string("not a valid image name: ") + kNamingRule);
      } else {
        warning({(folder / name).string(), 0, 0, ""},
                std::string("ignored: not an image of the bundle (") + kNamingRule + ")");
      }
      continue;
    }
    const std::string id_text = m[1].str();
    std::int64_t id = 0;
    const char* first = id_text.data() + (id_text[0] == '+' ? 1 : 0);
    const auto parsed = std::from_chars(first, id_text.data() + id_text.size(), id);
    if (parsed.ec != std::errc() || std::to_string(id) != id_text) {
      error(name, "the keyframe id is written '" + id_text + "'; expected it as nav.csv writes it" +
                      (parsed.ec == std::errc() ? " ('" + std::to_string(id) + "', no padding or sign)" : ""));
      continue;
    }
    if (!keyframes.count(id)) {
      if (!unreadable.count(id)) error(name, "keyframe " + id_text + " is not in nav.csv");
      continue;
    }
    const bool bottom = m[2].str() == "bottom";
    if (bottom && !stereo) {
      error(name, "a monocular survey has no bottom camera (camera.type in survey.json is \"mono\")");
      continue;
    }
    KeyframeImages& k = found[id];
    std::string& slot = bottom ? k.bottom : k.top;
    if (!slot.empty()) {
      error(name, "a second image for keyframe " + id_text + "'s " + (bottom ? "bottom" : "top") + " camera (also " +
                      fs::path(slot).filename().string() + ")");
      continue;
    }
    slot = "images/" + name;
  }

  SurveyImages out;
  for (const NavRecord& n : nav) {
    KeyframeImages k = found.count(n.keyframe) ? found[n.keyframe] : KeyframeImages{};
    k.keyframe = n.keyframe;
    for (bool bottom : {false, true}) {
      if (bottom && !stereo) continue;
      ++out.expected;
      if (!(bottom ? k.bottom : k.top).empty()) continue;
      if (++out.dropped <= kNamedDrops) {
        warning({folder_name, 0, 0, SurveyImageName(n.keyframe, bottom)},
                "dropped frame: keyframe " + std::to_string(n.keyframe) + " has no " + (bottom ? "bottom" : "top") +
                    " image; its other measurements still count");
      }
    }
    out.frames.push_back(std::move(k));
  }
  if (out.dropped > 0) {
    warning({folder_name, 0, 0, ""},
            std::to_string(out.dropped) + " of " + std::to_string(out.expected) + " images missing (dropped frames)" +
                (out.dropped > kNamedDrops ? "; the first " + std::to_string(kNamedDrops) + " are listed above" : ""));
  }
  return out;
}

ImageRequirements SurveyImageRequirements(const SurveyManifest& manifest) {
  ImageRequirements r;
  r.width = manifest.camera.width;
  r.height = manifest.camera.height;
  r.size_source = "camera.width x camera.height in survey.json";
  return r;
}

std::optional<ImageInfo> CheckSurveyImages(const std::string& bundle_dir, const SurveyManifest& manifest,
                                           const SurveyImages& images, std::vector<Problem>& problems) {
  std::vector<std::string> paths;
  for (const KeyframeImages& k : images.frames) {
    for (const std::string* rel : {&k.top, &k.bottom}) {
      if (!rel->empty()) paths.push_back((fs::path(bundle_dir) / *rel).string());
    }
  }
  const ImageRequirements size = SurveyImageRequirements(manifest);
  std::vector<std::optional<ImageInfo>> infos(paths.size());
  std::vector<std::optional<Problem>> errors(paths.size());
  // Every image decoded: only the decoder proves the compressed data sound.
  tbb::parallel_for(std::size_t{0}, paths.size(), [&](std::size_t i) {
    try {
      ImageInfo info;
      ReadImageFile(paths[i], size, &info);
      infos[i] = info;
    } catch (const InputError& e) {
      errors[i] = Problem{e.where(), e.detail(), Severity::kError};
    }
  });
  std::optional<ImageInfo> first;
  ImageRequirements layout;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (errors[i]) {
      problems.push_back(*errors[i]);
      continue;
    }
    if (!first) {
      first = infos[i];
      layout.same_layout_as = first;
      layout.layout_source = fs::path(paths[i]).lexically_relative(bundle_dir).string();
      continue;
    }
    try {
      CheckImageRequirements(*infos[i], paths[i], layout);
    } catch (const InputError& e) {
      problems.push_back({e.where(), e.detail(), Severity::kError});
    }
  }
  return first;
}

cv::Mat ReadSurveyImage(const SurveyBundle& bundle, std::int64_t keyframe, bool bottom_camera,
                        const std::optional<ImageInfo>& same_layout_as, ImageInfo* info) {
  const std::string path = bundle.ImagePath(keyframe, bottom_camera);
  if (path.empty()) {
    throw InputError({(fs::path(bundle.directory) / "images").string(), 0, 0, SurveyImageName(keyframe, bottom_camera)},
                     "keyframe " + std::to_string(keyframe) + " has no " + (bottom_camera ? "bottom" : "top") +
                         " image (a dropped frame)");
  }
  ImageRequirements r = SurveyImageRequirements(bundle.manifest);
  r.same_layout_as = same_layout_as;
  return ReadImageFile(path, r, info);
}

}  // namespace hull
