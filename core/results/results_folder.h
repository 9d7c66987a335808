// A results folder of ours: every folder HullInspect writes results into
// carries a manifest (.hullinspect-results.json) naming the run that wrote it
// (command, program, when, and the inputs it read with their fingerprints)
// and every file it wrote with its size and fingerprint
// (docs/results-format.md, "The manifest").
//
// Writing: `--out` must be absent, empty or a results folder of ours;
// anything else is refused before any work (CheckResultsFolder, OptionError:
// exit 2) unless `force`. The folder is then written as a whole into a
// hidden sibling and swapped into place in one step (WriteResultsFolder over
// base/atomic_directory.h), so a run that fails or is killed at any point
// leaves the previous folder whole. Of the previous folder, the files its
// manifest lists (and results folders of ours nested in it, derived from
// them) are dropped; everything else (the user's own files) is carried into
// the new folder, and a file of the user's where this run writes one stops
// the write before the swap, naming the file. Nothing the user had is
// deleted or overwritten.
//
// Reading: CheckResultsFiles refuses files that are not all listed,
// unchanged, in the manifest of one run (a mixed folder); folders without a
// manifest (written by older versions, or assembled by hand) are read as
// they are.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"

namespace hull {

// Something a run read: a survey bundle, a mesh, an acoustic sequence, or
// results of an earlier run.
struct ResultsInput {
  std::string role;  // "bundle", "mesh", "sequence", "adjustment", "mapping", "results_a", ...
  std::string path;  // absolute
  std::string hash;  // file_hash.h: SurveyHash, SequenceHash or FileHash ("" when not taken)
  std::string run;   // for results: the id of the run that wrote them ("" when unknown)
};

struct ResultsRun {
  std::string id;       // unique: UTC time, host process and a counter
  std::string command;  // "run", "adjust", "map", "mosaic", "compare", "sonar", "report", "gui mosaic", ...
  std::string program;  // "HullInspect 0.1.0"
  std::string started;  // UTC, ISO 8601
  std::vector<ResultsInput> inputs;

  // The input of this role (nullptr: none).
  const ResultsInput* Input(const std::string& role) const;
  // Records a survey bundle (SurveyHash), a sequence (SequenceHash), a
  // file (FileHash) or results folder (the run of its manifest, if any).
  // `recorded_as`: the path to record when it differs from where it is read
  // now (a survey written into the new results folder before the swap).
  void AddSurvey(const std::string& role, const std::string& bundle_dir, const std::string& recorded_as = "");
  void AddSequence(const std::string& role, const std::string& sequence_dir);
  void AddFile(const std::string& role, const std::string& path);
  void AddResults(const std::string& role, const std::string& dir);
};

// A new run of `command` (id, program and time filled in).
ResultsRun NewResultsRun(const std::string& command);

struct ResultsFile {
  std::string path;  // relative to the folder, '/'-separated
  std::uint64_t bytes = 0;
  std::string hash;  // FileHash
};

struct ResultsManifest {
  static constexpr const char* kFileName = ".hullinspect-results.json";
  // Written before the manifest existed: the names of the top-level entries
  // a run wrote, one per line, without the run or the files' fingerprints.
  static constexpr const char* kLegacyFileName = ".hullinspect-results";

  std::string folder;  // where it was read from (absolute)
  ResultsRun run;
  std::vector<ResultsFile> files;
  bool legacy = false;                    // read from kLegacyFileName
  std::vector<std::string> legacy_names;  // its top-level names

  // The entry of `relative` (nullptr: not listed).
  const ResultsFile* Find(const std::string& relative) const;
  // A legacy manifest lists top-level names: true for anything under one.
  bool Covers(const std::string& relative) const;
};

// The manifest of `dir` (nullopt: none). Throws InputError naming the file
// when it is malformed.
std::optional<ResultsManifest> ReadResultsManifest(const std::string& dir);

// The --out folder of a command and whether --force was given.
struct OutputFolder {
  std::string path;
  bool force = false;
};

// An --out folder refused: what() is "--out PATH: why", as the CLI's other
// checks of the command line say it (exit 2, like every OptionError).
class OutputFolderRefused : public OptionError {
 public:
  OutputFolderRefused(const std::string& path, const std::string& why);
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

// What `path` holds now.
enum class OutputFolderState { kAbsent, kEmpty, kOurs, kForeign };
OutputFolderState ClassifyOutputFolder(const std::string& path);

// Before any work: the folder must be creatable where it will be created
// (its hidden sibling in the parent folder, the parent existing and
// writable, `path` not a file) and be absent, empty or ours, or `force`.
// Throws OutputFolderRefused saying why and what to do.
void CheckResultsFolder(const OutputFolder& out);

// Calls write(tmp) with a fresh folder that will become `out.path`, then
// lists what write() put there in the manifest (with `run`, read after
// write() returns: write() may add the inputs it read), carries the
// user's entries of the previous folder over and swaps the new folder into
// place. Throws OutputFolderRefused when the folder fails CheckResultsFolder
// (it is checked again: the folder may have changed since) or where write()
// put a file of the same name as one of the user's (naming it; nothing is
// changed then), and whatever write() throws (nothing is changed either).
void WriteResultsFolder(const OutputFolder& out, const ResultsRun& run,
                        const std::function<void(const std::string& tmp)>& write);

// The manifest that lists `file` (the nearest folder above it with a
// manifest; nullopt when none does: results without a manifest).
std::optional<ResultsManifest> ManifestOf(const std::string& file);

// Reading results: every file of `files` that exists must be listed,
// unchanged (size and fingerprint), in the manifest of one run. `what` names
// the set in the message ("the adjustment in R"). Returns that manifest, or
// nullopt when none of the files is under a folder with a manifest (results
// written before manifests: read as they are). Throws InputError naming the
// first file at fault: not written by a run, changed since, or written by
// another run than the others (a mixed folder).
std::optional<ResultsManifest> CheckResultsFiles(const std::vector<std::string>& files, const std::string& what);

// Pairings: throws InputError naming both when the survey bundle at
// `bundle_dir` is not the one the run that wrote `results_file` read (its
// manifest records another survey: survey.json and nav.csv differ). Nothing
// to check for results without a manifest or a recorded survey.
void CheckBundleOfResults(const std::string& results_file, const std::string& bundle_dir);

}  // namespace hull
