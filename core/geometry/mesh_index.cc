// MeshIndex on Embree 3. Embree's BVH is in single precision, so it only
// proposes candidates: every answer is recomputed in double precision on the
// mesh's own vertices, and every float bound the BVH is given is widened by
// a margin that covers the float rounding of vertices and query points.
#include "geometry/mesh_index.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include "base/csv.h"
#include "base/error.h"
#include "geometry/point_index.h"
#include "geometry/query_bounds.h"

namespace hull {
namespace {

// ---- the process-wide Embree device, shared by all indices and released
// with the last of them.
struct Device {
  RTCDevice device = nullptr;
  Device() {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("MeshIndex: cannot create an Embree device");
  }
  ~Device() { rtcReleaseDevice(device); }
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
};

std::shared_ptr<Device> SharedDevice() {
  static std::mutex mutex;
  static std::weak_ptr<Device> shared;
  std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<Device> d = shared.lock();
  if (!d) {
    d = std::make_shared<Device>();
    shared = d;
  }
  return d;
}

void ThrowOnDeviceError(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("MeshIndex: Embree error ") + std::to_string(static_cast<int>(e)) + " while " +
                             what);
  }
}

// Which feature of a triangle the closest point lies on; the numbering
// matches the per-face edge pseudonormals (edge k = vertex k -> k + 1).
enum Feature : int { kInterior = 0, kEdge0, kEdge1, kEdge2, kVertex0, kVertex1, kVertex2 };

struct TrianglePoint {
  Eigen::Vector3d point;
  Feature feature;
};

// Closest point on segment a + s (b - a), s in [0, 1]; returns s.
double SegmentParameter(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return 0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

// Exact closest point on triangle abc to the origin (Ericson, Real-Time
// Collision Detection, 5.1.5: Voronoi regions), with the feature it lies on.
// The caller passes the corners relative to the query point, so that
// distances keep full precision even far from the coordinate origin.
// Degenerate triangles (zero area) fall back to their three edges.
TrianglePoint ClosestOnTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) return {a, kVertex0};
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) return {b, kVertex1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return {a + (d1 / (d1 - d3)) * ab, kEdge0};
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) return {c, kVertex2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return {a + (d2 / (d2 - d6)) * ac, kEdge2};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
    return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), kEdge1};
  }
  const double sum = va + vb + vc;
  if (sum > 0 && va >= 0 && vb >= 0 && vc >= 0) {
    const double v = vb / sum, w = vc / sum;
    return {a + v * ab + w * ac, kInterior};
  }
  // Degenerate (or numerically flat) triangle: the nearest of its edges.
  TrianglePoint best{a, kVertex0};
  double best_d2 = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d* corners[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& s = *corners[k];
    const Eigen::Vector3d& e = *corners[(k + 1) % 3];
    const double t = SegmentParameter(Eigen::Vector3d::Zero(), s, e);
    const Eigen::Vector3d x = s + t * (e - s);
    if (x.squaredNorm() < best_d2) {
      best_d2 = x.squaredNorm();
      const Feature edge = static_cast<Feature>(kEdge0 + k);
      const Feature start = static_cast<Feature>(kVertex0 + k);
      const Feature end = static_cast<Feature>(kVertex0 + (k + 1) % 3);
      best = {x, t <= 0 ? start : (t >= 1 ? end : edge)};
    }
  }
  return best;
}

// Runs body(begin, end) over [0, n) in contiguous chunks on all cores.
template <typename Body>
void ParallelFor(int n, const Body& body) {
  const int threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 16);
  if (threads == 1 || n < 4096) {
    body(0, n);
    return;
  }
  const int chunk = (n + threads - 1) / threads;
  std::vector<std::thread> pool;
  for (int t = 1; t < threads && t * chunk < n; ++t) pool.emplace_back(body, t * chunk, std::min(n, (t + 1) * chunk));
  body(0, std::min(n, chunk));
  for (auto& t : pool) t.join();
}

