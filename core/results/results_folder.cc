#include "results/results_folder.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <set>

#include "base/atomic_directory.h"
#include "base/error.h"
#include "base/file_io.h"
#include "base/json.h"
#include "base/printable.h"
#include "results/file_hash.h"

#ifndef HI_VERSION
#define HI_VERSION "unknown"
#endif

namespace hull {
namespace {

namespace fs = std::filesystem;

fs::path Normal(const std::string& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p;
}

std::string Relative(const fs::path& file, const fs::path& folder) {
  return file.lexically_relative(folder).generic_string();
}

bool IsManifestName(const std::string& name) {
  return name == ResultsManifest::kFileName || name == ResultsManifest::kLegacyFileName;
}

std::string UtcNow(const char* format) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, format, &tm);
  return buf;
}

// ---- the manifest file

Json RunJson(const ResultsRun& run) {
  Json j = Json::Object();
  j.Set("id", run.id);
  j.Set("command", run.command);
  j.Set("program", run.program);
  j.Set("started", run.started);
  Json inputs = Json::Array();
  for (const ResultsInput& in : run.inputs) {
    Json i = Json::Object();
    i.Set("role", in.role);
    i.Set("path", in.path);
    i.Set("hash", in.hash);
    i.Set("run", in.run);
    inputs.Push(std::move(i));
  }
  j.Set("inputs", std::move(inputs));
  return j;
}

std::string ManifestText(const ResultsManifest& m) {
  Json root = Json::Object();
  root.Set("format", "hull-results-manifest");
  root.Set("version", 1);
  root.Set("run", RunJson(m.run));
  Json files = Json::Array();
  for (const ResultsFile& f : m.files) {
    Json j = Json::Object();
    j.Set("path", f.path);
    j.Set("bytes", static_cast<std::int64_t>(f.bytes));
    j.Set("hash", f.hash);
    files.Push(std::move(j));
  }
  root.Set("files", std::move(files));
  return root.Dump() + "\n";
}

ResultsRun ReadRun(const JsonReader& r) {
  ResultsRun run;
  run.id = r.String("id");
  run.command = r.String("command");
  run.program = r.OptionalString("program").value_or("");
  run.started = r.OptionalString("started").value_or("");
  const Json& inputs = r.Required("inputs");
  if (!inputs.is_array()) r.Fail(inputs, "inputs", "expected an array");
  for (std::size_t i = 0; i < inputs.items().size(); ++i) {
    const JsonReader in(inputs.items()[i], r.file(), r.PathOf("inputs") + "[" + std::to_string(i) + "]");
    run.inputs.push_back({in.String("role"), in.String("path"), in.OptionalString("hash").value_or(""),
                          in.OptionalString("run").value_or("")});
  }
  return run;
}

ResultsManifest ParseManifest(const std::string& path) {
  const Json doc = Json::Parse(ReadFileToString(path), path);
  const JsonReader root(doc, path);
  if (root.String("format") != "hull-results-manifest") {
    root.Fail(root.Required("format"), "format", "expected \"hull-results-manifest\"");
  }
  if (root.Integer("version") != 1) root.Fail(root.Required("version"), "version", "unsupported; this reader knows 1");
  ResultsManifest m;
  m.run = ReadRun(root.Object("run"));
  const Json& files = root.Required("files");
  if (!files.is_array()) root.Fail(files, "files", "expected an array");
  for (std::size_t i = 0; i < files.items().size(); ++i) {
    const JsonReader f(files.items()[i], path, "files[" + std::to_string(i) + "]");
    const std::int64_t bytes = f.Integer("bytes");
    if (bytes < 0) f.Fail(f.Required("bytes"), "bytes", "expected a size (0 or more)");
    m.files.push_back({f.String("path"), static_cast<std::uint64_t>(bytes), f.String("hash")});
  }
  return m;
}

// Every file under tmp (this run's), sorted, with size and fingerprint.
std::vector<ResultsFile> ListFiles(const fs::path& tmp) {
  std::vector<ResultsFile> files;
  for (auto it = fs::recursive_directory_iterator(tmp); it != fs::recursive_directory_iterator(); ++it) {
    if (it->is_symlink() || !it->is_regular_file()) continue;
    const std::string rel = Relative(it->path(), tmp);
    if (IsManifestName(rel)) continue;
    files.push_back({rel, static_cast<std::uint64_t>(it->file_size()), FileHash(it->path().string())});
  }
  std::sort(files.begin(), files.end(), [](const ResultsFile& a, const ResultsFile& b) { return a.path < b.path; });
  return files;
}

