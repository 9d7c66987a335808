// The entity references of a STEP file (ISO 10303-21), read from its text
// before OpenCASCADE sees it: OpenCASCADE 7.6 follows references
// recursively while it loads and checks a file (an ORIENTED_EDGE's start is
// its edge element's start), so a file whose references go round in a
// circle overflows its stack (found by fuzzing, docs/reliability.md).
#pragma once

#include <string>
#include <vector>

namespace hull::step_iges {

struct ReferenceCycle {
  std::vector<long> entities;  // #ids along the cycle, the first repeated last: {77, 77} or {5, 9, 5}
  int line = 0;                // line of the first entity's definition (1-based)
};

// The first cycle of references among the DATA section's entity instances,
// if any (an empty `entities` otherwise). Reads `text` leniently: strings
// ('...' with '' inside), comments (/* */) and complex instances are skipped
// over correctly; what is not well-formed is left for OpenCASCADE's parser
// to report. Linear in the file's size.
ReferenceCycle FindReferenceCycle(const std::string& text);

// Throws std::runtime_error naming the line and the entities when the STEP
// file at `path` has a reference cycle (a legal STEP file has none: its
// entity instances form a directed acyclic graph).
void RefuseReferenceCycles(const std::string& path);

}  // namespace hull::step_iges