// Smallest float >= x (x >= 0), so a float bound never undercuts a double one.
float FloatAtLeast(double x) {
  if (!(x < static_cast<double>(std::numeric_limits<float>::max()))) return std::numeric_limits<float>::infinity();
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Per-query state of a closest-point search (lives on the caller's stack).
struct ClosestSearch {
  const TriangleMesh* mesh;
  Eigen::Vector3d q;
  double margin;
  double best_d2 = std::numeric_limits<double>::infinity();
  int best_face = -1;
  Eigen::Vector3d best_offset = Eigen::Vector3d::Zero();  // closest point - q
  Feature best_feature = kInterior;

  // Evaluates face f exactly; keeps the lexicographic minimum of
  // (squared distance, face index), so the answer does not depend on the
  // order in which faces are visited. Returns true when f became the best.
  bool Offer(int f) {
    const Face& F = mesh->faces[f];
    const TrianglePoint tp =
        ClosestOnTriangle(mesh->vertices[F[0]] - q, mesh->vertices[F[1]] - q, mesh->vertices[F[2]] - q);
    const double d2 = tp.point.squaredNorm();
    if (d2 < best_d2 || (d2 == best_d2 && f < best_face)) {
      best_d2 = d2;
      best_face = f;
      best_offset = tp.point;
      best_feature = tp.feature;
      return true;
    }
    return false;
  }

  // The float search radius that still contains every face that could tie.
  float Radius() const { return FloatAtLeast(std::sqrt(best_d2) + margin); }
};

bool ClosestCallback(RTCPointQueryFunctionArguments* args) {
  auto* s = static_cast<ClosestSearch*>(args->userPtr);
  const int f = static_cast<int>(args->primID);
  if (f == s->best_face || !s->Offer(f)) return false;
  const float r = s->Radius();
  if (r < args->query->radius) {
    args->query->radius = r;
    return true;
  }
  return false;
}

// Per-vertex state of the clearance computation (see vertex_clearance).
struct ClearanceSearch {
  const TriangleMesh* mesh;
  int v;
  double margin;
  double best_d2 = std::numeric_limits<double>::infinity();
};

bool ClearanceCallback(RTCPointQueryFunctionArguments* args) {
  auto* s = static_cast<ClearanceSearch*>(args->userPtr);
  const Face& F = s->mesh->faces[args->primID];
  if (F[0] == s->v || F[1] == s->v || F[2] == s->v) return false;
  const Eigen::Vector3d& x = s->mesh->vertices[s->v];
  const double d2 =
      ClosestOnTriangle(s->mesh->vertices[F[0]] - x, s->mesh->vertices[F[1]] - x, s->mesh->vertices[F[2]] - x)
          .point.squaredNorm();
  if (d2 >= s->best_d2) return false;
  s->best_d2 = d2;
  const float r = FloatAtLeast(std::sqrt(d2) + s->margin);
  if (r < args->query->radius) {
    args->query->radius = r;
    return true;
  }
  return false;
}

}  // namespace

struct MeshIndex::Impl {
  std::shared_ptr<Device> device;
  RTCScene scene = nullptr;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // Embree works on vertices - centre
  double extent = 0;                                 // largest |vertex - centre| coordinate
  std::vector<Eigen::Vector3d> face_normals;         // unit, right-hand rule (zero if degenerate)
  std::vector<Eigen::Vector3d> edge_pseudonormals;   // 3 per face: edge k = F[k] -> F[k + 1]
  std::vector<Eigen::Vector3d> vertex_pseudonormals;
  std::vector<std::vector<int>> vertex_faces;
  std::vector<int> star_offsets, star_faces;  // the same, flat: faces of v in [offsets[v], offsets[v + 1])
  std::unique_ptr<PointIndex> vertex_index;
  // Clearance of vertex v: the distance from it to the nearest face that
  // does not use it. For a face g that uses none of the corners of face f,
  // and any corner v of f, |q - g| >= clearance(v) - |q - v|: the bound
  // that lets a search around a (hinted) face prove its answer exact
  // without a BVH traversal.
  std::vector<double> vertex_clearance;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
  }

  struct Span {
    const int* first;
    const int* last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
  };
  Span Star(int v) const { return {star_faces.data() + star_offsets[v], star_faces.data() + star_offsets[v + 1]}; }

  // The range along the unit direction d at which the ray from origin meets
  // face f's plane, in double precision (Moeller-Trumbore's t); Embree's
  // float estimate when the ray runs parallel to the plane.
  static double RefinedRange(const TriangleMesh& mesh, const Eigen::Vector3d& origin, const Eigen::Vector3d& d, int f,
                             float estimate) {
    const Face& F = mesh.faces[f];
    const Eigen::Vector3d& v0 = mesh.vertices[F[0]];
    const Eigen::Vector3d e1 = mesh.vertices[F[1]] - v0;
    const Eigen::Vector3d e2 = mesh.vertices[F[2]] - v0;
    const double det = e1.dot(d.cross(e2));
    return det != 0 ? (origin - v0).cross(e1).dot(e2) / det : static_cast<double>(estimate);
  }

  // Absolute slack added to float bounds for a query at q: covers the float
  // rounding of the BVH's vertices and of q (relative 2^-24 each) with a
  // wide safety factor.
  double Margin(const Eigen::Vector3d& q) const { return 1e-6 * (extent + (q - centre).cwiseAbs().maxCoeff()) + 1e-30; }

  // Point query of the BVH: offers every face whose box lies within the
  // current best distance (plus the rounding margin), shrinking it.
  void QueryBvh(ClosestSearch& s) const {
    RTCPointQuery query;
    const Eigen::Vector3d qs = s.q - centre;
    query.x = static_cast<float>(qs.x());
    query.y = static_cast<float>(qs.y());
    query.z = static_cast<float>(qs.z());
    query.time = 0;
    query.radius = s.Radius();
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene, &query, &context, ClosestCallback, &s);
  }

  // Offers the faces around the given vertices, nearest vertex first,
  // until the vertices' clearances prove that no face left out can be as
  // near as the best found (true), or the vertices run out (false). The
  // `done` vertices' faces were offered already (their bounds hold too).
  bool SearchStars(ClosestSearch& s, const TriangleMesh& mesh, std::array<int, 3> vs, int n,
                   std::array<int, 3> done = {-1, -1, -1}, int ndone = 0) const {
    std::array<double, 3> dist{};
    for (int k = 0; k < n; ++k) dist[k] = (s.q - mesh.vertices[vs[k]]).norm();
    for (int k = 1; k < n; ++k) {
      for (int j = k; j > 0 && dist[j] < dist[j - 1]; --j) {
        std::swap(dist[j], dist[j - 1]);
        std::swap(vs[j], vs[j - 1]);
      }
    }
    double bound = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < ndone; ++j) {
      bound = std::max(bound, vertex_clearance[done[j]] - (s.q - mesh.vertices[done[j]]).norm());
    }
    for (int k = 0; k < n; ++k) {
      for (int g : Star(vs[k])) {
        const Face& G = mesh.faces[g];
        bool offered = false;
        for (int j = 0; j < ndone; ++j) offered |= G[0] == done[j] || G[1] == done[j] || G[2] == done[j];
        if (!offered) s.Offer(g);
      }
      done[ndone++] = vs[k];
      bound = std::max(bound, vertex_clearance[vs[k]] - dist[k]);
      if (bound - s.margin > std::sqrt(s.best_d2)) return true;
    }
    return false;
  }

  // Exact closest point. Starts around the hint face's corners (or the
  // nearest vertex), where a near query is usually proven exact by the
  // clearances; otherwise Embree's point query finishes the search from the
  // bound found. Ties go to the lowest face index, so the answer never
  // depends on the hint or the visiting order.
  ClosestSearch Search(const TriangleMesh& mesh, const Eigen::Vector3d& q, int hint_face) const {
    ClosestSearch s{&mesh, q, Margin(q)};
    if (hint_face >= 0 && hint_face < static_cast<int>(mesh.faces.size())) {
      if (SearchStars(s, mesh, mesh.faces[hint_face], 3)) return s;
    } else {
      const int v = vertex_index->NearestOne(q).first;
      if (v < 0) return s;
      if (SearchStars(s, mesh, {v, -1, -1}, 1)) return s;
      if (s.best_face >= 0) {
        // Then around the corners of the best face found.
        std::array<int, 3> rest{};
        int n = 0;
        for (int c : mesh.faces[s.best_face]) {
          if (c != v) rest[n++] = c;
        }
        if (SearchStars(s, mesh, rest, n, {v, -1, -1}, 1)) return s;
      }
    }
    QueryBvh(s);
    return s;
  }
};

