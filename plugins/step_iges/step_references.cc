#include "step_iges/step_references.h"

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace hull::step_iges {
namespace {

struct Instance {
  long id = 0;
  int line = 0;
  std::vector<long> refs;  // as written, possibly to entities never defined
};

// Splits the text into statements (ended by ';' outside strings and
// comments) and keeps those of the form "#id = ...", with the #references
// that follow the '='.
std::vector<Instance> ReadInstances(const std::string& text) {
  std::vector<Instance> out;
  const std::size_t n = text.size();
  std::size_t i = 0;
  int line = 1;
  Instance current;
  bool defining = false;  // the statement started with "#id ="
  bool at_start = true;   // nothing but white space seen in this statement yet
  auto read_number = [&](std::size_t* pos) {
    long v = 0;
    bool any = false;
    while (*pos < n && std::isdigit(static_cast<unsigned char>(text[*pos]))) {
      if (v < 1000000000000L) v = v * 10 + (text[*pos] - '0');
      ++*pos;
      any = true;
    }
    return any ? v : -1L;
  };
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
      continue;
    }
    if (c == '\'') {  // a string; '' is a quote inside it
      at_start = false;
      for (++i; i < n; ++i) {
        if (text[i] == '\n') ++line;
        if (text[i] == '\'') {
          if (i + 1 < n && text[i + 1] == '\'') {
            ++i;
          } else {
            break;
          }
        }
      }
      ++i;
      continue;
    }
    if (c == '/' && i + 1 < n && text[i + 1] == '*') {  // a comment
      for (i += 2; i < n && !(text[i] == '*' && i + 1 < n && text[i + 1] == '/'); ++i) {
        if (text[i] == '\n') ++line;
      }
      i += 2;
      continue;
    }
    if (c == ';') {
      if (defining) out.push_back(std::move(current));
      current = Instance();
      defining = false;
      at_start = true;
      ++i;
      continue;
    }
    if (c == '#') {
      std::size_t j = i + 1;
      const long id = read_number(&j);
      if (id >= 0 && at_start) {
        std::size_t k = j;
        while (k < n && std::isspace(static_cast<unsigned char>(text[k])) && text[k] != '\n') ++k;
        if (k < n && text[k] == '=') {
          defining = true;
          current.id = id;
          current.line = line;
          j = k + 1;
        }
      } else if (id >= 0 && defining) {
        current.refs.push_back(id);
      }
      at_start = false;
      i = j;
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) at_start = false;
    ++i;
  }
  return out;
}

}  // namespace

ReferenceCycle FindReferenceCycle(const std::string& text) {
  const std::vector<Instance> instances = ReadInstances(text);
  std::unordered_map<long, std::size_t> index;
  index.reserve(instances.size());
  for (std::size_t v = 0; v < instances.size(); ++v) index.emplace(instances[v].id, v);  // the first definition

  // Depth-first search without recursion (a hull's file has millions of
  // entities): 0 unvisited, 1 on the current path, 2 finished.
  std::vector<unsigned char> state(instances.size(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> path;  // (instance, next reference to follow)
  for (std::size_t root = 0; root < instances.size(); ++root) {
    if (state[root] != 0) continue;
    path.push_back({root, 0});
    state[root] = 1;
    while (!path.empty()) {
      auto& [v, next] = path.back();
      if (next == instances[v].refs.size()) {
        state[v] = 2;
        path.pop_back();
        continue;
      }
      const auto found = index.find(instances[v].refs[next++]);
      if (found == index.end()) continue;  // undefined: OpenCASCADE reports it
      const std::size_t w = found->second;
      if (state[w] == 1) {
        ReferenceCycle cycle;
        std::size_t start = 0;
        while (path[start].first != w) ++start;
        for (std::size_t p = start; p < path.size(); ++p) cycle.entities.push_back(instances[path[p].first].id);
        cycle.entities.push_back(instances[w].id);
        cycle.line = instances[w].line;
        return cycle;
      }
      if (state[w] == 0) {
        state[w] = 1;
        path.push_back({w, 0});
      }
    }
  }
  return {};
}

void RefuseReferenceCycles(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // OpenCASCADE's reader reports the file it cannot open
  std::ostringstream text;
  text << in.rdbuf();
  const ReferenceCycle cycle = FindReferenceCycle(text.str());
  if (cycle.entities.empty()) return;
  std::string chain;
  const std::size_t shown = 8;
  for (std::size_t k = 0; k < cycle.entities.size(); ++k) {
    if (k == shown && cycle.entities.size() > shown + 1) {
      chain += " -> ... (" + std::to_string(cycle.entities.size() - 1 - shown) + " more)";
      k = cycle.entities.size() - 1;
    }
    chain += (k ? " -> #" : "#") + std::to_string(cycle.entities[k]);
  }
  const std::string what = cycle.entities.size() == 2 ? "refers to itself" : "refers back to itself through others";
  throw std::runtime_error("malformed STEP file, line " + std::to_string(cycle.line) + ": entity #" +
                           std::to_string(cycle.entities.front()) + " " + what + " (" + chain +
                           "); STEP entities must not form a reference cycle");
}

}  // namespace hull::step_iges
