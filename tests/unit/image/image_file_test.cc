// Image files: every supported layout round-trips exactly, and every damaged
// or unexpected file is refused with an InputError naming it -- in
// particular a file cut short at any byte, which libjpeg would otherwise
// decode into a grey-filled image with only a warning.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "base/error.h"
#include "image/image_file.h"
#include "support/test_files.h"
#include "support/test_images.h"

namespace hull {
namespace {
namespace fs = std::filesystem;
using testing::HandMadePng;
using testing::PatternImage;
using testing::ReadText;
using testing::ScratchDir;
using testing::WriteText;

// The message of the InputError `f` throws (fails the test when none is
// thrown or the error does not name `file`).
template <typename F>
std::string InputErrorOf(F&& f, const std::string& file) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, file) << e.what();
    return e.detail();
  }
  ADD_FAILURE() << "no InputError for " << file;
  return "";
}

bool SamePixels(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

class ImageFileTest : public ::testing::Test {
 protected:
  ScratchDir dir_{"image"};
};

TEST_F(ImageFileTest, PngLayoutsRoundTripExactly) {
  for (int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_16UC3}) {
    const cv::Mat image = PatternImage(37, 23, type, type);
    const std::string path = dir_ / ("t" + std::to_string(type) + ".png");
    WriteImageFile(path, image);
    ImageInfo info;
    const cv::Mat back = ReadImageFile(path, {}, &info);
    EXPECT_TRUE(SamePixels(image, back)) << "type " << type;
    EXPECT_EQ(info.codec, ImageCodec::kPng);
    EXPECT_EQ(info.width, 37);
    EXPECT_EQ(info.height, 23);
    EXPECT_EQ(info.bit_depth, CV_MAT_DEPTH(type) == CV_16U ? 16 : 8);
    EXPECT_EQ(info.channels, CV_MAT_CN(type));
    EXPECT_EQ(info.CvType(), type);
    const ImageInfo header = InspectImageFile(path);
    EXPECT_EQ(header.Describe(), info.Describe());
  }
  // 16-bit values above 255 survive (not squeezed into 8 bits).
  cv::Mat deep(4, 4, CV_16UC1, cv::Scalar(40000));
  WriteImageFile(dir_ / "deep.png", deep);
  EXPECT_EQ(ReadImageFile(dir_ / "deep.png").at<std::uint16_t>(2, 2), 40000);
}

// Huffman-only coding (the simulator's renderings): still an exact PNG, and
// on sensor-like noise smaller than the default strategy at the same level.
TEST_F(ImageFileTest, HuffmanOnlyPngRoundTripsAndIsSmallerOnNoise) {
  cv::Mat noise(96, 128, CV_8UC1);
  cv::randn(noise, cv::Scalar(120), cv::Scalar(12));  // cv::theRNG's fixed default seed
  ImageWriteOptions huffman;
  huffman.png_huffman_only = true;
  const std::string path = dir_ / "noise.png";
  WriteImageFile(path, noise, huffman);
  ImageInfo info;
  EXPECT_TRUE(SamePixels(noise, ReadImageFile(path, {}, &info)));
  EXPECT_EQ(info.codec, ImageCodec::kPng);
  EXPECT_EQ(info.bit_depth, 8);
  EXPECT_EQ(info.channels, 1);
  EXPECT_LT(EncodeImage(noise, ".png", huffman).size(), EncodeImage(noise, ".png").size());
}

TEST_F(ImageFileTest, JpegGreyAndColourAreRead) {
  for (int type : {CV_8UC1, CV_8UC3}) {
    const cv::Mat image = PatternImage(64, 48, type, 3);
    const std::string path = dir_ / ("t" + std::to_string(type) + ".jpg");
    WriteImageFile(path, image);
    ImageInfo info;
    const cv::Mat back = ReadImageFile(path, {}, &info);
    EXPECT_EQ(info.codec, ImageCodec::kJpeg);
    EXPECT_EQ(info.Describe(), std::string("64x48 8-bit ") + (type == CV_8UC1 ? "grey" : "colour") + " JPEG");
    ASSERT_EQ(back.type(), type);
    EXPECT_LT(cv::norm(image, back, cv::NORM_L1) / image.total() / image.channels(), 20.0);  // lossy, but close
  }
  EXPECT_THROW(WriteImageFile(dir_ / "deep.jpg", cv::Mat(4, 4, CV_16UC1, cv::Scalar(1))), std::invalid_argument);
}

