// Foreign structure on the true hull surface: cylinders (e.g. the paper's
// known 0.15 m x 0.11 m cylinder), boxes, and biofouling patches (irregular
// bumps of 0.06-0.18 m; a strip of fouling along the centreline where docking
// blocks left the hull unpainted is a chain of patches).
//
// An object is described as in the contract (truth/objects.json): the centre
// of its base on the CAD surface, the outward normal there, and its size. Its
// mesh is closed and sunk a few centimetres into the hull so that hull and
// object together form the true surface without gaps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/mesh_index.h"
#include "geometry/triangle_mesh.h"
#include "survey/survey.h"

namespace hull {

// The mesh of one object in the model frame M. A box's side a lies along the
// model x axis projected onto the surface. For patches the shape is
// irregular but deterministic from the seed; its top is exactly `height`
// above the centre along the normal and its footprint within `radius`.
TriangleMesh MakeObjectMesh(const TrueObject& object, std::uint64_t seed, double sink = 0.05);

// Places an object's base centre on the CAD surface nearest to `near` and
// sets its normal to the outward normal of that face.
TrueObject PlaceObject(const MeshIndex& cad, std::string id, ObjectKind kind, const Eigen::Vector3d& near,
                       double radius, double height, const Eigen::Vector3d& box_size = Eigen::Vector3d::Zero());

// A chain of overlapping patches from `from` to `to` (both in M, projected
// onto the surface), with heights drawn in [h_min, h_max] and radii in
// [r_min, r_max]; ids are "<prefix>-1", "<prefix>-2", ...
std::vector<TrueObject> PlacePatchStrip(const MeshIndex& cad, const std::string& prefix, const Eigen::Vector3d& from,
                                        const Eigen::Vector3d& to, double r_min, double r_max, double h_min,
                                        double h_max, std::uint64_t seed);

}  // namespace hull
