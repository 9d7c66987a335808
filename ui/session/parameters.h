// The tunable parameters as a table of field descriptors (COLMAP's option
// structs seen from the GUI): name, type, range, default, unit and tooltip,
// plus a validator that returns errors per field. The parameter panel, the
// undo stack and project files work from this table alone, so binding the
// panel to the core options structs means (1) listing their fields here and
// (2) a validator that copies the values into the struct, calls its Check()
// and turns an OptionError(field, why) into a ParameterError for that field.
#pragma once

#include <QString>
#include <QStringList>
#include <QVariantMap>
#include <functional>
#include <vector>

namespace hull::ui {

struct ParameterDescriptor {
  enum class Type { kReal, kInteger, kChoice };
  // What a change of the field re-runs: the visual front end (feature
  // extraction from the images, then everything after it), the bundle
  // adjustment (and mapping after it), mapping only, or nothing
  // (display-only fields).
  enum class Stage { kFrontEnd, kAdjustment, kMapping, kNone };

  QString key;    // stable name: project files, later the options field
  QString group;  // panel section ("Adjustment", "Mapping", ...)
  QString label;  // shown in the panel
  Type type = Type::kReal;
  double minimum = 0, maximum = 1;
  double default_value = 0;   // kChoice: index into choices
  int decimals = 3;           // kReal
  double step = 0.01;         // kReal, kInteger
  QString unit;               // suffix, e.g. "m"
  QStringList choice_keys;    // kChoice: values as stored ("max_mixture", ...)
  QStringList choice_labels;  // kChoice: as shown
  QString tooltip;
  Stage stage = Stage::kNone;

  // The default as a value of the map: double, int or the choice key.
  QVariant DefaultValue() const;
};

// Values by key: double (kReal), int (kInteger) or QString choice key (kChoice).
using ParameterValues = QVariantMap;

struct ParameterError {
  QString key;      // the field at fault
  QString message;  // why, in words
};

using ParameterValidator = std::function<std::vector<ParameterError>(const ParameterValues&)>;

using ParameterTable = std::vector<ParameterDescriptor>;

// The model-assisted bundle adjustment and mapping parameters of Ozog et al.
// (sigma0, sigma1, surface model, tau, alpha, DBSCAN epsilon and minimum
// points, solver limits) and the visual front end's (ratio tests, CLAHE,
// RANSAC, search window), bound to the core options structs: their defaults
// are the structs' defaults (see inspection_parameters.h).
const ParameterTable& DefaultParameterTable();
ParameterValues DefaultValues(const ParameterTable& table);
const ParameterDescriptor* FindParameter(const ParameterTable& table, const QString& key);

// Every field present, of its type, in its range, a known choice.
std::vector<ParameterError> CheckAgainstTable(const ParameterTable& table, const ParameterValues& values);

// Why an editor refused what was typed into it (`text`: the editor's whole
// text, the unit suffix included or not): "2 m is outside [0.001, 1] m",
// or that it is not a number; the value in force stays, and the message says
// so. The editors keep their values in the descriptor's range, so without
// this a refused keystroke would vanish without a word.
ParameterError RefusedEntry(const ParameterDescriptor& d, const QString& text, const QVariant& in_force);

// CheckAgainstTable, then the values copied into the core options structs
// and their Check() (an OptionError names the field at fault).
std::vector<ParameterError> CheckDefaultParameters(const ParameterValues& values);

// A value converted to the descriptor's type (doubles from JSON become ints
// for kInteger); false when it cannot be.
bool CoerceValue(const ParameterDescriptor& d, const QVariant& in, QVariant* out);

// The table's rows, as the tables of inspection_parameters.h and
// sonar_parameters.h build them.
namespace table {
ParameterDescriptor Real(QString key, QString group, ParameterDescriptor::Stage stage, QString label, double min,
                         double max, double def, int decimals, double step, QString unit, QString tooltip);
ParameterDescriptor Integer(QString key, QString group, ParameterDescriptor::Stage stage, QString label, int min,
                            int max, int def, QString tooltip);
ParameterDescriptor Choice(QString key, QString group, ParameterDescriptor::Stage stage, QString label,
                           QStringList keys, QStringList labels, int def, QString tooltip);
}  // namespace table

}  // namespace hull::ui
