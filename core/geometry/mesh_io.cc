// Mesh readers and writers. STL, PLY, OBJ and OFF are read by our own
// double-precision parsers (errors name the line and column); every other
// format goes through assimp. Readers produce a RawMesh; LoadMesh then
// welds triangle soups, applies the model-frame transform and orients.
#include "geometry/mesh_io.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "base/csv.h"
#include "base/error.h"
#include "base/file_io.h"
#include "geometry/mesh_plugins.h"

namespace hull {
namespace {

// What a reader produced, before LoadMesh's post-processing.
struct RawMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  bool soup = false;  // vertices repeated per face (STL, assimp): welding applies
};

std::string Quote(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string q = "'";
  for (char c : s.substr(0, kMax)) q += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  if (s.size() > kMax) q += "...";
  return q + "'";
}

[[noreturn]] void FailFile(const std::string& file, const std::string& message, const std::string& field = "") {
  throw InputError({file, 0, 0, field}, message);
}

// ---- a cursor over text that knows its line and column ------------------

class TextCursor {
 public:
  TextCursor(std::string_view text, const std::string& file) : t_(text), file_(file) {}
  // A cursor that starts at `pos`, the beginning of line `line`.
  TextCursor(std::string_view text, const std::string& file, std::size_t pos, int line)
      : t_(text), file_(file), pos_(pos), line_start_(pos), line_(line) {}

  bool AtEnd() const { return pos_ >= t_.size(); }
  std::size_t pos() const { return pos_; }
  int line() const { return line_; }

  // Skips spaces and tabs (and a '\r' before the newline) on this line.
  void SkipBlanks() {
    while (pos_ < t_.size() &&
           (t_[pos_] == ' ' || t_[pos_] == '\t' || t_[pos_] == '\r' || t_[pos_] == '\f' || t_[pos_] == '\v')) {
      ++pos_;
    }
  }
  // Skips white space across lines and, when comment != 0, comments that
  // run from that character to the end of the line.
  void SkipSpace(char comment = 0) {
    while (true) {
      SkipBlanks();
      if (AtEnd()) return;
      if (t_[pos_] == '\n') {
        NewLine(pos_ + 1);
      } else if (comment != 0 && t_[pos_] == comment) {
        NextLine();
      } else {
        return;
      }
    }
  }
  // True at the end of the line (or of the text, or at a comment).
  bool AtLineEnd(char comment = 0) {
    SkipBlanks();
    return AtEnd() || t_[pos_] == '\n' || (comment != 0 && t_[pos_] == comment);
  }
  // Moves to the start of the next line.
  void NextLine() {
    const std::size_t nl = t_.find('\n', pos_);
    if (nl == std::string_view::npos) {
      pos_ = t_.size();
    } else {
      NewLine(nl + 1);
    }
  }
  // The rest of the current line, without the newline; moves past it.
  std::string_view RestOfLine() {
    SkipBlanks();
    const std::size_t start = pos_;
    std::size_t end = t_.find('\n', pos_);
    if (end == std::string_view::npos) end = t_.size();
    std::string_view s = t_.substr(start, end - start);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    pos_ = end;
    return s;
  }
  // The next token on this line ("" at the end of the line).
  std::string_view Token() {
    SkipBlanks();
    token_pos_ = pos_;
    while (pos_ < t_.size() && !std::isspace(static_cast<unsigned char>(t_[pos_]))) ++pos_;
    return t_.substr(token_pos_, pos_ - token_pos_);
  }
  // The next token, on this line or a later one.
  std::string_view TokenAcrossLines(char comment = 0) {
    SkipSpace(comment);
    return Token();
  }

