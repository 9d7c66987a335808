// docs/results-format.md and the writers held together (issue 24, part 1):
// the results of `run` (pipeline, adjustment, mapping, manifest), `compare`
// and `sonar --from-images --smoother` on small inputs, and for every file
// the part of the page that documents it. Every JSON key written (at any
// depth) and every CSV column appears in backticks there; every documented
// CSV header is the written one, column for column; and every key the page
// lists in a key table's first column or at the head of a bullet is
// written. A key added to a writer without the page, or a key the page
// documents that is no longer written, fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "base/json.h"
#include "support/cli_run.h"
#include "support/test_files.h"
#include "support/test_surveys.h"

namespace {

namespace fs = std::filesystem;
using hull::testing::CliRun;
using hull::testing::ReadText;
using hull::testing::ScratchDir;

CliRun Cli(const std::vector<std::string>& args) { return hull::testing::RunProgram(HI_CLI_PATH, args); }

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The page's text from `heading` (a whole line) to the next heading of its
// level or above; with `row`, only the table row whose first cell is `row`.
std::string Scope(const std::string& page, const std::string& heading, const std::string& row = "") {
  const std::vector<std::string> lines = Lines(page);
  const auto start = std::find(lines.begin(), lines.end(), heading);
  if (start == lines.end()) return "";
  const std::size_t level = heading.find(' ');
  std::string text;
  for (auto it = start + 1; it != lines.end(); ++it) {
    const std::size_t hashes = it->find_first_not_of('#');
    if (hashes > 0 && hashes != std::string::npos && hashes <= level && (*it)[hashes] == ' ') break;
    if (row.empty() || it->rfind("| `" + row + "`", 0) == 0) text += *it + "\n";
  }
  return text;
}

// Every name in backticks: `a`, `a, b` and `a.b[]` give a, b.
std::set<std::string> Backticked(const std::string& text) {
  std::set<std::string> out;
  static const std::regex tick("`([^`]+)`"), name("[A-Za-z_][A-Za-z0-9_]*");
  for (auto m = std::sregex_iterator(text.begin(), text.end(), tick); m != std::sregex_iterator(); ++m) {
    const std::string inner = (*m)[1];
    for (auto n = std::sregex_iterator(inner.begin(), inner.end(), name); n != std::sregex_iterator(); ++n) {
      out.insert((*n)[0]);
    }
  }
  return out;
}

// Keys a key table lists in its first column, and bullets' leading keys.
std::set<std::string> ListedKeys(const std::string& text) {
  std::set<std::string> out;
  static const std::regex name("[A-Za-z_][A-Za-z0-9_]*");
  for (const std::string& line : Lines(text)) {
    std::string cell;
    if (line.rfind("| `", 0) == 0) {
      cell = line.substr(2, line.find(" |", 2) - 2);
    } else if (line.rfind("- `", 0) == 0) {
      cell = line.substr(2, line.find('`', 3) + 1 - 2);
    } else {
      continue;
    }
    const std::set<std::string> names = Backticked(cell);
    out.insert(names.begin(), names.end());
  }
  return out;
}

void CollectKeys(const hull::Json& j, std::set<std::string>& keys) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.members()) {
      keys.insert(k);
      CollectKeys(v, keys);
    }
  } else if (j.is_array()) {
    for (const hull::Json& v : j.items()) CollectKeys(v, keys);
  }
}

// The documented CSV header: the backticked token of the scope with most commas.
std::string DocumentedHeader(const std::string& scope) {
  static const std::regex tick("`([^`]+)`");
  std::string best;
  for (auto m = std::sregex_iterator(scope.begin(), scope.end(), tick); m != std::sregex_iterator(); ++m) {
    const std::string t = (*m)[1];
    if (std::count(t.begin(), t.end(), ',') > std::count(best.begin(), best.end(), ',')) best = t;
  }
  return best;
}

struct Documented {
  std::string file;  // written, relative to its results folder
  std::string page;  // docs/<page>
  std::string heading;
  std::string row = "";  // "": the whole section
};

