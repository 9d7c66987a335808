#include "ui/session/project_file.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QStringList>
#include <cmath>
#include <stdexcept>

#include "base/error.h"
#include "base/json.h"
#include "ui/session/model_placement.h"

namespace hull::ui {

namespace {

constexpr const char* kFormat = "hullinspect-project";

// 1-based line and column of a byte offset.
std::pair<int, int> LineColumn(const QByteArray& text, int offset) {
  int line = 1, column = 1;
  for (int i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Where the key path (e.g. {"view", "camera", "position"}) appears in the
// text: each key searched after the previous one. Good enough to point at a
// bad value in a file QJsonDocument has already parsed.
std::pair<int, int> LocateKey(const QByteArray& text, const QStringList& path) {
  int from = 0;
  for (const QString& key : path) {
    const int at = text.indexOf(QByteArray("\"") + key.toUtf8() + "\"", from);
    if (at < 0) return {0, 0};
    from = at;
  }
  return LineColumn(text, from);
}

class Reader {
 public:
  Reader(QString path, QByteArray text) : path_(std::move(path)), text_(std::move(text)) {}

  [[noreturn]] void Fail(const QStringList& key_path, const QString& message) const {
    const auto [line, column] = LocateKey(text_, key_path);
    throw InputError({path_.toStdString(), line, column, key_path.join('.').toStdString()}, message.toStdString());
  }

  QJsonObject Object(const QJsonObject& parent, const QStringList& key_path, bool required) const {
    const QJsonValue v = parent.value(key_path.back());
    if (v.isUndefined() && !required) return {};
    if (!v.isObject()) Fail(key_path, QStringLiteral("expected an object"));
    return v.toObject();
  }

  QString String(const QJsonObject& parent, const QStringList& key_path) const {
    const QJsonValue v = parent.value(key_path.back());
    if (v.isUndefined() || v.isNull()) return {};
    if (!v.isString()) Fail(key_path, QStringLiteral("expected a string"));
    return v.toString();
  }

  bool Bool(const QJsonObject& parent, const QStringList& key_path, bool fallback) const {
    const QJsonValue v = parent.value(key_path.back());
    if (v.isUndefined()) return fallback;
    if (!v.isBool()) Fail(key_path, QStringLiteral("expected true or false"));
    return v.toBool();
  }

  double Number(const QJsonObject& parent, const QStringList& key_path, double fallback) const {
    const QJsonValue v = parent.value(key_path.back());
    if (v.isUndefined()) return fallback;
    if (!v.isDouble() || !std::isfinite(v.toDouble())) Fail(key_path, QStringLiteral("expected a number"));
    return v.toDouble();
  }

  std::array<double, 3> Vector3(const QJsonObject& parent, const QStringList& key_path) const {
    const QJsonValue v = parent.value(key_path.back());
    const QJsonArray a = v.toArray();
    if (!v.isArray() || a.size() != 3) Fail(key_path, QStringLiteral("expected an array of 3 numbers"));
    std::array<double, 3> out{};
    for (int i = 0; i < 3; ++i) {
      if (!a[i].isDouble() || !std::isfinite(a[i].toDouble())) {
        Fail(key_path, QStringLiteral("expected an array of 3 numbers"));
      }
      out[i] = a[i].toDouble();
    }
    return out;
  }

 private:
  QString path_;
  QByteArray text_;
};

QJsonArray ToJson(const std::array<double, 3>& v) { return QJsonArray{v[0], v[1], v[2]}; }

QString Resolve(const QDir& base, const QString& relative) {
  return relative.isEmpty() ? QString() : QDir::cleanPath(base.absoluteFilePath(relative));
}

}  // namespace

ProjectData ReadProject(const QString& path, const ParameterTable& table, const ParameterValidator& validator) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly)) {
    throw InputError({path.toStdString(), 0, 0, ""},
                     "cannot open the project file: " + file.errorString().toStdString());
  }
  const QByteArray text = file.readAll();
  // The syntax is checked by HullInspect's own JSON layer first, as strictly
  // as survey.json: Qt's parser accepts what JSON does not (".5"), keeps the
  // last of duplicate keys silently, and Qt 5.15 leaks the first value of a
  // duplicate key when it is an array or object (found by fuzzing:
  // tests/fuzz/regressions/project). Refused here with line and column.
  (void)Json::Parse(std::string_view(text.constData(), static_cast<std::size_t>(text.size())), path.toStdString());
  QJsonParseError parse_error;
  const QJsonDocument doc = QJsonDocument::fromJson(text, &parse_error);
  if (parse_error.error != QJsonParseError::NoError) {
    const auto [line, column] = LineColumn(text, parse_error.offset);
    throw InputError({path.toStdString(), line, column, ""},
                     "malformed JSON: " + parse_error.errorString().toStdString());
  }
  const Reader r(path, text);
  if (!doc.isObject()) r.Fail({}, QStringLiteral("expected a JSON object"));
  const QJsonObject root = doc.object();
  if (root.value(QStringLiteral("format")).toString() != QLatin1String(kFormat)) {
    r.Fail({QStringLiteral("format")}, QStringLiteral("expected \"%1\"").arg(QLatin1String(kFormat)));
  }
  const QJsonValue version = root.value(QStringLiteral("version"));
  if (!version.isDouble() || version.toDouble() != kProjectVersion) {
    r.Fail({QStringLiteral("version")},
           QStringLiteral("this HullInspect reads project version %1 (the file says %2)")
               .arg(kProjectVersion)
               .arg(version.isDouble() ? QString::number(version.toDouble()) : QStringLiteral("nothing usable")));
  }