MeshIndex::MeshIndex(const TriangleMesh& mesh) : mesh_(mesh), impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  const int nv = static_cast<int>(mesh.vertices.size());
  const int nf = static_cast<int>(mesh.faces.size());
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.faces[f][k] < 0 || mesh.faces[f][k] >= nv) {
        throw std::invalid_argument("MeshIndex: face " + std::to_string(f) + " uses vertex " +
                                    std::to_string(mesh.faces[f][k]) + " of " + std::to_string(nv));
      }
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (!Queryable(mesh.vertices[static_cast<std::size_t>(v)])) {
      throw InputError({"mesh", 0, 0, "vertex " + std::to_string(v)},
                       "a coordinate is not finite or beyond " + FormatDouble(kMaxQueryCoordinate) +
                           " m; the mesh cannot be indexed (Embree works in float)");
    }
  }
  if (nv > 0) {
    const Eigen::AlignedBox3d box = mesh.Bounds();
    I.centre = box.center();
    I.extent = (box.max() - I.centre).cwiseAbs().maxCoeff();
  }

  // Faces around each vertex (the star), as one flat array for the search
  // and as vectors for FacesOfVertex.
  I.star_offsets.assign(static_cast<std::size_t>(nv) + 1, 0);
  for (const Face& F : mesh.faces) {
    for (int v : F) ++I.star_offsets[v + 1];
  }
  for (int v = 0; v < nv; ++v) I.star_offsets[v + 1] += I.star_offsets[v];
  I.star_faces.resize(static_cast<std::size_t>(nf) * 3);
  {
    std::vector<int> fill(I.star_offsets.begin(), I.star_offsets.end() - 1);
    for (int f = 0; f < nf; ++f) {
      for (int v : mesh.faces[f]) I.star_faces[fill[v]++] = f;
    }
  }
  I.vertex_faces.resize(nv);
  ParallelFor(nv, [&](int begin, int end) {
    for (int v = begin; v < end; ++v) I.vertex_faces[v].assign(I.Star(v).begin(), I.Star(v).end());
  });

  // Normals and the angle-weighted pseudonormals (Baerentzen and Aanaes):
  // the unit normals of an edge's faces summed, and those of a vertex's
  // faces weighted by their angle at the vertex.
  I.face_normals.resize(nf);
  ParallelFor(nf, [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      const Face& F = mesh.faces[f];
      const Eigen::Vector3d n =
          (mesh.vertices[F[1]] - mesh.vertices[F[0]]).cross(mesh.vertices[F[2]] - mesh.vertices[F[0]]);
      const double len = n.norm();
      I.face_normals[f] = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
    }
  });
  I.vertex_pseudonormals.assign(nv, Eigen::Vector3d::Zero());
  ParallelFor(nv, [&](int begin, int end) {
    for (int v = begin; v < end; ++v) {
      for (int g : I.Star(v)) {
        const Face& G = mesh.faces[g];
        const int k = G[0] == v ? 0 : (G[1] == v ? 1 : 2);
        const Eigen::Vector3d e1 = mesh.vertices[G[(k + 1) % 3]] - mesh.vertices[v];
        const Eigen::Vector3d e2 = mesh.vertices[G[(k + 2) % 3]] - mesh.vertices[v];
        I.vertex_pseudonormals[v] += std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * I.face_normals[g];
      }
    }
  });
  I.edge_pseudonormals.resize(static_cast<std::size_t>(nf) * 3);
  ParallelFor(nf, [&](int begin, int end) {
    for (int f = begin; f < end; ++f) {
      const Face& F = mesh.faces[f];
      for (int k = 0; k < 3; ++k) {
        // Every face on edge a-b is in a's star.
        const int a = F[k], b = F[(k + 1) % 3];
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int g : I.Star(a)) {
          const Face& G = mesh.faces[g];
          if (G[0] == b || G[1] == b || G[2] == b) sum += I.face_normals[g];
        }
        I.edge_pseudonormals[3 * static_cast<std::size_t>(f) + k] = sum;
      }
    }
  });
  I.vertex_index = std::make_unique<PointIndex>(mesh.vertices);

  // Embree scene: float vertices shifted by the box centre.
  I.device = SharedDevice();
  RTCDevice device = I.device->device;
  I.scene = rtcNewScene(device);
  rtcSetSceneFlags(I.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(I.scene, RTC_BUILD_QUALITY_HIGH);
  if (nf > 0) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nf));
    ThrowOnDeviceError(device, "allocating the mesh buffers");
    for (int v = 0; v < nv; ++v) {
      const Eigen::Vector3d p = mesh.vertices[v] - I.centre;
      for (int k = 0; k < 3; ++k) vb[3 * v + k] = static_cast<float>(p[k]);
    }
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) ib[3 * f + k] = static_cast<unsigned>(mesh.faces[f][k]);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(I.scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(I.scene);
  ThrowOnDeviceError(device, "building the BVH");

  // Vertex clearances, exact in double, in parallel.
  I.vertex_clearance.assign(nv, std::numeric_limits<double>::infinity());
  if (nf > 0) {
    const auto clearances = [&](int begin, int end) {
      for (int v = begin; v < end; ++v) {
        ClearanceSearch s{&mesh, v, I.Margin(mesh.vertices[v])};
        // A first bound: a face across the edge opposite v in v's star.
        const Eigen::Vector3d& x = mesh.vertices[v];
        for (int g : I.Star(v)) {
          const Face& G = mesh.faces[g];
          int b = -1, c = -1;
          for (int u : G) {
            if (u != v) (b < 0 ? b : c) = u;
          }
          if (c < 0) continue;  // a degenerate face
          for (int h : I.Star(b)) {
            const Face& H = mesh.faces[h];
            const bool has_c = H[0] == c || H[1] == c || H[2] == c;
            const bool has_v = H[0] == v || H[1] == v || H[2] == v;
            if (has_c && !has_v) {
              s.best_d2 = std::min(s.best_d2, ClosestOnTriangle(mesh.vertices[H[0]] - x, mesh.vertices[H[1]] - x,
                                                                mesh.vertices[H[2]] - x)
                                                  .point.squaredNorm());
            }
          }
          if (std::isfinite(s.best_d2)) break;
        }
        RTCPointQuery query;
        const Eigen::Vector3d p = mesh.vertices[v] - I.centre;
        query.x = static_cast<float>(p.x());
        query.y = static_cast<float>(p.y());
        query.z = static_cast<float>(p.z());
        query.time = 0;
        query.radius = FloatAtLeast(std::sqrt(s.best_d2) + s.margin);
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(I.scene, &query, &context, ClearanceCallback, &s);
        I.vertex_clearance[v] = std::sqrt(s.best_d2);
      }
    };
    ParallelFor(nv, clearances);
  }
}