TEST_F(ImageFileTest, TruncatedFilesAreRefusedAtEveryCut) {
  for (const std::string ext : {".png", ".jpg"}) {
    const std::string whole = EncodeImage(PatternImage(40, 30, CV_8UC1, 1), ext);
    ASSERT_NO_THROW(DecodeImageBytes(whole, "whole" + ext));
    // Every cut (each byte near the start and end, a stride in between).
    for (std::size_t cut = 0; cut < whole.size(); cut += (cut < 64 || cut + 64 > whole.size()) ? 1 : 7) {
      const std::string path = dir_ / ("cut" + ext);
      WriteText(path, whole.substr(0, cut));
      const std::string message = InputErrorOf([&] { ReadImageFile(path); }, path);
      EXPECT_TRUE(message.find("truncated") != std::string::npos || message.find("empty file") != std::string::npos)
          << ext << " cut at " << cut << " of " << whole.size() << ": " << message;
    }
  }
}

TEST_F(ImageFileTest, CorruptDataIsRefused) {
  const std::string whole = EncodeImage(PatternImage(40, 30, CV_8UC1, 1), ".png");
  const std::size_t idat = whole.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  // A flipped bit inside the compressed data: the chunk CRC no longer matches.
  std::string bad = whole;
  bad[idat + 10] = static_cast<char>(bad[idat + 10] ^ 0x10);
  EXPECT_NE(InputErrorOf([&] { InspectImageBytes(bad, "bad.png"); }, "bad.png").find("CRC mismatch in chunk IDAT"),
            std::string::npos);
  // Garbage compressed data with a valid CRC: the container is fine, the decoder refuses it.
  const std::string rows(41 * 30, '\x07');  // filter type 7 does not exist
  const std::string png = HandMadePng(40, 30, 8, 0, rows);
  EXPECT_NO_THROW(InspectImageBytes(png, "filters.png"));
  EXPECT_NE(InputErrorOf([&] { DecodeImageBytes(png, "filters.png"); }, "filters.png").find("cannot decode"),
            std::string::npos);
  // Not an image at all, an empty file, a missing file, a folder.
  WriteText(dir_ / "notes.png", "hello, not a PNG\n");
  EXPECT_NE(InputErrorOf([&] { ReadImageFile(dir_ / "notes.png"); }, dir_ / "notes.png").find("not a PNG or JPEG"),
            std::string::npos);
  WriteText(dir_ / "empty.png", "");
  EXPECT_NE(InputErrorOf([&] { ReadImageFile(dir_ / "empty.png"); }, dir_ / "empty.png").find("empty file"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { ReadImageFile(dir_ / "none.png"); }, dir_ / "none.png").find("no such file"),
            std::string::npos);
  fs::create_directories(dir_ / "folder.png");
  EXPECT_NE(InputErrorOf([&] { ReadImageFile(dir_ / "folder.png"); }, dir_ / "folder.png").find("not a regular file"),
            std::string::npos);
}