  ProjectData p;
  const QDir base = QFileInfo(path).absoluteDir();
  const QJsonObject inputs = r.Object(root, {QStringLiteral("inputs")}, false);
  p.mesh_path = Resolve(base, r.String(inputs, {QStringLiteral("inputs"), QStringLiteral("mesh")}));
  p.bundle_path = Resolve(base, r.String(inputs, {QStringLiteral("inputs"), QStringLiteral("survey")}));

  // Parameters: missing ones take their defaults (older files), unknown ones
  // are ignored (newer files); present ones must fit the table.
  p.parameters = DefaultValues(table);
  const QJsonObject params = r.Object(root, {QStringLiteral("parameters")}, false);
  for (const ParameterDescriptor& d : table) {
    if (!params.contains(d.key)) continue;
    QVariant value;
    if (!CoerceValue(d, params.value(d.key).toVariant(), &value)) {
      r.Fail({QStringLiteral("parameters"), d.key},
             d.type == ParameterDescriptor::Type::kChoice
                 ? QStringLiteral("expected one of: %1").arg(d.choice_keys.join(QStringLiteral(", ")))
                 : QStringLiteral("expected a number"));
    }
    p.parameters.insert(d.key, value);
  }
  if (validator) {
    const std::vector<ParameterError> errors = validator(p.parameters);
    if (!errors.empty()) r.Fail({QStringLiteral("parameters"), errors.front().key}, errors.front().message);
  }

  p.placement = r.String(root, {QStringLiteral("model_placement")});
  ModelPlacement placement;
  if (!p.placement.isEmpty() && !ModelPlacementFromKey(p.placement.toStdString(), &placement)) {
    QStringList keys;
    for (ModelPlacement c :
         {ModelPlacement::kIdentity, ModelPlacement::kGuess, ModelPlacement::kTruth, ModelPlacement::kAdjusted}) {
      keys << QString::fromLatin1(ModelPlacementKey(c));
    }
    r.Fail({QStringLiteral("model_placement")},
           QStringLiteral("expected one of: %1").arg(keys.join(QStringLiteral(", "))));
  }

  const QJsonObject view = r.Object(root, {QStringLiteral("view")}, false);
  const QJsonObject layers = r.Object(view, {QStringLiteral("view"), QStringLiteral("layers")}, false);
  for (auto it = layers.begin(); it != layers.end(); ++it) {
    const std::optional<SceneLayer> layer = LayerFromKey(it.key());
    if (!layer) continue;
    p.scene.visible[*layer] = r.Bool(layers, {QStringLiteral("view"), QStringLiteral("layers"), it.key()}, true);
  }
  p.scene.hull_edges = r.Bool(view, {QStringLiteral("view"), QStringLiteral("hull_edges")}, false);
  const QString colouring = r.String(view, {QStringLiteral("view"), QStringLiteral("landmark_colouring")});
  if (!colouring.isEmpty()) {
    const auto c = ColouringFromKey(colouring);
    if (!c)
      r.Fail({QStringLiteral("view"), QStringLiteral("landmark_colouring")}, "expected \"label\" or \"deviation\"");
    p.scene.colouring = *c;
  }
  const QStringList range_path = {QStringLiteral("view"), QStringLiteral("legend_range")};
  const QJsonObject range = r.Object(view, range_path, false);
  p.scene.auto_range = r.Bool(range, range_path + QStringList{QStringLiteral("auto")}, true);
  p.scene.range_min = r.Number(range, range_path + QStringList{QStringLiteral("min")}, p.scene.range_min);
  p.scene.range_max = r.Number(range, range_path + QStringList{QStringLiteral("max")}, p.scene.range_max);
  if (!(p.scene.range_min < p.scene.range_max)) r.Fail(range_path, QStringLiteral("expected min < max"));
  p.scene.tolerance = r.Number(view, {QStringLiteral("view"), QStringLiteral("tolerance")}, 0.0);
  if (!(p.scene.tolerance >= 0 && p.scene.tolerance <= 10)) {
    r.Fail({QStringLiteral("view"), QStringLiteral("tolerance")}, QStringLiteral("expected metres in [0, 10]"));
  }
  const double stride = r.Number(view, {QStringLiteral("view"), QStringLiteral("frustum_stride")}, 10);
  if (stride < 1 || stride > 100000 || stride != std::floor(stride)) {
    r.Fail({QStringLiteral("view"), QStringLiteral("frustum_stride")}, QStringLiteral("expected a whole number >= 1"));
  }
  p.scene.frustum_stride = static_cast<int>(stride);