// ---- carrying the user's entries over

// `from` recreated at `to` with hard links (a copy where links fail), so the
// previous folder stays whole until the swap.
void LinkTree(const fs::path& from, const fs::path& to) {
  const fs::file_status st = fs::symlink_status(from);
  if (fs::is_symlink(st)) {
    fs::copy_symlink(from, to);
  } else if (fs::is_directory(st)) {
    fs::create_directory(to);
    for (const auto& e : fs::directory_iterator(from)) LinkTree(e.path(), to / e.path().filename());
  } else {
    std::error_code ec;
    fs::create_hard_link(from, to, ec);
    if (ec) fs::copy_file(from, to);
  }
}

bool HasManifest(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / ResultsManifest::kFileName, ec) ||
         fs::is_regular_file(dir / ResultsManifest::kLegacyFileName, ec);
}

struct CarryOver {
  fs::path previous_root, tmp_root, final_root;
  const ResultsManifest* ours = nullptr;  // the previous folder's manifest (nullptr: not ours)

  bool Ours(const std::string& rel) const {
    if (!ours) return false;
    return ours->legacy ? ours->Covers(rel) : ours->Find(rel) != nullptr;
  }

  // A file of the previous run lies under the folder rel.
  bool OursUnder(const std::string& rel) const {
    if (!ours) return false;
    const std::string prefix = rel + "/";
    return std::any_of(ours->files.begin(), ours->files.end(),
                       [&](const ResultsFile& f) { return f.path.compare(0, prefix.size(), prefix) == 0; });
  }

  [[noreturn]] void Collision(const std::string& rel) const {
    throw OutputFolderRefused(final_root.string(),
                              "'" + (final_root / rel).string() +
                                  "' is not a HullInspect result (no results manifest lists it), and this run "
                                  "writes a file of that name: it is not replaced. Move it away or choose another "
                                  "folder; nothing was changed");
  }

  // The entries of previous_root/rel that are the user's, into tmp_root/rel.
  void Folder(const std::string& rel) const {
    for (const auto& e : fs::directory_iterator(previous_root / rel)) {
      const std::string name = e.path().filename().string();
      const std::string sub = rel.empty() ? name : rel + "/" + name;
      if (rel.empty() && IsManifestName(name)) continue;
      if (Ours(sub)) continue;  // the previous run's: replaced
      const fs::path target = tmp_root / sub;
      const fs::file_status st = fs::symlink_status(e.path());
      const bool dir = fs::is_directory(st);
      // Results of ours nested in results of ours were made from them: dropped with them.
      if (dir && ours && HasManifest(e.path())) continue;
      const fs::file_status there = fs::symlink_status(target);
      if (dir && fs::is_directory(there)) {
        Folder(sub);
      } else if (fs::exists(there)) {
        Collision(sub);
      } else if (!dir || !OursUnder(sub)) {
        LinkTree(e.path(), target);
      } else {  // the previous run's files and the user's: the user's only
        fs::create_directory(target);
        Folder(sub);
        std::error_code ec;
        if (fs::is_empty(target, ec)) fs::remove(target, ec);
      }
    }
  }
};

// ---- out checks

std::string SomeEntries(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    names.push_back(e.path().filename().string() + (e.is_directory() ? "/" : ""));
  }
  std::sort(names.begin(), names.end());
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < 3; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 3) s += ", ... (" + std::to_string(names.size()) + " entries)";
  return s;
}

// Refusals name the option and the folder as the CLI's other checks do:
// "option --out DIR: why".
[[noreturn]] void Refuse(const std::string& path, const std::string& why) { throw OutputFolderRefused(path, why); }

// The hidden sibling the write goes through must be creatable in the parent.
void ProbeParent(const std::string& path, const fs::path& dir) {
  const fs::path parent = dir.parent_path();
  std::error_code ec;
  if (!fs::exists(parent, ec)) Refuse(path, "the folder '" + parent.string() + "' does not exist; create it first");
  if (!fs::is_directory(parent, ec)) Refuse(path, "'" + parent.string() + "' is not a folder");
  const fs::path probe = AtomicDirectorySibling(dir.string());
  fs::remove_all(probe, ec);
  if (::mkdir(probe.c_str(), 0700) != 0) {
    const int err = errno;
    Refuse(path, "cannot write in '" + parent.string() + "' (the results are written beside '" +
                     dir.filename().string() + "' and then swapped into place): " + std::strerror(err) +
                     (err == EROFS || err == EACCES || err == EPERM ? " (read-only)" : ""));
  }
  fs::remove(probe, ec);
}

