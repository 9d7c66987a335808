// The scene an acoustic image is rendered from: triangles with an acoustic
// material each (the object, a floor, tank walls) and point scatterers (the
// object's vertices: edges and corners return strongly, which is what makes
// them the feature points of Mai et al.).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "simulate/sonar_simulator.h"

namespace hull {

// Backscatter of a surface: reflectivity * |cos(incidence)|^exponent
// (exponent 2 is Lambert's law for backscatter, 1 a rougher surface).
struct SonarMaterial {
  double reflectivity = 1.0;
  double exponent = 2.0;
};

struct SonarSceneOptions {
  // The prism (painted metal or concrete: bright, fairly smooth).
  SonarMaterial object{0.3, 2.0};
  // The floor under the object (sand or concrete, rough: returns at grazing angles).
  SonarMaterial floor{0.3, 1.0};
  // The tank's walls (tank layout).
  SonarMaterial walls{0.3, 1.0};
  // Strength of each vertex as a point scatterer, in units of the strongest
  // return a surface can give one pixel (reflectivity 1, seen head-on across
  // the whole elevation fan in one range bin).
  double vertex_strength = 6.0;
  // Tank layout: the walls' distance (m) behind the prism and to either side
  // of the boresight's vertical plane.
  double tank_back_wall = 1.0;
  double tank_side_walls = 1.6;

  bool Check(std::string* why = nullptr) const;
};

struct SonarScene {
  TriangleMesh mesh;               // world frame (z down), with face normals
  std::vector<int> face_material;  // per face: index into materials
  std::vector<int> face_surface;   // per face: the flat surface it belongs to (continuity of returns)
  std::vector<SonarMaterial> materials;
  std::vector<Eigen::Vector3d> scatterers;  // point scatterers (world)
  std::vector<double> scatterer_strength;
};

// The object of a layout (the prism) standing on a floor (prism and above
// layouts) or in a tank (floor, back and side walls); the prism's vertices
// are the point scatterers.
SonarScene MakeSonarScene(const SonarLayout& layout, SonarPreset preset, const SonarSceneOptions& options = {});

}  // namespace hull
