// PLY, ASCII and binary (either byte order), any numeric property types,
// polygons triangulated, other vertex properties kept as scalars: reader
// and writer.
#include "geometry/mesh_io_internal.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace hull::mesh_io_internal {
namespace {

enum class PlyType { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

std::size_t SizeOf(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUInt8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUInt16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUInt32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

double LoadValue(const char* p, PlyType t, bool little) {
  switch (t) {
    case PlyType::kInt8:
      return LoadBytes<std::int8_t>(p, little);
    case PlyType::kUInt8:
      return LoadBytes<std::uint8_t>(p, little);
    case PlyType::kInt16:
      return LoadBytes<std::int16_t>(p, little);
    case PlyType::kUInt16:
      return LoadBytes<std::uint16_t>(p, little);
    case PlyType::kInt32:
      return LoadBytes<std::int32_t>(p, little);
    case PlyType::kUInt32:
      return LoadBytes<std::uint32_t>(p, little);
    case PlyType::kFloat32:
      return LoadBytes<float>(p, little);
    case PlyType::kFloat64:
      return LoadBytes<double>(p, little);
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUInt8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

// The type named by `tok`, the token the cursor read last.
PlyType PlyTypeOf(const TextCursor& cur, std::string_view tok, const char* role) {
  static const std::pair<const char*, PlyType> kTypes[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUInt8},
      {"uint8", PlyType::kUInt8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUInt16},  {"uint16", PlyType::kUInt16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUInt32},     {"uint32", PlyType::kUInt32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const auto& [name, type] : kTypes) {
    if (tok == name) return type;
  }
  cur.FailAtToken(std::string("unknown PLY type ") + (tok.empty() ? "(none)" : Quote(tok)) + " for the " + role +
                  "; expected char, uchar, short, ushort, int, uint, float, double or int8 ... float64");
}

enum class PlyFormat { kAscii, kBinaryLittle, kBinaryBig };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  // byte offset of the data
  int body_line = 0;     // its line (ASCII)
};

PlyHeader ReadPlyHeader(std::string_view data, const std::string& file) {
  TextCursor cur(data, file);
  PlyHeader h;
  if (cur.Token() != "ply") cur.FailAtToken("expected 'ply' on the first line of a PLY file");
  cur.NextLine();
  bool have_format = false;
  while (true) {
    if (cur.AtEnd()) cur.FailHere("the PLY header has no 'end_header' line");
    const std::string_view kw = cur.Token();
    if (kw.empty() || kw == "comment" || kw == "obj_info") {
      cur.NextLine();
      continue;
    }
    if (kw == "format") {
      const std::string_view f = cur.Token();
      if (f == "ascii") {
        h.format = PlyFormat::kAscii;
      } else if (f == "binary_little_endian") {
        h.format = PlyFormat::kBinaryLittle;
      } else if (f == "binary_big_endian") {
        h.format = PlyFormat::kBinaryBig;
      } else {
        cur.FailAtToken("unknown PLY format " + Quote(f) +
                        "; expected ascii, binary_little_endian or binary_big_endian");
      }
      if (cur.Token() != "1.0") cur.FailAtToken("expected PLY version 1.0");
      have_format = true;
    } else if (kw == "element") {
      PlyElement e;
      e.name = std::string(cur.Token());
      if (e.name.empty()) cur.FailAtToken("expected an element name");
      const std::int64_t n = cur.Integer("the element count");
      if (n < 0) cur.FailAtToken("negative element count");
      // Every record takes at least a byte: refuse counts the file cannot hold.
      if (static_cast<std::uint64_t>(n) > data.size()) {
        cur.FailAtToken("the header announces " + std::to_string(n) + " '" + e.name + "' records but the file has " +
                        std::to_string(data.size()) + " bytes");
      }
      e.count = static_cast<std::size_t>(n);
      h.elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (h.elements.empty()) cur.FailAtToken("'property' before any 'element'");
      PlyProperty p;
      const std::string_view t = cur.Token();
      if (t == "list") {
        p.is_list = true;
        p.count_type = PlyTypeOf(cur, cur.Token(), "list count");
        if (p.count_type == PlyType::kFloat32 || p.count_type == PlyType::kFloat64) {
          cur.FailAtToken("a list count must have an integer type");
        }
        p.type = PlyTypeOf(cur, cur.Token(), "list items");
      } else {
        p.type = PlyTypeOf(cur, t, "property");
      }
      p.name = std::string(cur.Token());
      if (p.name.empty()) cur.FailAtToken("expected a property name");
      for (const PlyProperty& q : h.elements.back().properties) {
        if (q.name == p.name) {
          cur.FailAtToken("property '" + p.name + "' declared twice in element '" + h.elements.back().name + "'");
        }
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (kw == "end_header") {
      if (!have_format) cur.FailAtToken("the PLY header has no 'format' line");
      cur.NextLine();
      h.body = cur.pos();
      h.body_line = cur.line();
      return h;
    } else {
      cur.FailAtToken("unexpected " + Quote(kw) +
                      " in the PLY header; expected format, element, property, comment or end_header");
    }
    if (!cur.AtLineEnd()) {
      cur.Token();
      cur.FailAtToken("unexpected text at the end of the header line");
    }
    cur.NextLine();
  }
}

// Reads the values of a PLY body, ASCII or binary, one at a time.
class PlyValues {
 public:
  PlyValues(std::string_view data, const PlyHeader& h, const std::string& file)
      : data_(data), file_(file), format_(h.format), pos_(h.body), text_(data, file, h.body, h.body_line) {}

  void SetRecord(const std::string* element, std::size_t index) {
    element_ = element;
    index_ = index;
  }

  double Next(PlyType t, const char* what) {
    if (format_ == PlyFormat::kAscii) {
      const std::string_view tok = text_.TokenAcrossLines();
      double v = 0;
      if (tok.empty()) {
        text_.FailAtToken("the file ends in " + Record() + "; expected " + what);
      }
      if (!ParseFiniteDouble(tok, v)) {
        text_.FailAtToken("expected " + std::string(what) + " (a number) in " + Record() + ", found " + Quote(tok));
      }
      return v;
    }
    const std::size_t n = SizeOf(t);
    if (pos_ + n > data_.size()) {
      FailFile(file_, "truncated binary PLY: the file ends in " + Record() + " (byte " + std::to_string(pos_) + ")",
               Record());
    }
    const double v = LoadValue(data_.data() + pos_, t, format_ == PlyFormat::kBinaryLittle);
    pos_ += n;
    return v;
  }

  std::string Record() const { return "element '" + *element_ + "' " + std::to_string(index_); }
  [[noreturn]] void Fail(const std::string& message) const {
    if (format_ == PlyFormat::kAscii) text_.FailAtToken(message);
    FailFile(file_, message, Record());
  }
  // Rejects data after the last element.
  void CheckEnd() {
    if (format_ == PlyFormat::kAscii) {
      if (!text_.TokenAcrossLines().empty()) text_.FailAtToken("unexpected data after the last PLY element");
    } else if (pos_ != data_.size()) {
      FailFile(file_, "binary PLY with " + std::to_string(data_.size() - pos_) +
                          " bytes after the last element the header announces");
    }
  }

 private:
  std::string_view data_;
  const std::string& file_;
  PlyFormat format_;
  std::size_t pos_;
  TextCursor text_;
  const std::string* element_ = nullptr;
  std::size_t index_ = 0;
};

// PLY property names are single tokens.
std::string PlyName(const std::string& name) {
  std::string s = name.empty() ? std::string("scalar") : name;
  for (char& c : s) {
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  }
  if (s == "x" || s == "y" || s == "z") s = "scalar_" + s;
  return s;
}

void AppendFloat(std::string& out, float v) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  (void)ec;
  out.append(buf, p);
}

}  // namespace

RawMesh ReadPly(std::string_view data, const std::string& file) {
  const PlyHeader h = ReadPlyHeader(data, file);
  RawMesh m;
  std::size_t num_vertices = 0;
  for (const PlyElement& e : h.elements) {
    if (e.name == "vertex") num_vertices = e.count;
  }
  PlyValues values(data, h, file);
  bool have_vertices = false;
  for (const PlyElement& e : h.elements) {
    const int np = static_cast<int>(e.properties.size());
    if (e.name == "vertex") {
      // x, y, z and every other scalar property (as vertex_scalars).
      std::array<int, 3> xyz{-1, -1, -1};
      std::vector<int> scalar_of(np, -1);
      for (int i = 0; i < np; ++i) {
        const PlyProperty& p = e.properties[i];
        if (p.is_list) continue;
        if (p.name == "x" || p.name == "y" || p.name == "z") {
          xyz[p.name[0] - 'x'] = i;
        } else {
          scalar_of[i] = static_cast<int>(m.scalars.size());
          m.scalars.emplace_back(p.name, std::vector<double>());
          m.scalars.back().second.reserve(e.count);
        }
      }
      for (int c = 0; c < 3; ++c) {
        if (xyz[c] < 0) {
          FailFile(file, std::string("the PLY vertex element has no '") + static_cast<char>('x' + c) + "' property");
        }
      }
      m.vertices.resize(e.count);
      for (std::size_t r = 0; r < e.count; ++r) {
        values.SetRecord(&e.name, r);
        for (int i = 0; i < np; ++i) {
          const PlyProperty& p = e.properties[i];
          if (p.is_list) {
            const double n = values.Next(p.count_type, "a list length");
            for (double k = 0; k < n; ++k) values.Next(p.type, "a list item");
            continue;
          }
          const double v = values.Next(p.type, p.name.c_str());
          if (i == xyz[0] || i == xyz[1] || i == xyz[2]) {
            if (!std::isfinite(v)) values.Fail("non-finite coordinate " + p.name);
            m.vertices[r][p.name[0] - 'x'] = v;
          } else {
            m.scalars[scalar_of[i]].second.push_back(v);
          }
        }
      }
      have_vertices = true;
    } else if (e.name == "face") {
      int list = -1;
      for (int i = 0; i < np; ++i) {
        const PlyProperty& p = e.properties[i];
        if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) list = i;
      }
      if (list < 0 && e.count > 0) {
        FailFile(file, "the PLY face element has no 'vertex_indices' (or 'vertex_index') list property");
      }
      m.faces.reserve(m.faces.size() + e.count);
      std::vector<int> poly;
      for (std::size_t r = 0; r < e.count; ++r) {
        values.SetRecord(&e.name, r);
        for (int i = 0; i < np; ++i) {
          const PlyProperty& p = e.properties[i];
          if (!p.is_list) {
            values.Next(p.type, p.name.c_str());
            continue;
          }
          const double n = values.Next(p.count_type, "the number of vertices of the face");
          if (i != list) {
            for (double k = 0; k < n; ++k) values.Next(p.type, "a list item");
            continue;
          }
          if (n < 3) {
            values.Fail("a face with " + FormatDouble(n) + " vertices; expected at least 3");
          }
          poly.clear();
          for (double k = 0; k < n; ++k) {
            const double v = values.Next(p.type, "a vertex index");
            if (v < 0 || v >= static_cast<double>(num_vertices) || v != std::floor(v)) {
              values.Fail("face vertex index " + FormatDouble(v) + " out of range; expected 0 to " +
                          std::to_string(static_cast<long long>(num_vertices) - 1));
            }
            poly.push_back(static_cast<int>(v));
          }
          for (std::size_t k = 1; k + 1 < poly.size(); ++k) m.faces.push_back({poly[0], poly[k], poly[k + 1]});
        }
      }
    } else {
      // Any other element (edges, materials, ...) is read past.
      for (std::size_t r = 0; r < e.count; ++r) {
        values.SetRecord(&e.name, r);
        for (const PlyProperty& p : e.properties) {
          const double n = p.is_list ? values.Next(p.count_type, "a list length") : 1;
          for (double k = 0; k < n; ++k) values.Next(p.type, p.name.c_str());
        }
      }
    }
  }
  if (!have_vertices) FailFile(file, "the PLY file has no 'vertex' element");
  values.CheckEnd();
  return m;
}

std::string WritePly(const TriangleMesh& mesh, const MeshSaveOptions& o) {
  const auto& scalars = mesh.vertex_scalars;
  const bool with_scalars = o.include_scalars && !scalars.empty();
  const char* coord_type = o.double_precision ? "double" : "float";
  std::string out = "ply\nformat ";
  out += o.binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  out += "comment written by HullInspect\n";
  out += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
  for (const char* axis : {"x", "y", "z"}) out += std::string("property ") + coord_type + " " + axis + "\n";
  if (with_scalars) {
    for (const auto& [name, values] : scalars) out += "property double " + PlyName(name) + "\n";
  }
  out += "element face " + std::to_string(mesh.faces.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  const std::size_t per_vertex =
      (o.double_precision ? 24 : 12) + (with_scalars ? 8 * scalars.size() : 0) + (o.binary ? 0 : 32);
  out.reserve(out.size() + mesh.vertices.size() * per_vertex + mesh.faces.size() * (o.binary ? 13 : 32));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const double x = mesh.vertices[v][c];
      if (o.binary) {
        if (o.double_precision) {
          StoreLittle(out, x);
        } else {
          StoreLittle(out, static_cast<float>(x));
        }
      } else {
        if (c > 0) out += ' ';
        if (o.double_precision) {
          AppendDouble(out, x);
        } else {
          AppendFloat(out, static_cast<float>(x));
        }
      }
    }
    if (with_scalars) {
      for (const auto& [name, values] : scalars) {
        if (o.binary) {
          StoreLittle(out, values[v]);
        } else {
          out += ' ';
          AppendDouble(out, values[v]);
        }
      }
    }
    if (!o.binary) out += '\n';
  }
  for (const Face& f : mesh.faces) {
    if (o.binary) {
      out += static_cast<char>(3);
      for (int k = 0; k < 3; ++k) StoreLittle(out, static_cast<std::int32_t>(f[k]));
    } else {
      out += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
    }
  }
  return out;
}

}  // namespace hull::mesh_io_internal
