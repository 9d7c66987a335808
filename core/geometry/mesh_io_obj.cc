// Wavefront OBJ: vertices and (polygon) faces; reader and writer.
#include "geometry/mesh_io_internal.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace hull::mesh_io_internal {

RawMesh ReadObj(std::string_view data, const std::string& file) {
  TextCursor cur(data, file);
  RawMesh m;
  std::vector<int> poly;
  while (!cur.AtEnd()) {
    if (cur.AtLineEnd('#')) {
      cur.NextLine();
      continue;
    }
    const std::string_view kw = cur.Token();
    if (kw == "v") {
      Eigen::Vector3d v;
      v.x() = cur.Double("the vertex x coordinate");
      v.y() = cur.Double("the vertex y coordinate");
      v.z() = cur.Double("the vertex z coordinate");
      m.vertices.push_back(v);  // a w or colour that follows is ignored
    } else if (kw == "f") {
      const SourceLocation face_at = cur.TokenLocation();
      poly.clear();
      const auto n = static_cast<std::int64_t>(m.vertices.size());
      while (!cur.AtLineEnd('#')) {
        const std::string_view tok = cur.Token();
        const std::string_view first = tok.substr(0, tok.find('/'));
        std::int64_t i = 0;
        if (!ParseInt64(first, i)) {
          cur.FailAtToken("expected a vertex index (v, v/vt, v/vt/vn or v//vn), found " + Quote(tok));
        }
        // 1-based; negative counts back from the last vertex read so far.
        const std::int64_t index = i > 0 ? i - 1 : n + i;
        if (i == 0 || index < 0 || index >= n) {
          cur.FailAtToken("face vertex index " + std::to_string(i) + " out of range; " +
                          (n == 0 ? std::string("no vertices are defined before this line")
                                  : "expected 1 to " + std::to_string(n) + " or -1 to -" + std::to_string(n)));
        }
        poly.push_back(static_cast<int>(index));
      }
      if (poly.size() < 3) {
        throw InputError(face_at, "a face with " + std::to_string(poly.size()) + " vertices; expected at least 3");
      }
      for (std::size_t k = 1; k + 1 < poly.size(); ++k) m.faces.push_back({poly[0], poly[k], poly[k + 1]});
    }
    // vt, vn, g, o, s, usemtl, mtllib, l, p, ...: not geometry we keep.
    cur.NextLine();
  }
  return m;
}

std::string WriteObj(const TriangleMesh& mesh) {
  std::string out = "# written by HullInspect: " + std::to_string(mesh.vertices.size()) + " vertices, " +
                    std::to_string(mesh.faces.size()) + " faces\n";
  out.reserve(out.size() + mesh.vertices.size() * 64 + mesh.faces.size() * 32);
  for (const auto& v : mesh.vertices) {
    out += "v ";
    AppendDouble(out, v.x());
    out += ' ';
    AppendDouble(out, v.y());
    out += ' ';
    AppendDouble(out, v.z());
    out += '\n';
  }
  for (const Face& f : mesh.faces) {
    out += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " + std::to_string(f[2] + 1) + "\n";
  }
  return out;
}

}  // namespace hull::mesh_io_internal