TEST_F(ImageFileTest, UnsupportedLayoutsAreRefused) {
  // Hand-made PNGs: OpenCV would expand or keep these silently.
  const std::string grey8 = HandMadePng(4, 2, 8, 0, std::string(2 * 5, '\0'));
  EXPECT_EQ(InspectImageBytes(grey8, "ok.png").Describe(), "4x2 8-bit grey PNG");
  const std::string one_bit = HandMadePng(8, 2, 1, 0, std::string(2 * 2, '\0'));
  EXPECT_NE(InputErrorOf([&] { InspectImageBytes(one_bit, "a.png"); }, "a.png").find("1-bit PNG"), std::string::npos);
  const std::string alpha = HandMadePng(4, 2, 8, 6, std::string(2 * 17, '\0'));
  EXPECT_NE(InputErrorOf([&] { InspectImageBytes(alpha, "b.png"); }, "b.png").find("alpha channel"), std::string::npos);
  const std::string trns = HandMadePng(4, 2, 8, 0, std::string(2 * 5, '\0'), {{"tRNS", std::string(2, '\0')}});
  EXPECT_NE(InputErrorOf([&] { InspectImageBytes(trns, "c.png"); }, "c.png").find("transparency"), std::string::npos);
  // A palette image is 8-bit colour once decoded.
  const std::string palette = HandMadePng(4, 2, 8, 3, std::string("\0\1\1\1\1\0\1\1\1\1", 10),
                                          {{"PLTE", std::string("\x00\x00\x00\x10\x20\x30", 6)}});
  ImageInfo info;
  const cv::Mat decoded = DecodeImageBytes(palette, "p.png", {}, &info);
  EXPECT_EQ(info.Describe(), "4x2 8-bit colour PNG");
  EXPECT_EQ(decoded.at<cv::Vec3b>(1, 3), cv::Vec3b(0x30, 0x20, 0x10));  // BGR
}

TEST_F(ImageFileTest, RequirementsNameWhatWasExpected) {
  const std::string path = dir_ / "7_top.png";
  WriteImageFile(path, PatternImage(340, 256, CV_16UC1));
  ImageRequirements size;
  size.width = 1360;
  size.height = 1024;
  size.size_source = "camera.width x camera.height in survey.json";
  EXPECT_EQ(InputErrorOf([&] { ReadImageFile(path, size); }, path),
            "the image is 340x256; expected 1360x1024 (camera.width x camera.height in survey.json)");
  size.width = 340;
  size.height = 256;
  EXPECT_NO_THROW(ReadImageFile(path, size));

  ImageRequirements layout;
  layout.same_layout_as = ImageInfo{ImageCodec::kPng, 1360, 1024, 8, 1};
  layout.layout_source = "images/0_top.png";
  EXPECT_EQ(InputErrorOf([&] { InspectImageFile(path, layout); }, path),
            "the image is 16-bit grey; expected 8-bit grey like images/0_top.png (all images of a set must share bit "
            "depth and channels)");
  layout.same_layout_as = ImageInfo{ImageCodec::kJpeg, 1, 1, 16, 1};  // the codec and size do not matter
  EXPECT_NO_THROW(InspectImageFile(path, layout));
  WriteImageFile(dir_ / "rgb.png", PatternImage(340, 256, CV_16UC3));
  EXPECT_NE(InputErrorOf([&] { InspectImageFile(dir_ / "rgb.png", layout); }, dir_ / "rgb.png")
                .find("the image is 16-bit colour; expected 16-bit grey"),
            std::string::npos);
}

TEST_F(ImageFileTest, WriterIsAtomicAndRefusesOtherTypes) {
  const std::string path = dir_ / "a.png";
  WriteImageFile(path, PatternImage(8, 8, CV_8UC1));
  const std::string first = ReadText(path);
  WriteImageFile(path, PatternImage(8, 8, CV_8UC1, 5));
  EXPECT_NE(ReadText(path), first);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_.path())) files += e.is_regular_file();
  EXPECT_EQ(files, 1);  // no temporary left behind
  EXPECT_THROW(WriteImageFile(dir_ / "f.png", cv::Mat(4, 4, CV_32FC1, cv::Scalar(0.5))), std::invalid_argument);
  EXPECT_THROW(WriteImageFile(dir_ / "f.png", cv::Mat(4, 4, CV_8UC4, cv::Scalar(1))), std::invalid_argument);
  EXPECT_THROW(WriteImageFile(dir_ / "f.bmp", cv::Mat(4, 4, CV_8UC1, cv::Scalar(1))), std::invalid_argument);
  EXPECT_THROW(WriteImageFile(dir_ / "f.png", cv::Mat()), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "f.png"));
}

}  // namespace
}  // namespace hull
