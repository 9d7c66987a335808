// The inspection's parameters bound to the core options structs: the
// parameter table (DefaultParameterTable, declared in parameters.h) lists
// fields of AdjustmentOptions, MappingOptions, FrontEndOptions and
// MosaicOptions under the structs' own
// names and with the structs' defaults; the validator copies the values into
// the structs and calls their Check(). The keys below are also what project
// files store.
#pragma once

#include <QString>

#include "adjust/adjust_options.h"
#include "mapping/mapping_options.h"
#include "mosaic/mosaic_options.h"
#include "ui/session/parameters.h"
#include "vision/vision_options.h"

namespace hull::ui {

// The surface model as stored in the table ("naive", "all-on-surface",
// "max-mixture": the core's names).
QString ModelKey(SurfaceModel model);
QString ModelLabel(SurfaceModel model);         // "Max-mixture (Ozog et al.)", ...
SurfaceModel ModelFromKey(const QString& key);  // max-mixture for an unknown key

// The adjustment options for the values (assumed valid: see
// CheckDefaultParameters); fields the table does not hold keep the struct's
// defaults.
AdjustmentOptions AdjustmentOptionsFrom(const ParameterValues& values);
MappingOptions MappingOptionsFrom(const ParameterValues& values);
// The visual front end's options (group "Visual front end", keys "fe_...").
FrontEndOptions FrontEndOptionsFrom(const ParameterValues& values);
// The photomosaic's options (group "Photomosaic", keys "mosaic_<field>";
// the other fields keep MosaicOptions' defaults).
MosaicOptions MosaicOptionsFrom(const ParameterValues& values);

// A canonical text of the values of one stage, for caching results per
// parameter set. For the adjustment, fields the model ignores are left out
// (the naive model has no surface factor, so its result does not depend on
// sigma0 or sigma1; all-on-surface uses sigma1 only), so that a result is
// reused whenever it would be the same.
QString AdjustmentKey(const ParameterValues& values);
// AdjustmentKey plus the mapping fields: a mapping result depends on both.
QString MappingKey(const ParameterValues& values);
// The front end's fields: extracted features are cached per this key.
QString FrontEndKey(const ParameterValues& values);

// The values with the model replaced (for the comparison runs).
ParameterValues WithModel(const ParameterValues& values, SurfaceModel model);

}  // namespace hull::ui