  double Double(const std::string& what) {
    const std::string_view tok = Token();
    double v = 0;
    if (tok.empty()) FailAtToken("expected " + what + ", found the end of the line");
    if (!ParseFiniteDouble(tok, v)) FailAtToken("expected " + what + " (a finite number), found " + Quote(tok));
    return v;
  }
  std::int64_t Integer(const std::string& what) {
    const std::string_view tok = Token();
    std::int64_t v = 0;
    if (tok.empty()) FailAtToken("expected " + what + ", found the end of the line");
    if (!ParseInt64(tok, v)) FailAtToken("expected " + what + " (an integer), found " + Quote(tok));
    return v;
  }
  // Requires the next token (across lines) to be `word`.
  void Expect(std::string_view word, const std::string& context) {
    const std::string_view tok = TokenAcrossLines();
    if (tok != word) {
      FailAtToken("expected '" + std::string(word) + "' " + context + ", found " +
                  (tok.empty() ? std::string("the end of the file") : Quote(tok)));
    }
  }

  // Location of the last token read.
  SourceLocation TokenLocation() const { return {file_, line_, static_cast<int>(token_pos_ - line_start_) + 1, ""}; }
  [[noreturn]] void FailAtToken(const std::string& message) const { throw InputError(TokenLocation(), message); }
  [[noreturn]] void FailHere(const std::string& message) const {
    throw InputError({file_, line_, static_cast<int>(pos_ - line_start_) + 1, ""}, message);
  }

 private:
  void NewLine(std::size_t start) {
    pos_ = start;
    line_start_ = start;
    ++line_;
  }

  std::string_view t_;
  const std::string& file_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  std::size_t token_pos_ = 0;
  int line_ = 1;
};

// ---- little/big-endian binary values ---------------------------------------

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

bool HostIsLittleEndian() {
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

// Reads `n` bytes at p in the file's byte order into a host-order value.
template <typename T>
T LoadBytes(const char* p, bool little) {
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), p, sizeof(T));
  if (little != HostIsLittleEndian()) std::reverse(bytes.begin(), bytes.end());
  T v;
  std::memcpy(&v, bytes.data(), sizeof(T));
  return v;
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

template <typename T>
void StoreLittle(std::string& out, T v) {
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), &v, sizeof(T));
  if (!HostIsLittleEndian()) std::reverse(bytes.begin(), bytes.end());
  out.append(bytes.data(), bytes.size());
}

// ---- STL -------------------------------------------------------------------

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

RawMesh ReadStl(std::string_view data, const std::string& file) {
  return StlIsBinary(data) ? ReadStlBinary(data, file) : ReadStlAscii(data, file);
}

// ---- PLY -------------------------------------------------------------------

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

// ---- OBJ -------------------------------------------------------------------

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

// ---- OFF -------------------------------------------------------------------

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

// ---- assimp ------------------------------------------------------------------

RawMesh ReadWithAssimp(const std::string& data, const std::string& file, const std::string& ext) {
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices;
  // A plain file is read by name so that files it refers to (a glTF's .bin,
  // an OBJ's .mtl) are found; a compressed one from the inflated memory.
  const aiScene* scene = nullptr;
  std::string lower = file;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (EndsWith(lower, ".gz")) {
    const std::string hint = ext.empty() ? std::string() : ext.substr(1);
    scene = aiImportFileFromMemory(data.data(), static_cast<unsigned>(data.size()), flags, hint.c_str());
  } else {
    scene = aiImportFile(file.c_str(), flags);
  }
  if (!scene) {
    const std::string why = aiGetErrorString();
    FailFile(file, "cannot read the mesh" + (why.empty() ? std::string() : ": " + why));
  }
  RawMesh m;
  m.soup = true;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh* mesh = scene->mMeshes[i];
    const int base = static_cast<int>(m.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      m.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      m.faces.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                         base + static_cast<int>(face.mIndices[2])});
    }
  }
  aiReleaseImport(scene);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (!m.vertices[v].allFinite()) FailFile(file, "non-finite vertex coordinate", "vertex " + std::to_string(v));
  }
  return m;
}

// `report`, when given, receives what a plugin importer reported.
RawMesh ReadAny(const std::string& path, std::vector<std::pair<std::string, std::string>>* report = nullptr) {
  if (auto p = ReadMeshWithPlugin(path)) {  // a plugin outbids the readers below
    if (report) *report = std::move(p->report);
    return {std::move(p->vertices), std::move(p->faces), std::move(p->scalars), p->soup};
  }
  const std::string data = ReadFileToString(path);
  if (data.empty()) FailFile(path, "the file is empty; expected a mesh");
  const std::string ext = MeshExtension(path);
  if (ext == ".stl") return ReadStl(data, path);
  if (ext == ".ply") return ReadPly(data, path);
  if (ext == ".obj") return ReadObj(data, path);
  if (ext == ".off") return ReadOff(data, path);
  return ReadWithAssimp(data, path, ext);
}

