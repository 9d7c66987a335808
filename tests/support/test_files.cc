#include "support/test_files.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace hull::testing {
namespace fs = std::filesystem;

ScratchDir::ScratchDir(const std::string& tag) {
  static std::atomic<int> counter{0};
  path_ =
      (fs::temp_directory_path() / ("hi_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++)))
          .string();
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

static std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::string cur;
  for (char c : text) {
    if (c == '\n') {
      lines.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) lines.push_back(cur);
  return lines;
}

std::string LineOf(const std::string& text, int line) { return Lines(text).at(static_cast<std::size_t>(line - 1)); }

static void Rewrite(const std::string& path, int line, const std::string* replacement) {
  std::vector<std::string> lines = Lines(ReadText(path));
  const auto i = static_cast<std::size_t>(line - 1);
  if (replacement) {
    lines.at(i) = *replacement;
  } else {
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(i));
  }
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  WriteText(path, out);
}

void ReplaceLine(const std::string& path, int line, const std::string& replacement) {
  Rewrite(path, line, &replacement);
}

void RemoveLine(const std::string& path, int line) { Rewrite(path, line, nullptr); }

int CsvColumn(const std::string& line, int field) {
  int f = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (f == field) return static_cast<int>(i) + 1;
    if (line[i] == ',') ++f;
  }
  return f == field ? static_cast<int>(line.size()) + 1 : -1;
}

}  // namespace hull::testing
