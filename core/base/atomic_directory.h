// A results folder replaced as a whole: everything is written into a hidden
// sibling folder, which is then swapped into place in one step (Linux
// renameat2 RENAME_EXCHANGE; where the file system lacks it, two renames).
// A run that fails or is killed before the swap leaves the previous folder
// intact and complete; at worst a hidden ".NAME.writing-PID" sibling remains,
// which the next write to the same folder removes.
#pragma once

#include <functional>
#include <string>

namespace hull {

// Calls write(tmp) with a fresh, empty sibling folder of `dir`, then puts
// it in place of `dir` (creating dir's parent when needed) and removes the
// previous results. The names a run writes are listed in the folder
// (".hullinspect-results"); entries of the previous folder that no run
// wrote (the user's own files, a survey or a report saved there) and that
// this run does not write are kept (hard-linked into the new folder before
// the swap, so the previous folder stays whole until then). When write throws, tmp is removed, `dir` is untouched
// and the exception propagates. Throws std::runtime_error when the swap fails.
void WriteDirectoryAtomic(const std::string& dir, const std::function<void(const std::string& tmp)>& write);

}  // namespace hull