std::atomic<int> run_counter{0};

}  // namespace

// ---- ResultsRun, ResultsManifest

OutputFolderRefused::OutputFolderRefused(const std::string& path, const std::string& why)
    : OptionError("--out", why),
      message_("--out " + PrintableText(path, kMaxPrintedPath) + ": " + PrintableText(why, kMaxPrintedMessage)) {}

const ResultsInput* ResultsRun::Input(const std::string& role) const {
  for (const ResultsInput& in : inputs) {
    if (in.role == role) return &in;
  }
  return nullptr;
}

void ResultsRun::AddSurvey(const std::string& role, const std::string& bundle_dir, const std::string& recorded_as) {
  inputs.push_back({role, Normal(recorded_as.empty() ? bundle_dir : recorded_as).string(), SurveyHash(bundle_dir), ""});
}

void ResultsRun::AddSequence(const std::string& role, const std::string& sequence_dir) {
  inputs.push_back({role, Normal(sequence_dir).string(), SequenceHash(sequence_dir), ""});
}

void ResultsRun::AddFile(const std::string& role, const std::string& path) {
  inputs.push_back({role, Normal(path).string(), FileHash(path), ""});
}

void ResultsRun::AddResults(const std::string& role, const std::string& dir) {
  // The folder's own manifest, or the one of the results folder it lies in
  // (e.g. a pipeline's adjustment/).
  std::optional<ResultsManifest> m = ReadResultsManifest(dir);
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !m && !ec && it != fs::directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec)) m = ManifestOf(it->path().string());
  }
  inputs.push_back({role, Normal(dir).string(), "", m && !m->legacy ? m->run.id : ""});
}

ResultsRun NewResultsRun(const std::string& command) {
  ResultsRun run;
  run.command = command;
  run.program = std::string("HullInspect ") + HI_VERSION;
  run.started = UtcNow("%Y-%m-%dT%H:%M:%SZ");
  run.id = UtcNow("%Y%m%dT%H%M%SZ") + "-" + std::to_string(static_cast<long>(::getpid())) + "-" +
           std::to_string(++run_counter);
  return run;
}

const ResultsFile* ResultsManifest::Find(const std::string& relative) const {
  for (const ResultsFile& f : files) {
    if (f.path == relative) return &f;
  }
  return nullptr;
}

bool ResultsManifest::Covers(const std::string& relative) const {
  const std::string top = relative.substr(0, relative.find('/'));
  return std::find(legacy_names.begin(), legacy_names.end(), top) != legacy_names.end();
}

std::optional<ResultsManifest> ReadResultsManifest(const std::string& dir) {
  const fs::path d = Normal(dir);
  std::error_code ec;
  if (fs::is_regular_file(d / ResultsManifest::kFileName, ec)) {
    ResultsManifest m = ParseManifest((d / ResultsManifest::kFileName).string());
    m.folder = d.string();
    return m;
  }
  if (fs::is_regular_file(d / ResultsManifest::kLegacyFileName, ec)) {
    ResultsManifest m;
    m.folder = d.string();
    m.legacy = true;
    const std::string text = ReadFileToString((d / ResultsManifest::kLegacyFileName).string());
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      if (end > start) m.legacy_names.push_back(text.substr(start, end - start));
      start = end + 1;
    }
    return m;
  }
  return std::nullopt;
}

// ---- writing

OutputFolderState ClassifyOutputFolder(const std::string& path) {
  const fs::path p = Normal(path);
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(p, ec))) return OutputFolderState::kAbsent;
  if (!fs::is_directory(p, ec)) return OutputFolderState::kForeign;
  if (HasManifest(p)) return OutputFolderState::kOurs;
  return fs::directory_iterator(p, ec) == fs::directory_iterator() ? OutputFolderState::kEmpty
                                                                   : OutputFolderState::kForeign;
}

void CheckResultsFolder(const OutputFolder& out) {
  if (out.path.empty()) throw OutputFolderRefused("", "no folder given");
  const fs::path p = Normal(out.path);
  std::error_code ec;
  if (fs::exists(p, ec) && !fs::is_directory(p, ec))
    Refuse(out.path, "'" + out.path + "' is a file; expected a folder for the results");
  ProbeParent(out.path, p);
  if (ClassifyOutputFolder(out.path) == OutputFolderState::kForeign && !out.force) {
    Refuse(out.path, "'" + out.path + "' holds files HullInspect did not write (" + SomeEntries(p) +
                         "; it has no results manifest). Choose a new or empty folder, or give --force to write "
                         "into it: your files are kept and none of them is replaced");
  }
}

