// Camera images for a simulated survey (survey bundle version 2): every
// keyframe's camera(s) rendered from the TRUE vehicle poses, servo angles,
// camera extrinsic and model pose, so the images agree exactly with the
// bundle's truth (a true landmark projected with the bundle's camera model
// lands on the surface point the image shows).
#pragma once

#include <memory>
#include <string>

#include "base/progress.h"
#include "geometry/pose.h"
#include "simulate/image_renderer.h"
#include "simulate/survey_simulator.h"
#include "simulate/true_scene.h"

namespace hull {

// Scales a camera rig's pixel grid by s (width, height, fx, fy; pixel
// centres keep their places: u' + 0.5 = s (u + 0.5)), e.g. 0.25 turns the
// HAUV's 1360x1024 into 340x256 for quick tests.
void ScaleCamera(CameraRig& rig, double s);

// The true scene of a simulated survey: its hull and object meshes, its
// truth objects, and the albedo seeded from the survey's seed along the
// bundle's model axes.
std::unique_ptr<TrueScene> MakeTrueScene(const SimulatedSurvey& survey);

// The true pose in M of keyframe index k's top (or bottom) camera.
Pose TrueCameraPose(const SimulatedSurvey& survey, std::size_t k, bool bottom_camera);

// The rig's cameras with their strobes: top, and bottom for a stereo survey.
std::unique_ptr<UnderwaterCamera> MakeSurveyCamera(const SurveyManifest& manifest,
                                                   const UnderwaterImagingOptions& options, bool bottom_camera);

// Renders every image survey.bundle.images lists (in parallel) into
// <dir>/images and writes truth/scene.ply and truth/albedo.json. Needs
// survey.imaging. Cancellable between images (throws Cancelled).
void WriteSurveyImages(const SimulatedSurvey& survey, const std::string& dir, Progress& progress);

}  // namespace hull