class ResultsFormatDoc : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("results_format_doc");
    hull::test::WriteSmallSurvey(*dir_ / "bundle");
    ASSERT_EQ(Cli({"run", *dir_ / "bundle", "--out", *dir_ / "R", "--threads", "1", "--quiet"}).exit_code, 0);
    ASSERT_EQ(Cli({"compare", *dir_ / "R", *dir_ / "R", "--out", *dir_ / "C"}).exit_code, 0);
    ASSERT_EQ(Cli({"simulate", "--preset", "sonar-prism", "--images", "--out", *dir_ / "seq", "--quiet"}).exit_code, 0);
    ASSERT_EQ(Cli({"sonar", *dir_ / "seq", "--from-images", "--smoother", "--out", *dir_ / "S", "--quiet"}).exit_code,
              0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  // Checks one file against its part of the page; returns what differs.
  static std::vector<std::string> Check(const std::string& folder, const Documented& d) {
    std::vector<std::string> problems;
    const std::string where =
        d.file + " (docs/" + d.page + ", " + d.heading + (d.row.empty() ? "" : ", " + d.row) + ")";
    const std::string scope = Scope(ReadText(std::string(HI_DOCS_DIR) + "/" + d.page), d.heading, d.row);
    if (scope.empty()) return {where + ": not documented"};
    const std::string path = (fs::path(*dir_ / folder) / d.file).string();
    if (!fs::exists(path)) return {where + ": not written"};
    const std::set<std::string> documented = Backticked(scope);
    std::set<std::string> written;
    if (d.file.size() > 4 && d.file.substr(d.file.size() - 4) == ".csv") {
      const std::string header = Lines(ReadText(path)).at(0);
      if (DocumentedHeader(scope) != header) {
        problems.push_back(where + ": header written '" + header + "', documented '" + DocumentedHeader(scope) + "'");
      }
      std::stringstream cols(header);
      for (std::string c; std::getline(cols, c, ',');) written.insert(c);
    } else {
      CollectKeys(hull::Json::Parse(ReadText(path), path), written);
      // A file table's row lists the file in its first cell, not a key.
      for (const std::string& k : d.row.empty() ? ListedKeys(scope) : std::set<std::string>{}) {
        if (!written.count(k)) problems.push_back(where + ": documents '" + k + "', which is not written");
      }
    }
    for (const std::string& k : written) {
      if (!documented.count(k)) problems.push_back(where + ": writes '" + k + "', which is not documented");
    }
    return problems;
  }

  static ScratchDir* dir_;
};
ScratchDir* ResultsFormatDoc::dir_ = nullptr;

void ExpectDocumented(const std::string& folder, const std::vector<Documented>& files,
                      std::vector<std::string> (*check)(const std::string&, const Documented&)) {
  std::vector<std::string> all;
  for (const Documented& d : files) {
    const std::vector<std::string> p = check(folder, d);
    all.insert(all.end(), p.begin(), p.end());
  }
  std::string text;
  for (const std::string& p : all) text += "\n  " + p;
  EXPECT_TRUE(all.empty()) << all.size() << " differences:" << text;
}

TEST_F(ResultsFormatDoc, PipelineAdjustmentMappingAndManifest) {
  const std::string f = "results-format.md";
  ExpectDocumented("R",
                   {{"summary.json", f, "## Pipeline results, version 1", "summary.json"},
                    {"alignment.json", f, "### alignment.json"},
                    {".hullinspect-results.json", f, "### .hullinspect-results.json"},
                    {"adjustment/adjustment.json", f, "### adjustment.json"},
                    {"adjustment/timing.json", f, "### timing.json"},
                    {"adjustment/poses.csv", f, "### poses.csv"},
                    {"adjustment/landmarks.csv", f, "### landmarks.csv"},
                    {"adjustment/dvl_residuals.csv", f, "### dvl_residuals.csv"},
                    {"mapping/mapping.json", f, "### mapping.json"},
                    {"mapping/objects.csv", f, "### objects.csv / objects.json"},
                    {"mapping/objects.json", f, "### objects.csv / objects.json"},
                    {"mapping/zones.csv", f, "### zones.csv / zones.json"},
                    {"mapping/zones.json", f, "### zones.csv / zones.json"},
                    {"mapping/shapes.csv", f, "### shapes.csv"}},
                   &ResultsFormatDoc::Check);
}

TEST_F(ResultsFormatDoc, Comparison) {
  const std::string f = "results-format.md", h = "## Comparison results, version 2";
  ExpectDocumented("C", {{"compare.json", f, h, "compare.json"}, {"objects.csv", f, h, "objects.csv"}},
                   &ResultsFormatDoc::Check);
}

TEST_F(ResultsFormatDoc, Sonar) {
  const std::string f = "results-format.md", h = "## Sonar results, version 1";
  ExpectDocumented("S",
                   {{"summary.json", f, "### Sonar summary.json"},
                    {"poses.csv", f, h, "poses.csv"},
                    {"features.csv", f, h, "features.csv"},
                    {"detections.csv", f, h, "detections.csv"},
                    {"smoother_poses.csv", f, h, "smoother_poses.csv"},
                    {"smoother_features.csv", f, h, "smoother_features.csv"}},
                   &ResultsFormatDoc::Check);
}

}  // namespace