  if (view.contains(QStringLiteral("camera"))) {
    const QStringList cam_path = {QStringLiteral("view"), QStringLiteral("camera")};
    const QJsonObject cam = r.Object(view, cam_path, true);
    CameraState c;
    c.position = r.Vector3(cam, cam_path + QStringList{QStringLiteral("position")});
    c.focal_point = r.Vector3(cam, cam_path + QStringList{QStringLiteral("focal_point")});
    c.view_up = r.Vector3(cam, cam_path + QStringList{QStringLiteral("view_up")});
    c.view_angle = r.Number(cam, cam_path + QStringList{QStringLiteral("view_angle")}, 30.0);
    if (c.view_angle <= 0 || c.view_angle >= 180) {
      r.Fail(cam_path + QStringList{QStringLiteral("view_angle")}, QStringLiteral("expected degrees in (0, 180)"));
    }
    if (c.position == c.focal_point) r.Fail(cam_path, QStringLiteral("position and focal point coincide"));
    p.camera = c;
  }
  return p;
}

QByteArray ProjectToJson(const ProjectData& project, const QString& project_dir) {
  const QDir base(project_dir);
  auto relative = [&](const QString& path) { return path.isEmpty() ? QString() : base.relativeFilePath(path); };
  QJsonObject inputs;
  if (!project.mesh_path.isEmpty()) inputs.insert(QStringLiteral("mesh"), relative(project.mesh_path));
  if (!project.bundle_path.isEmpty()) inputs.insert(QStringLiteral("survey"), relative(project.bundle_path));

  QJsonObject layers;
  for (SceneLayer layer : AllSceneLayers()) layers.insert(LayerKey(layer), project.scene.IsVisible(layer));
  QJsonObject view{
      {QStringLiteral("layers"), layers},
      {QStringLiteral("hull_edges"), project.scene.hull_edges},
      {QStringLiteral("landmark_colouring"), ColouringKey(project.scene.colouring)},
      {QStringLiteral("legend_range"), QJsonObject{{QStringLiteral("auto"), project.scene.auto_range},
                                                   {QStringLiteral("min"), project.scene.range_min},
                                                   {QStringLiteral("max"), project.scene.range_max}}},
      {QStringLiteral("tolerance"), project.scene.tolerance},
      {QStringLiteral("frustum_stride"), project.scene.frustum_stride},
  };
  if (project.camera) {
    view.insert(QStringLiteral("camera"),
                QJsonObject{{QStringLiteral("position"), ToJson(project.camera->position)},
                            {QStringLiteral("focal_point"), ToJson(project.camera->focal_point)},
                            {QStringLiteral("view_up"), ToJson(project.camera->view_up)},
                            {QStringLiteral("view_angle"), project.camera->view_angle}});
  }
  QJsonObject root{
      {QStringLiteral("format"), QLatin1String(kFormat)},
      {QStringLiteral("version"), kProjectVersion},
      {QStringLiteral("inputs"), inputs},
      {QStringLiteral("parameters"), QJsonObject::fromVariantMap(project.parameters)},
      {QStringLiteral("view"), view},
  };
  if (!project.placement.isEmpty()) root.insert(QStringLiteral("model_placement"), project.placement);
  return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

void WriteProject(const QString& path, const ProjectData& project) {
  QSaveFile file(path);
  if (!file.open(QIODevice::WriteOnly)) {
    throw std::runtime_error("cannot write " + path.toStdString() + ": " + file.errorString().toStdString());
  }
  const QByteArray json = ProjectToJson(project, QFileInfo(path).absolutePath());
  if (file.write(json) != json.size() || !file.commit()) {
    throw std::runtime_error("cannot write " + path.toStdString() + ": " + file.errorString().toStdString());
  }
}

}  // namespace hull::ui
