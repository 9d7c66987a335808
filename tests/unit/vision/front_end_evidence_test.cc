// Evidence before results (issue 23, part 1): images that show nothing, pure
// noise, or a stereo rig whose top and bottom images were swapped stop the
// front end with InsufficientData naming the images folder and the likely
// cause, instead of running through to "0 objects detected".
#include "vision/front_end_evidence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <random>

#include "base/error.h"
#include "image/image_file.h"
#include "support/test_files.h"
#include "survey/survey_images.h"
#include "survey/survey_io.h"
#include "unit/vision/vision_scene.h"
#include "vision/front_end.h"

namespace hull {
namespace {
namespace fs = std::filesystem;
using testing::MakeVisionScene;
using testing::ScratchDir;
using testing::VisionScene;
using testing::WriteSceneBundle;

enum class Spoil { kNone, kBlack, kWhite, kNoise, kSwap, kBlackBottom };

// A stereo (or mono) scene bundle written to dir with its images spoiled.
SurveyBundle SpoiltBundle(const std::string& dir, bool stereo, Spoil spoil) {
  const VisionScene s = MakeVisionScene(stereo, false, 4);
  WriteSceneBundle(s, dir);
  std::mt19937 rng(3);
  for (const NavRecord& n : s.nav) {
    const fs::path top = fs::path(dir) / "images" / SurveyImageName(n.keyframe, false);
    const fs::path bottom = fs::path(dir) / "images" / SurveyImageName(n.keyframe, true);
    if (spoil == Spoil::kSwap) {
      fs::rename(top, fs::path(dir) / "images/tmp");
      fs::rename(bottom, top);
      fs::rename(fs::path(dir) / "images/tmp", bottom);
      continue;
    }
    for (const fs::path& p : {top, bottom}) {
      if (!stereo && p == bottom) continue;
      if (spoil == Spoil::kBlackBottom && p == top) continue;
      cv::Mat m = ReadImageFile(p.string());
      if (spoil == Spoil::kBlack || spoil == Spoil::kBlackBottom) m.setTo(0);
      if (spoil == Spoil::kWhite) m.setTo(255);
      if (spoil == Spoil::kNoise) cv::randu(m, 0, 256);
      if (spoil != Spoil::kNone) WriteImageFile(p.string(), m);
    }
  }
  return ReadSurveyBundle(dir);
}

std::string InsufficientMessage(const SurveyBundle& b) {
  NullProgress progress;
  try {
    RunFrontEnd(b, FrontEndOptions{}, progress);
  } catch (const InsufficientData& e) {
    EXPECT_EQ(e.stage(), "front end");
    EXPECT_EQ(e.where(), (fs::path(b.directory) / "images").string());
    return e.what();
  }
  ADD_FAILURE() << "the front end gave a result";
  return "";
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(FrontEndEvidence, AGoodSurveyPassesWithItsFiguresKept) {
  const ScratchDir dir("evidence_good");
  NullProgress progress;
  const FrontEndResult r = RunFrontEnd(SpoiltBundle(dir.path(), true, Spoil::kNone), FrontEndOptions{}, progress);
  EXPECT_EQ(r.evidence.top.images, 4);
  EXPECT_EQ(r.evidence.top.images_with_features, 4);
  EXPECT_EQ(r.evidence.bottom.images_with_features, 4);
  EXPECT_EQ(r.evidence.stereo_matched, r.evidence.stereo_keyframes);
  EXPECT_EQ(r.evidence.swap_probed, 4);  // every keyframe, 4 < kSwapProbeKeyframes
  EXPECT_EQ(r.evidence.swap_matched, 0);
  EXPECT_EQ(r.evidence.landmarks, r.landmarks);
  EXPECT_GE(r.landmarks, evidence::kMinLandmarks);
}

TEST(FrontEndEvidence, BlankImagesNameTheCamera) {
  for (const Spoil spoil : {Spoil::kBlack, Spoil::kWhite}) {
    const ScratchDir dir("evidence_blank");
    const std::string m = InsufficientMessage(SpoiltBundle(dir.path(), true, spoil));
    EXPECT_TRUE(Has(m, "the top camera's images show nothing")) << m;
    EXPECT_TRUE(Has(m, "none of its 4 images")) << m;
  }
  const ScratchDir dir("evidence_bottom");
  const std::string m = InsufficientMessage(SpoiltBundle(dir.path(), true, Spoil::kBlackBottom));
  EXPECT_TRUE(Has(m, "the bottom camera's images show nothing")) << m;
  const ScratchDir mono("evidence_mono");
  const std::string mm = InsufficientMessage(SpoiltBundle(mono.path(), false, Spoil::kBlack));
  EXPECT_TRUE(Has(mm, "the top camera's images show nothing")) << mm;
}

TEST(FrontEndEvidence, NoiseGivesNoTracks) {
  for (const bool stereo : {true, false}) {
    const ScratchDir dir("evidence_noise");
    const std::string m = InsufficientMessage(SpoiltBundle(dir.path(), stereo, Spoil::kNoise));
    EXPECT_TRUE(Has(m, "match nowhere") || Has(m, "tracks seen in two keyframes or more")) << m;
    EXPECT_FALSE(Has(m, "swapped")) << m;
  }
}

TEST(FrontEndEvidence, SwappedCamerasAreNamed) {
  const ScratchDir dir("evidence_swap");
  const std::string m = InsufficientMessage(SpoiltBundle(dir.path(), true, Spoil::kSwap));
  EXPECT_TRUE(Has(m, "the top and bottom images appear swapped")) << m;
  EXPECT_TRUE(Has(m, "_top/_bottom")) << m;
}

// The rules on their own, on figures made by hand.
TEST(FrontEndEvidenceRules, SwapNeedsMostProbesToMatchTwiceAsWellExchanged) {
  FrontEndEvidence e;
  EXPECT_NO_THROW(CheckSwapEvidence(e, {}, "images"));  // mono: nothing probed
  EXPECT_NO_THROW(CheckSwapEvidence(e, {{350, 40}, {300, 35}, {320, 50}}, "images"));
  EXPECT_EQ(e.swap_probed, 3);
  EXPECT_EQ(e.swap_matched, 0);
  // Two of five probes (a repetitive texture) are not enough.
  EXPECT_NO_THROW(CheckSwapEvidence(e, {{40, 300}, {45, 310}, {300, 40}, {310, 30}, {290, 41}}, "images"));
  EXPECT_EQ(e.swap_matched, 2);
  try {
    CheckSwapEvidence(e, {{40, 300}, {45, 310}, {50, 320}, {310, 30}, {290, 41}}, "images");
    ADD_FAILURE() << "accepted";
  } catch (const InsufficientData& x) {
    EXPECT_TRUE(Has(x.what(), "appear swapped")) << x.what();
    EXPECT_TRUE(Has(x.what(), "3 of 5")) << x.what();
  }
  // Exchanged matches below kMinStereoMatches are no evidence of a swap.
  EXPECT_NO_THROW(CheckSwapEvidence(e, {{0, 5}, {1, 6}, {0, 4}}, "images"));
}

TEST(FrontEndEvidenceRules, StereoPairsMustMatchInOneKeyframeOfTen) {
  FrontEndResult r;
  r.keyframes.resize(10);
  for (FrontEndKeyframe& k : r.keyframes) {
    k.has_top = k.has_bottom = true;
    k.top_features = k.bottom_features = 100;
    k.stereo_matches = 2;
  }
  FrontEndEvidence e = ImageEvidence(r, true);
  EXPECT_EQ(e.stereo_keyframes, 10);
  EXPECT_EQ(e.stereo_matched, 0);
  try {
    CheckImageEvidence(e, true, "images");
    ADD_FAILURE() << "accepted";
  } catch (const InsufficientData& x) {
    EXPECT_TRUE(Has(x.what(), "the stereo pairs match nowhere")) << x.what();
  }
  EXPECT_NO_THROW(CheckImageEvidence(e, false, "images"));  // mono: no stereo rule
  r.keyframes[0].stereo_matches = evidence::kMinStereoMatches;
  e = ImageEvidence(r, true);
  EXPECT_NO_THROW(CheckImageEvidence(e, true, "images"));
  e.landmarks = evidence::kMinLandmarks - 1;
  EXPECT_THROW(CheckTrackEvidence(e, "images"), InsufficientData);
  e.landmarks = evidence::kMinLandmarks;
  EXPECT_NO_THROW(CheckTrackEvidence(e, "images"));
}

}  // namespace
}  // namespace hull