MeshIndex::~MeshIndex() = default;

RayHit MeshIndex::Raycast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_max,
                          double t_min) const {
  RayHit out;
  const double len = direction.norm();
  if (!(len > 0) || !std::isfinite(len) || !(t_max > t_min) || mesh_.faces.empty() || !Queryable(origin)) return out;
  const Eigen::Vector3d d = direction / len;
  const Eigen::Vector3d o = origin - impl_->centre;
  const double margin = impl_->Margin(origin);
  float tnear = static_cast<float>(std::max(0.0, t_min - margin));
  // A few retries step past hits that the double-precision refinement puts
  // at or before t_min (e.g. a ray leaving the surface it starts on).
  for (int attempt = 0; attempt < 4; ++attempt) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = static_cast<float>(o.x());
    rh.ray.org_y = static_cast<float>(o.y());
    rh.ray.org_z = static_cast<float>(o.z());
    rh.ray.dir_x = static_cast<float>(d.x());
    rh.ray.dir_y = static_cast<float>(d.y());
    rh.ray.dir_z = static_cast<float>(d.z());
    rh.ray.tnear = tnear;
    rh.ray.tfar = FloatAtLeast(t_max + margin);
    rh.ray.time = 0;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;

    const int f = static_cast<int>(rh.hit.primID);
    const double t = impl_->RefinedRange(mesh_, origin, d, f, rh.ray.tfar);
    if (t > t_min) {
      if (t > t_max) return out;
      out.hit = true;
      out.range = t;
      out.point = origin + t * d;
      out.face = f;
      return out;
    }
    tnear = std::nextafter(rh.ray.tfar, std::numeric_limits<float>::infinity());
  }
  return out;
}

