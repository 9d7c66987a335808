// The demo survey ("demo" preset of the simulator) kept in a cache folder:
// simulated once, reused while present and valid. Qt-free; runs in a job.
#pragma once

#include <string>

#include "base/progress.h"

namespace hull::ui {

struct DemoFiles {
  std::string directory;   // the bundle folder, <cache_root>/demo-<seed>
  std::string mesh;        // its hull.ply
  bool simulated = false;  // false when an existing valid copy was reused
};

// <cache_root>/demo-<seed> for the demo preset's seed.
std::string DemoDirectory(const std::string& cache_root);

// True when `dir` holds a complete demo written by this build: its stamp
// file (version, preset, seed and a fingerprint of the simulator's sources)
// matches, the mesh exists and the bundle validates without errors.
bool IsValidDemo(const std::string& dir);

// Returns the demo, simulating it first when needed (progress 0..1,
// cancellable). Writing is atomic: the bundle is written into a temporary
// sibling folder that is renamed into place when complete, so a cancelled or
// failed run leaves no partial demo behind.
DemoFiles PrepareDemo(const std::string& cache_root, Progress& progress);

}  // namespace hull::ui