// ---- writers -------------------------------------------------------------------

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

std::string Gzip(const std::string& data, const std::string& path) {
  z_stream zs{};
  if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("cannot write " + path + ": zlib initialisation failed");
  }
  std::string out(deflateBound(&zs, static_cast<uLong>(data.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw std::runtime_error("cannot write " + path + ": gzip compression failed");
  return out;
}

}  // namespace

TriangleMesh LoadMesh(const std::string& path, const MeshLoadOptions& options) {
  if (!std::isfinite(options.scale) || options.scale == 0) {
    throw OptionError("scale", "must be finite and non-zero, got " + FormatDouble(options.scale));
  }
  RawMesh raw = ReadAny(path, options.import_report);
  if (raw.faces.empty()) {
    FailFile(path, raw.vertices.empty() ? "the file contains no geometry; expected a triangle mesh"
                                        : "the file has " + std::to_string(raw.vertices.size()) +
                                              " vertices but no faces; expected a triangle mesh (a point cloud "
                                              "is read with LoadPointCloud)");
  }
  TriangleMesh mesh;
  mesh.vertices = std::move(raw.vertices);
  mesh.faces = std::move(raw.faces);
  mesh.vertex_scalars = std::move(raw.scalars);
  if (options.weld && raw.soup) mesh.WeldVertices(0.0);
  const bool identity =
      options.pose.translation() == Eigen::Vector3d::Zero() && options.pose.rotation() == Eigen::Matrix3d::Identity();
  if (options.scale != 1.0 || !identity) {
    mesh.Transform(options.pose, options.scale);
  }
  const OrientationReport report = options.orient_outward ? mesh.OrientOutward() : mesh.CheckTopology();
  if (options.orientation) *options.orientation = report;
  mesh.ComputeNormals();
  return mesh;
}

std::vector<Eigen::Vector3d> LoadPointCloud(const std::string& path) {
  RawMesh raw = ReadAny(path);
  if (raw.vertices.empty()) FailFile(path, "the file contains no points");
  if (!raw.soup) return std::move(raw.vertices);
  // A triangle soup repeats each point once per face: keep one of each.
  TriangleMesh mesh;
  mesh.vertices = std::move(raw.vertices);
  mesh.WeldVertices(0.0);
  return std::move(mesh.vertices);
}

void SaveMesh(const TriangleMesh& mesh, const std::string& path, const MeshSaveOptions& options) {
  const int nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (mesh.faces[f][k] < 0 || mesh.faces[f][k] >= nv) {
        throw std::invalid_argument("SaveMesh " + path + ": face " + std::to_string(f) + " uses vertex " +
                                    std::to_string(mesh.faces[f][k]) + " of " + std::to_string(nv));
      }
    }
  }
  for (const auto& [name, values] : mesh.vertex_scalars) {
    if (values.size() != mesh.vertices.size()) {
      throw std::invalid_argument("SaveMesh " + path + ": scalar '" + name + "' has " + std::to_string(values.size()) +
                                  " values for " + std::to_string(nv) + " vertices");
    }
  }
  const std::string ext = MeshExtension(path);
  std::string data;
  if (ext == ".ply") {
    data = WritePly(mesh, options);
  } else if (ext == ".obj") {
    data = WriteObj(mesh);
  } else if (ext == ".stl") {
    data = WriteStl(mesh);
  } else {
    throw std::invalid_argument("SaveMesh " + path + ": cannot write '" + ext + "' files; use .ply, .obj or .stl");
  }
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (EndsWith(lower, ".gz")) data = Gzip(data, path);
  WriteFileAtomic(path, data);
}

bool IsMeshFile(const std::string& path) { return BuiltinMeshScore(MeshExtension(path)) > 0 || PluginReadsMesh(path); }

}  // namespace hull