void MeshIndex::RaycastFan(const Eigen::Vector3d& origin, const Eigen::Vector3f* directions, int n, double t_max,
                           RayHit* hits) const {
  constexpr int kChunk = 256;  // rays per Embree stream call
  RTCRayHit rays[kChunk];
  const Eigen::Vector3d o = origin - impl_->centre;
  const float tfar = FloatAtLeast(t_max + impl_->Margin(origin));
  for (int begin = 0; begin < n; begin += kChunk) {
    const int count = std::min(kChunk, n - begin);
    for (int i = 0; i < count; ++i) {
      RTCRayHit& rh = rays[i];
      const Eigen::Vector3f& d = directions[begin + i];
      rh.ray.org_x = static_cast<float>(o.x());
      rh.ray.org_y = static_cast<float>(o.y());
      rh.ray.org_z = static_cast<float>(o.z());
      rh.ray.dir_x = d.x();
      rh.ray.dir_y = d.y();
      rh.ray.dir_z = d.z();
      rh.ray.tnear = 0;
      rh.ray.tfar = tfar;
      rh.ray.time = 0;
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.id = static_cast<unsigned>(i);
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(impl_->scene, &context, rays, static_cast<unsigned>(count), sizeof(RTCRayHit));
    for (int i = 0; i < count; ++i) {
      RayHit& out = hits[begin + i];
      out = RayHit();
      if (rays[i].hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      const Eigen::Vector3d d = directions[begin + i].cast<double>().normalized();
      const int f = static_cast<int>(rays[i].hit.primID);
      const double t = impl_->RefinedRange(mesh_, origin, d, f, rays[i].ray.tfar);
      if (!(t > 0) || t > t_max) continue;
      out.hit = true;
      out.range = t;
      out.point = origin + t * d;
      out.face = f;
    }
  }
}

void MeshIndex::OccludedToward(const Eigen::Vector3d* points, int n, const Eigen::Vector3d& target, double t_min,
                               bool* blocked) const {
  constexpr int kChunk = 256;
  RTCRay rays[kChunk];
  for (int begin = 0; begin < n; begin += kChunk) {
    const int count = std::min(kChunk, n - begin);
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d o = points[begin + i] - impl_->centre;
      const Eigen::Vector3d d = target - points[begin + i];
      const double len = d.norm();
      RTCRay& r = rays[i];
      r.org_x = static_cast<float>(o.x());
      r.org_y = static_cast<float>(o.y());
      r.org_z = static_cast<float>(o.z());
      r.dir_x = static_cast<float>(d.x() / len);
      r.dir_y = static_cast<float>(d.y() / len);
      r.dir_z = static_cast<float>(d.z() / len);
      r.tnear = static_cast<float>(t_min);
      r.tfar = len > t_min ? static_cast<float>(len) : 0.0f;  // tfar < tnear: nothing to test
      r.time = 0;
      r.mask = 0xFFFFFFFFu;
      r.id = static_cast<unsigned>(i);
      r.flags = 0;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Rays from neighbouring points toward one target are coherent (a hint
    // to Embree's stream traversal; the answers are the same).
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded1M(impl_->scene, &context, rays, static_cast<unsigned>(count), sizeof(RTCRay));
    // Embree sets tfar to -inf for an occluded ray.
    for (int i = 0; i < count; ++i) blocked[begin + i] = std::isinf(rays[i].tfar) && rays[i].tfar < 0;
  }
}

ClosestPoint MeshIndex::Closest(const Eigen::Vector3d& q, int hint_face) const {
  ClosestPoint out;
  if (mesh_.faces.empty()) return out;
  if (!Queryable(q)) {  // never reaches Embree: a valid face, an infinite distance
    out.face = 0;
    out.point = mesh_.vertices[static_cast<std::size_t>(mesh_.faces[0][0])];
    out.distance = std::numeric_limits<double>::infinity();
    return out;
  }
  const ClosestSearch s = impl_->Search(mesh_, q, hint_face);
  out.point = q + s.best_offset;
  out.face = s.best_face;
  out.distance = std::sqrt(s.best_d2);
  return out;
}

SurfaceDistance MeshIndex::OrthogonalSignedDistance(const Eigen::Vector3d& q, SurfaceLookup lookup,
                                                    int hint_face) const {
  SurfaceDistance out;
  if (mesh_.faces.empty()) return out;
  if (!Queryable(q)) {  // a valid face and a NaN distance: a solver rejects the step
    out.face = 0;
    out.point = mesh_.vertices[static_cast<std::size_t>(mesh_.faces[0][0])];
    out.normal = impl_->face_normals[0];
    out.signed_distance = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  if (lookup == SurfaceLookup::kNearestVertex) {
    // The paper's: p = the nearest vertex, n = the normal of a face using it.
    int v = impl_->vertex_index->NearestOne(q).first;
    if (v >= 0 && impl_->vertex_faces[v].empty()) {
      // An unreferenced vertex: fall back to the closest face's first corner.
      v = mesh_.faces[Closest(q, hint_face).face][0];
    }
    out.face = impl_->vertex_faces[v].front();
    out.point = mesh_.vertices[v];
  } else {
    const ClosestPoint c = Closest(q, hint_face);
    out.face = c.face;
    out.point = c.point;
  }
  out.normal = impl_->face_normals[out.face];
  out.signed_distance = (q - out.point).dot(out.normal);
  return out;
}

SurfaceDistance MeshIndex::OrthogonalSignedDistance(const Pose& x_gM, const Eigen::Vector3d& l_g, SurfaceLookup lookup,
                                                    int hint_face) const {
  // H = (-)x_gM maps g into M.
  return OrthogonalSignedDistance(x_gM.Inverse() * l_g, lookup, hint_face);
}

double MeshIndex::SignedDistance(const Eigen::Vector3d& q, int hint_face) const {
  if (mesh_.faces.empty()) return std::numeric_limits<double>::infinity();
  if (!Queryable(q)) return std::numeric_limits<double>::quiet_NaN();
  const ClosestSearch s = impl_->Search(mesh_, q, hint_face);
  const int f = s.best_face;
  Eigen::Vector3d pseudonormal;
  switch (s.best_feature) {
    case kInterior:
      pseudonormal = impl_->face_normals[f];
      break;
    case kEdge0:
    case kEdge1:
    case kEdge2:
      pseudonormal = impl_->edge_pseudonormals[3 * f + (s.best_feature - kEdge0)];
      break;
    default:
      pseudonormal = impl_->vertex_pseudonormals[mesh_.faces[f][s.best_feature - kVertex0]];
      break;
  }
  const double d = std::sqrt(s.best_d2);
  return s.best_offset.dot(pseudonormal) > 0 ? -d : d;
}

int MeshIndex::NearestVertex(const Eigen::Vector3d& q) const {
  if (!Queryable(q)) return mesh_.vertices.empty() ? -1 : 0;
  return impl_->vertex_index->NearestOne(q).first;
}

const std::vector<int>& MeshIndex::FacesOfVertex(int v) const { return impl_->vertex_faces.at(v); }

}  // namespace hull
