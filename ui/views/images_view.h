// The images view (Ozog et al.'s keyframe figure on real pixels): one
// keyframe's camera image (top or bottom) with its SIFT features (circles
// of their SIFT size; filled: in a track), its stereo matches (top <->
// bottom) and its temporal matches with the previous keyframe as lines from
// the feature to the matched feature's pixel in the other image, coloured
// by RANSAC's verdict (green inlier, red outlier, grey unverified), and after
// the adjustment the adjusted landmarks' reprojections (crosses) with the
// residual vector from the feature, drawn magnified. A slider and a spin box
// pick the keyframe; the mouse wheel zooms about the cursor, dragging pans,
// a double click fits the image. The legend counts what is drawn.
#pragma once

#include <QImage>
#include <QWidget>
#include <memory>

#include "adjust/adjust_result.h"
#include "survey/survey.h"
#include "ui/models/image_overlay.h"
#include "vision/front_end.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QSlider;
class QSpinBox;

namespace hull::ui {

class ImagesCanvas;

class ImagesView : public QWidget {
  Q_OBJECT

 public:
  explicit ImagesView(QWidget* parent = nullptr);
  ~ImagesView() override;

  // The open survey and what the front end found in it (null: none).
  void SetSurvey(std::shared_ptr<const SurveyBundle> bundle, std::shared_ptr<const FrontEndResult> front_end);
  void SetAdjustment(std::shared_ptr<const AdjustmentResult> adjustment);
  // Nav row (clamped); -1 with no survey.
  void ShowKeyframe(int index);
  void SetBottomCamera(bool bottom);
  // Residual vectors are drawn this many times their length.
  void SetResidualScale(double scale);

  int keyframe() const { return index_; }
  const ImageOverlay& overlay() const { return overlay_; }
  const QImage& image() const { return image_; }
  QString legendText() const;
  QString imageError() const { return image_error_; }  // why the image could not be read ("" if it could)
  // What is written where the image is missing: its read error, a dropped
  // frame, or that the survey has no images at all ("" while one is shown).
  QString missingImageText() const;
  QSpinBox* keyframeBox() const { return spin_; }
  QSlider* keyframeSlider() const { return slider_; }
  QComboBox* cameraBox() const { return camera_; }
  ImagesCanvas* canvas() const { return canvas_; }

  // Which layers are drawn (all by default).
  struct Layers {
    bool features = true, stereo = true, temporal = true, reprojections = true;
  };
  const Layers& layers() const { return layers_; }

 private:
  void Refresh();
  void ReadImage();

  std::shared_ptr<const SurveyBundle> bundle_;
  std::shared_ptr<const FrontEndResult> front_end_;
  std::shared_ptr<const AdjustmentResult> adjustment_;
  int index_ = -1;
  bool bottom_ = false;
  double residual_scale_ = 10.0;
  Layers layers_;
  ImageOverlay overlay_;
  QImage image_;
  QString image_error_;
  int image_index_ = -2;  // what image_ holds
  bool image_bottom_ = false;

  QSpinBox* spin_ = nullptr;
  QSlider* slider_ = nullptr;
  QComboBox* camera_ = nullptr;
  QCheckBox* show_features_ = nullptr;
  QCheckBox* show_stereo_ = nullptr;
  QCheckBox* show_temporal_ = nullptr;
  QCheckBox* show_reprojections_ = nullptr;
  QLabel* legend_ = nullptr;
  ImagesCanvas* canvas_ = nullptr;
};

}  // namespace hull::ui