void WriteResultsFolder(const OutputFolder& out, const ResultsRun& run,
                        const std::function<void(const std::string& tmp)>& write) {
  CheckResultsFolder(out);
  const fs::path dir = Normal(out.path);
  WriteDirectoryAtomic(dir.string(), [&](const std::string& tmp) {
    write(tmp);
    ResultsManifest m;
    m.run = run;
    m.files = ListFiles(tmp);
    std::error_code ec;
    if (fs::is_directory(dir, ec)) {
      const std::optional<ResultsManifest> previous = ReadResultsManifest(dir.string());
      CarryOver c{dir, fs::path(tmp), dir, previous ? &*previous : nullptr};
      c.Folder("");
    }
    WriteFileAtomic((fs::path(tmp) / ResultsManifest::kFileName).string(), ManifestText(m));
  });
}

// ---- reading

std::optional<ResultsManifest> ManifestOf(const std::string& file) {
  const fs::path f = Normal(file);
  for (fs::path dir = f.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (HasManifest(dir)) {
      std::optional<ResultsManifest> m = ReadResultsManifest(dir.string());
      const std::string rel = Relative(f, dir);
      if (m->legacy) return m->Covers(rel) ? m : std::nullopt;
      if (m->Find(rel)) return m;
      // Unlisted: the manifest's when it wrote other files in that folder
      // (a file added or replaced by hand), else the folder is not its.
      const std::string folder = fs::path(rel).parent_path().generic_string();
      for (const ResultsFile& r : m->files) {
        if (fs::path(r.path).parent_path().generic_string() == folder) return m;
      }
      return std::nullopt;
    }
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

namespace {

std::string RunText(const ResultsRun& r) {
  return "run " + r.id + " ('" + r.command + "', " + (r.started.empty() ? "time unknown" : r.started) + ")";
}

}  // namespace

std::optional<ResultsManifest> CheckResultsFiles(const std::vector<std::string>& files, const std::string& what) {
  std::optional<ResultsManifest> common;
  std::string common_file, unmanaged_file;
  for (const std::string& file : files) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) continue;
    std::optional<ResultsManifest> m = ManifestOf(file);
    if (!m || m->legacy) {
      if (unmanaged_file.empty()) unmanaged_file = file;
      continue;
    }
    const fs::path manifest = fs::path(m->folder) / ResultsManifest::kFileName;
    const ResultsFile* entry = m->Find(Relative(Normal(file), m->folder));
    if (!entry) {
      throw InputError({file, 0, 0, ""},
                       "is not listed in " + manifest.string() + ": it was not written by " + RunText(m->run) +
                           ", which wrote " + what +
                           " (added or replaced by hand?); the folder mixes files of different origins");
    }
    if (static_cast<std::uint64_t>(fs::file_size(file, ec)) != entry->bytes || FileHash(file) != entry->hash) {
      throw InputError({file, 0, 0, ""}, "has changed since " + RunText(m->run) + " wrote it (" + manifest.string() +
                                             " records another size or fingerprint): the folder mixes files of "
                                             "different runs; run the command that wrote " +
                                             what + " again");
    }
    if (common && common->run.id != m->run.id) {
      throw InputError({file, 0, 0, ""}, "was written by " + RunText(m->run) + ", but " + common_file + " by " +
                                             RunText(common->run) + ": " + what +
                                             " mixes files of different runs; run the command that wrote it again");
    }
    if (!common) {
      common = std::move(m);
      common_file = file;
    }
  }
  if (common && !unmanaged_file.empty()) {
    throw InputError({unmanaged_file, 0, 0, ""}, "is not listed in any results manifest, while " + common_file +
                                                     " was written by " + RunText(common->run) + ": " + what +
                                                     " mixes files of different origins");
  }
  return common;
}

void CheckBundleOfResults(const std::string& results_file, const std::string& bundle_dir) {
  const std::optional<ResultsManifest> m = ManifestOf(results_file);
  if (!m || m->legacy) return;
  const ResultsInput* recorded = m->run.Input("bundle");
  if (!recorded || recorded->hash.empty() || SurveyHash(bundle_dir) == recorded->hash) return;
  throw InputError({(fs::path(bundle_dir) / "survey.json").string(), 0, 0, ""},
                   "is not the survey " + results_file + " was computed from (" + RunText(m->run) + " read " +
                       recorded->path +
                       ", whose survey.json and nav.csv differ): choose that survey or results of "
                       "this one");
}

}  // namespace hull
