// Scratch folders and text edits for tests that write files and break them.
#pragma once

#include <string>

namespace hull::testing {

// A fresh, empty folder under the system temp dir, removed by the destructor.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

std::string ReadText(const std::string& path);
void WriteText(const std::string& path, const std::string& text);
// 1-based line `line` of a text (without its newline).
std::string LineOf(const std::string& text, int line);
// Replaces 1-based line `line` of a file.
void ReplaceLine(const std::string& path, int line, const std::string& replacement);
// Removes 1-based line `line` of a file.
void RemoveLine(const std::string& path, int line);
// 1-based character column where the field number `field` (0-based) of a CSV line starts.
int CsvColumn(const std::string& line, int field);

}  // namespace hull::testing
