// bench_mesh_io: HullInspect's own STL/PLY/OBJ/OFF readers against assimp on
// a large real hull (the DTC container ship, 116,062 triangles, from
// ../shared/data), written in each format into a temporary folder first.
//
// "ours" is LoadMesh as the programs call it: read, weld the STL soup,
// orient outward, normals. "assimp" does the same work the assimp way:
// aiImportFile with the flags LoadMesh's assimp path uses (Triangulate,
// JoinIdenticalVertices, PreTransformVertices), the copy into a
// TriangleMesh, then the same weld, orientation and normals. The "read"
// columns leave out the orientation (the costly part both share): LoadMesh
// with orient_outward = false, against assimp plus the same topology check
// and normals LoadMesh then does. Median of --repeats runs each. --subdivide N
// splits every triangle into four N times first (midpoints on the flat
// facets): 116,062 triangles become 1.86 million with N = 2, for the
// readers' speed on a large mesh.
//
//   build/bin/bench_mesh_io [--repeats N] [--subdivide N] [--mesh PATH] [--dir DIR]
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/mesh_io.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double MedianSeconds(int repeats, const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    f();
    t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// OFF is read but not written by SaveMesh.
void WriteOff(const hull::TriangleMesh& m, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << m.num_vertices() << " " << m.num_faces() << " 0\n";
  for (const auto& v : m.vertices) out << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : m.faces) out << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
}

// What LoadMesh's assimp path does before the weld, orientation and normals.
hull::TriangleMesh ReadWithAssimp(const std::string& path) {
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices;
  const aiScene* scene = aiImportFile(path.c_str(), flags);
  if (!scene) throw std::runtime_error("assimp cannot read " + path + ": " + aiGetErrorString());
  hull::TriangleMesh m;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[i];
    const int base = static_cast<int>(m.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      m.vertices.emplace_back(mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      m.faces.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                         base + static_cast<int>(face.mIndices[2])});
    }
  }
  aiReleaseImport(scene);
  return m;
}

// What LoadMesh does after reading, whichever reader read.
void PostProcess(hull::TriangleMesh& m, bool soup, bool orient) {
  if (soup) m.WeldVertices(0.0);
  if (orient) {
    m.OrientOutward();
  } else {
    m.CheckTopology();
  }
  m.ComputeNormals();
}

// Each triangle into four through its edges' midpoints; the midpoint of an
// edge is computed the same way from both of its triangles (a + b is
// commutative), so the exact weld joins them.
hull::TriangleMesh Subdivide(const hull::TriangleMesh& m) {
  hull::TriangleMesh out;
  out.vertices.reserve(6 * m.faces.size());
  for (const auto& f : m.faces) {
    const Eigen::Vector3d& a = m.vertices[f[0]];
    const Eigen::Vector3d& b = m.vertices[f[1]];
    const Eigen::Vector3d& c = m.vertices[f[2]];
    const int i = static_cast<int>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), {a, b, c, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)});
    out.faces.push_back({i, i + 3, i + 5});
    out.faces.push_back({i + 3, i + 1, i + 4});
    out.faces.push_back({i + 5, i + 4, i + 2});
    out.faces.push_back({i + 3, i + 4, i + 5});
  }
  out.WeldVertices(0.0);
  out.ComputeNormals();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  int subdivide = 0;
  std::string mesh_path = std::string(HI_SHARED_DATA_DIR) + "/dtc-hull-scaled.stl.gz";
  std::string dir = (fs::temp_directory_path() / "hi_bench_mesh_io").string();
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--subdivide") && i + 1 < argc) {
      subdivide = std::clamp(std::atoi(argv[++i]), 0, 4);
    } else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc) {
      mesh_path = argv[++i];
    } else if (!std::strcmp(argv[i], "--dir") && i + 1 < argc) {
      dir = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [--repeats N] [--subdivide N] [--mesh PATH] [--dir DIR]\n", argv[0]);
      return 2;
    }
  }
  if (!fs::exists(mesh_path)) {
    std::printf("skipped: %s is absent (the real data in ../shared/data)\n", mesh_path.c_str());
    return 0;
  }
  hull::TriangleMesh hull = hull::LoadMesh(mesh_path);
  for (int i = 0; i < subdivide; ++i) hull = Subdivide(hull);
  std::printf("%s (subdivided %d times): %zu vertices, %zu triangles; median of %d runs\n\n", mesh_path.c_str(),
              subdivide, hull.num_vertices(), hull.num_faces(), repeats);
  fs::create_directories(dir);
  struct Case {
    const char* name;
    std::string path;
    bool soup;
  };
  const std::vector<Case> cases = {{"STL binary", dir + "/hull.stl", true},
                                   {"PLY binary, double", dir + "/hull.ply", false},
                                   {"PLY binary, float", dir + "/hull_float.ply", false},
                                   {"OBJ", dir + "/hull.obj", false},
                                   {"OFF", dir + "/hull.off", false}};
  hull::SaveMesh(hull, cases[0].path);
  hull::SaveMesh(hull, cases[1].path);
  hull::MeshSaveOptions single;
  single.double_precision = false;
  hull::SaveMesh(hull, cases[2].path, single);
  hull::SaveMesh(hull, cases[3].path);
  WriteOff(hull, cases[4].path);

  std::printf(
      "| format | size MB | ours read s | assimp read s | assimp / ours, read | ours total s | "
      "assimp total s | assimp / ours, total |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Case& c : cases) {
    hull::MeshLoadOptions no_orientation;
    no_orientation.orient_outward = false;
    std::size_t ours_faces = 0, theirs_faces = 0;
    const double ours_read = MedianSeconds(repeats, [&] { hull::LoadMesh(c.path, no_orientation); });
    const double theirs_read = MedianSeconds(repeats, [&] {
      hull::TriangleMesh m = ReadWithAssimp(c.path);
      PostProcess(m, c.soup, false);
    });
    const double ours = MedianSeconds(repeats, [&] { ours_faces = hull::LoadMesh(c.path).num_faces(); });
    const double theirs = MedianSeconds(repeats, [&] {
      hull::TriangleMesh m = ReadWithAssimp(c.path);
      PostProcess(m, c.soup, true);
      theirs_faces = m.num_faces();
    });
    if (ours_faces != theirs_faces) {
      std::fprintf(stderr, "%s: ours %zu triangles, assimp %zu\n", c.name, ours_faces, theirs_faces);
    }
    std::printf("| %s | %.1f | %.3f | %.3f | %.1fx | %.3f | %.3f | %.1fx |\n", c.name,
                static_cast<double>(fs::file_size(c.path)) / 1e6, ours_read, theirs_read, theirs_read / ours_read, ours,
                theirs, theirs / ours);
    std::fflush(stdout);
  }
  fs::remove_all(dir);
  return 0;
}
