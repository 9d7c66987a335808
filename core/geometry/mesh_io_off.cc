// OFF (and COFF, NOFF, CNOFF, STOFF): reader.
#include "geometry/mesh_io_internal.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace hull::mesh_io_internal {

RawMesh ReadOff(std::string_view data, const std::string& file) {
  TextCursor cur(data, file);
  const std::string_view magic = cur.TokenAcrossLines('#');
  if (magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF" && magic != "STOFF") {
    cur.FailAtToken("expected 'OFF' (or COFF, NOFF, CNOFF, STOFF) at the start of an OFF file, found " +
                    (magic.empty() ? std::string("nothing") : Quote(magic)));
  }
  cur.SkipSpace('#');
  const std::int64_t nv = cur.Integer("the number of vertices");
  if (cur.AtLineEnd('#')) cur.SkipSpace('#');
  const std::int64_t nf = cur.Integer("the number of faces");
  if (nv < 0 || nf < 0) cur.FailAtToken("negative vertex or face count");
  if (static_cast<std::uint64_t>(nv) + static_cast<std::uint64_t>(nf) > data.size()) {
    cur.FailAtToken("the counts announce more vertices and faces than the file can hold");
  }
  cur.NextLine();  // the edge count, if any, is not used
  RawMesh m;
  m.vertices.reserve(static_cast<std::size_t>(nv));
  for (std::int64_t i = 0; i < nv; ++i) {
    cur.SkipSpace('#');
    if (cur.AtEnd()) {
      cur.FailHere("the file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    }
    Eigen::Vector3d v;
    v.x() = cur.Double("the vertex x coordinate");
    v.y() = cur.Double("the vertex y coordinate");
    v.z() = cur.Double("the vertex z coordinate");
    m.vertices.push_back(v);
    cur.NextLine();
  }
  std::vector<int> poly;
  for (std::int64_t f = 0; f < nf; ++f) {
    cur.SkipSpace('#');
    if (cur.AtEnd()) {
      cur.FailHere("the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    }
    const std::int64_t n = cur.Integer("the number of vertices of the face");
    if (n < 3) cur.FailAtToken("a face with " + std::to_string(n) + " vertices; expected at least 3");
    poly.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t i = cur.Integer("a vertex index");
      if (i < 0 || i >= nv) {
        cur.FailAtToken("face vertex index " + std::to_string(i) + " out of range; expected 0 to " +
                        std::to_string(nv - 1));
      }
      poly.push_back(static_cast<int>(i));
    }
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) m.faces.push_back({poly[0], poly[k], poly[k + 1]});
    cur.NextLine();  // a colour that follows is ignored
  }
  return m;
}

}  // namespace hull::mesh_io_internal
