// The photomosaic's input built from an adjustment and a survey bundle. Its
// files (mosaic.obj/.mtl/_atlas.png, mosaic.ply, mosaic.json,
// mosaic_faces.csv) and where its inputs lie in a results folder are
// results/mosaic_files.h's.
#pragma once

#include "adjust/adjust_result.h"
#include "mosaic/photomosaic.h"
#include "survey/survey.h"

namespace hull {

// The adjusted poses, servo angles, extrinsic and model pose of `adjustment`
// with the images of `bundle` (which must outlive the input). Throws
// InputError when the bundle has no images.
MosaicInput MosaicInputFromAdjustment(const AdjustmentResult& adjustment, const SurveyBundle& bundle,
                                      TriangleMesh model);

}  // namespace hull
