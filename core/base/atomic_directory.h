// A folder replaced as a whole: everything is written into a hidden sibling
// folder, which is then swapped into place in one step (Linux renameat2
// RENAME_EXCHANGE; where the file system lacks it, two renames, and a
// folder left aside by a writer killed between them is put back by the
// next write). A writer that fails or is killed before the swap leaves the
// previous folder intact and complete; at worst a hidden ".NAME.writing-PID"
// sibling remains, which the next write to the same folder removes.
// Results folders go through results/results_folder.h, which adds the
// manifest and keeps the user's own files.
#pragma once

#include <functional>
#include <string>

namespace hull {

// The hidden sibling folder a write of `dir` by this process goes through:
// "<parent>/.<name>.writing-<pid>" (dir absolute, without a trailing '/').
std::string AtomicDirectorySibling(const std::string& dir);

// Calls write(tmp) with a fresh, empty sibling folder of `dir`, then puts
// it in place of `dir` (creating dir's parent when needed) and removes the
// previous folder. When write throws, tmp is removed, `dir` is untouched
// and the exception propagates. Throws std::runtime_error when the swap fails.
void WriteDirectoryAtomic(const std::string& dir, const std::function<void(const std::string& tmp)>& write);

}  // namespace hull
