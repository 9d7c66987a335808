#include "simulate/sonar_scene.h"

#include "base/error.h"

namespace hull {
namespace {

// Adds the quad a b c d (in order around it) as two triangles of one surface.
void AddQuad(SonarScene& s, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d, int material, int surface) {
  const int base = static_cast<int>(s.mesh.vertices.size());
  for (const Eigen::Vector3d* p : {&a, &b, &c, &d}) s.mesh.vertices.push_back(*p);
  s.mesh.faces.push_back({base, base + 1, base + 2});
  s.mesh.faces.push_back({base, base + 2, base + 3});
  for (int i = 0; i < 2; ++i) {
    s.face_material.push_back(material);
    s.face_surface.push_back(surface);
  }
}

bool Usable(const SonarMaterial& m) { return m.reflectivity >= 0 && m.exponent >= 0 && m.exponent <= 100; }

}  // namespace

bool SonarSceneOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& field, const std::string& reason) {
    if (why) *why = field + ": " + reason;
    return false;
  };
  if (!Usable(object)) return fail("object", "needs reflectivity >= 0 and exponent in [0, 100]");
  if (!Usable(floor)) return fail("floor", "needs reflectivity >= 0 and exponent in [0, 100]");
  if (!Usable(walls)) return fail("walls", "needs reflectivity >= 0 and exponent in [0, 100]");
  if (!(vertex_strength >= 0)) return fail("vertex_strength", "must not be negative");
  if (!(tank_back_wall > 0)) return fail("tank_back_wall", "must be positive");
  if (!(tank_side_walls > 0.2)) return fail("tank_side_walls", "must exceed the prism's half width (0.1 m) with room");
  return true;
}

SonarScene MakeSonarScene(const SonarLayout& layout, SonarPreset preset, const SonarSceneOptions& o) {
  std::string why;
  if (!o.Check(&why)) {
    const auto colon = why.find(':');
    throw OptionError(why.substr(0, colon), why.substr(colon + 2));
  }
  SonarScene s;
  s.materials = {o.object, o.floor, o.walls};
  constexpr int kObject = 0, kFloor = 1, kWalls = 2;
  // The prism: six faces, corners named by (x, y, z) = lo or hi.
  const Eigen::Vector3d lo = layout.object.min(), hi = layout.object.max();
  auto corner = [&](int x, int y, int z) {
    return Eigen::Vector3d(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z());
  };
  int surface = 0;
  AddQuad(s, corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(0, 1, 0), kObject, surface++);  // top (z down)
  AddQuad(s, corner(0, 0, 1), corner(0, 1, 1), corner(1, 1, 1), corner(1, 0, 1), kObject, surface++);  // bottom
  AddQuad(s, corner(0, 0, 0), corner(0, 1, 0), corner(0, 1, 1), corner(0, 0, 1), kObject, surface++);  // -x
  AddQuad(s, corner(1, 0, 0), corner(1, 0, 1), corner(1, 1, 1), corner(1, 1, 0), kObject, surface++);  // +x
  AddQuad(s, corner(0, 0, 0), corner(0, 0, 1), corner(1, 0, 1), corner(1, 0, 0), kObject, surface++);  // -y
  AddQuad(s, corner(0, 1, 0), corner(1, 1, 0), corner(1, 1, 1), corner(0, 1, 1), kObject, surface++);  // +y
  // The floor the prism stands on (z down: its bottom is hi.z()).
  const double fz = hi.z();
  const double x0 = -2.0, x1 = layout.centre.x() + 6.0, y0 = -6.0, y1 = 6.0;
  if (preset == SonarPreset::kTank) {
    const double xb = hi.x() + o.tank_back_wall, ys = o.tank_side_walls, top = fz - 4.0;
    AddQuad(s, {x0, -ys, fz}, {xb, -ys, fz}, {xb, ys, fz}, {x0, ys, fz}, kFloor, surface++);
    AddQuad(s, {xb, -ys, fz}, {xb, -ys, top}, {xb, ys, top}, {xb, ys, fz}, kWalls, surface++);  // back
    AddQuad(s, {x0, -ys, fz}, {x0, -ys, top}, {xb, -ys, top}, {xb, -ys, fz}, kWalls, surface++);
    AddQuad(s, {x0, ys, fz}, {xb, ys, fz}, {xb, ys, top}, {x0, ys, top}, kWalls, surface++);
  } else {
    AddQuad(s, {x0, y0, fz}, {x1, y0, fz}, {x1, y1, fz}, {x0, y1, fz}, kFloor, surface++);
  }
  s.mesh.ComputeNormals();
  for (const Eigen::Vector3d& v : layout.object_vertices) {
    s.scatterers.push_back(v);
    s.scatterer_strength.push_back(o.vertex_strength);
  }
  return s;
}

}  // namespace hull
