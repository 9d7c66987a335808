// Fingerprints of the files a run read and wrote, so that a results folder
// can say which survey, mesh and earlier results it came from and whether a
// file is still the one a run wrote (results_folder.h). FNV-1a over the
// bytes (64 bits): an identity check against mix-ups, not a defence
// against forgery.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace hull {

// "fnv1a64:" and 16 hex digits.
std::string HashText(std::string_view bytes);
// The same over a file's bytes, read in blocks. Throws InputError naming the
// file when it cannot be read.
std::string FileHash(const std::string& path);
// Over several files in turn (each file's name and size are hashed with it,
// so moving bytes from one to the other changes the hash). Files that do not
// exist are hashed as absent.
std::string FilesHash(const std::vector<std::string>& paths);

// What identifies a survey bundle: its survey.json and nav.csv (the
// vehicle, cameras, sensors and every keyframe's navigation). Features found
// later from its images (features.csv) do not change it.
std::string SurveyHash(const std::string& bundle_dir);
// What identifies an acoustic sequence: its sonar.json and controls.csv.
std::string SequenceHash(const std::string& sequence_dir);

}  // namespace hull
