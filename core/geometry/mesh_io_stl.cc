// STL, ASCII and binary: reader and (binary) writer.
#include "geometry/mesh_io_internal.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace hull::mesh_io_internal {
namespace {

// Binary when the size is exactly 84 + 50 n for the count n in the header
// (some binary files begin with "solid" too); ASCII when the text begins with
// "solid" and has no NUL byte near the start.
bool StlIsBinary(std::string_view data) {
  if (data.size() >= 84) {
    const auto n = LoadBytes<std::uint32_t>(data.data() + 80, true);
    if (84 + 50 * static_cast<std::uint64_t>(n) == data.size()) return true;
  }
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (data.compare(i, 5, "solid") != 0) return true;
  return data.substr(0, std::min<std::size_t>(data.size(), 512)).find('\0') != std::string_view::npos;
}

RawMesh ReadStlBinary(std::string_view data, const std::string& file) {
  if (data.size() < 84) {
    FailFile(file, "truncated binary STL: " + std::to_string(data.size()) +
                       " bytes, less than the 84-byte header and triangle count");
  }
  const auto n = LoadBytes<std::uint32_t>(data.data() + 80, true);
  const std::uint64_t need = 84 + 50 * static_cast<std::uint64_t>(n);
  if (data.size() < need) {
    FailFile(file, "truncated binary STL: the header announces " + std::to_string(n) + " triangles (" +
                       std::to_string(need) + " bytes) but the file has " + std::to_string(data.size()) + " bytes");
  }
  if (data.size() > need) {
    FailFile(file, "binary STL with " + std::to_string(data.size() - need) + " bytes after the " + std::to_string(n) +
                       " triangles the header announces");
  }
  // A first pass over the records, before any allocation: a file of mostly
  // zero-area triangles (a "degenerate-mesh bomb") is refused at once.
  {
    std::uint64_t degenerate = 0;
    for (std::uint32_t t = 0; t < n; ++t) {
      const char* rec = data.data() + 84 + 50 * static_cast<std::size_t>(t);
      Eigen::Vector3d v[3];
      for (int k = 0; k < 3; ++k) {
        for (int c = 0; c < 3; ++c) v[k][c] = LoadBytes<float>(rec + 12 + 12 * k + 4 * c, true);
      }
      if (!((v[1] - v[0]).cross(v[2] - v[0]).squaredNorm() > 0)) ++degenerate;
    }
    if (n > 0 && 2 * degenerate > n) FailDegenerate(file, degenerate, n);
  }
  RawMesh m;
  m.soup = true;
  m.vertices.reserve(3 * static_cast<std::size_t>(n));
  m.faces.reserve(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* rec = data.data() + 84 + 50 * static_cast<std::size_t>(t);
    const int base = static_cast<int>(m.vertices.size());
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d v;
      for (int c = 0; c < 3; ++c) v[c] = LoadBytes<float>(rec + 12 + 12 * k + 4 * c, true);
      if (!v.allFinite()) FailFile(file, "non-finite vertex coordinate", "triangle " + std::to_string(t));
      m.vertices.push_back(v);
    }
    m.faces.push_back({base, base + 1, base + 2});
  }
  return m;
}

RawMesh ReadStlAscii(std::string_view data, const std::string& file) {
  TextCursor cur(data, file);
  RawMesh m;
  m.soup = true;
  cur.Expect("solid", "at the start of an ASCII STL file");
  cur.RestOfLine();  // the solid's name
  while (true) {
    const std::string_view tok = cur.TokenAcrossLines();
    if (tok.empty()) break;
    if (tok == "endsolid") {
      cur.RestOfLine();
      const std::string_view next = cur.TokenAcrossLines();
      if (next.empty()) break;
      if (next != "solid") cur.FailAtToken("expected 'solid' or the end of the file, found " + Quote(next));
      cur.RestOfLine();
      continue;
    }
    if (tok != "facet") cur.FailAtToken("expected 'facet' or 'endsolid', found " + Quote(tok));
    cur.Expect("normal", "after 'facet'");
    for (int c = 0; c < 3; ++c) cur.Double("a normal component");
    cur.Expect("outer", "after the facet normal");
    cur.Expect("loop", "after 'outer'");
    const int base = static_cast<int>(m.vertices.size());
    for (int k = 0; k < 3; ++k) {
      cur.Expect("vertex", "(a facet has three vertices)");
      Eigen::Vector3d v;
      v.x() = cur.Double("the vertex x coordinate");
      v.y() = cur.Double("the vertex y coordinate");
      v.z() = cur.Double("the vertex z coordinate");
      m.vertices.push_back(v);
    }
    cur.Expect("endloop", "after the third vertex");
    cur.Expect("endfacet", "after 'endloop'");
    m.faces.push_back({base, base + 1, base + 2});
  }
  return m;
}

}  // namespace

RawMesh ReadStl(std::string_view data, const std::string& file) {
  // An ASCII STL saved by an editor that writes a UTF-8 byte order mark was
  // read as binary ("announces 1919252000 triangles"): the mark is skipped
  // when what follows it is ASCII STL.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (data.substr(0, 3) == kByteOrderMark && !StlIsBinary(data.substr(3))) return ReadStlAscii(data.substr(3), file);
  return StlIsBinary(data) ? ReadStlBinary(data, file) : ReadStlAscii(data, file);
}

std::string WriteStl(const TriangleMesh& mesh) {
  std::string out(80, ' ');
  const char title[] = "binary STL written by HullInspect";  // must not begin with "solid"
  std::memcpy(out.data(), title, sizeof(title) - 1);
  StoreLittle(out, static_cast<std::uint32_t>(mesh.faces.size()));
  out.reserve(84 + 50 * mesh.faces.size());
  for (const Face& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    Eigen::Vector3d n = (mesh.vertices[f[1]] - a).cross(mesh.vertices[f[2]] - a);
    const double len = n.norm();
    n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) StoreLittle(out, static_cast<float>(n[c]));
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) StoreLittle(out, static_cast<float>(mesh.vertices[f[k]][c]));
    }
    StoreLittle(out, static_cast<std::uint16_t>(0));
  }
  return out;
}

}  // namespace hull::mesh_io_internal
