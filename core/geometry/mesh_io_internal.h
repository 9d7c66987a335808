// Private to the mesh readers and writers (core/geometry/mesh_io*.cc): what
// a reader produces, the text cursor that knows its line and column, binary
// value helpers, and the per-format entry points mesh_io.cc dispatches to.
// Included by those files only.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/csv.h"
#include "base/error.h"
#include "geometry/mesh_io.h"
#include "geometry/triangle_mesh.h"

namespace hull::mesh_io_internal {

// What a reader produced, before LoadMesh's post-processing.
struct RawMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  std::vector<std::pair<std::string, std::vector<double>>> scalars;
  bool soup = false;  // vertices repeated per face (STL, assimp): welding applies
};

// `s` in quotes for a message: at most 40 characters, unprintable ones as '?'.
std::string Quote(std::string_view s);

// Throws InputError naming the file (and `field`), without a line.
[[noreturn]] void FailFile(const std::string& file, const std::string& message, const std::string& field = "");

// Throws InputError: more than half of the triangles have zero area.
[[noreturn]] void FailDegenerate(const std::string& file, std::uint64_t degenerate, std::uint64_t faces);

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

inline bool HostIsLittleEndian() {
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

template <typename T>
void StoreLittle(std::string& out, T v) {
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), &v, sizeof(T));
  if (!HostIsLittleEndian()) std::reverse(bytes.begin(), bytes.end());
  out.append(bytes.data(), bytes.size());
}

// ---- the formats, one file each ----------------------------------------------

// mesh_io_stl.cc: ASCII or binary (told apart by the content); written binary.
RawMesh ReadStl(std::string_view data, const std::string& file);
std::string WriteStl(const TriangleMesh& mesh);

// mesh_io_ply.cc: ASCII and binary, any numeric property types.
RawMesh ReadPly(std::string_view data, const std::string& file);
std::string WritePly(const TriangleMesh& mesh, const MeshSaveOptions& o);

// mesh_io_obj.cc
RawMesh ReadObj(std::string_view data, const std::string& file);
std::string WriteObj(const TriangleMesh& mesh);

// mesh_io_off.cc
RawMesh ReadOff(std::string_view data, const std::string& file);

// mesh_io_assimp.cc: every other format. A compressed file is read from
// `data` (its inflated content), a plain one by name.
RawMesh ReadWithAssimp(const std::string& data, const std::string& file, const std::string& ext);

}  // namespace hull::mesh_io_internal
