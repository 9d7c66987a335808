// Parse and write time of core/base/json on a document shaped like a large
// adjustment.json: per-keyframe objects with a pose, its 6x6 covariance and
// a few scalars, written by Json::Dump and read back by Json::Parse.
//   bench_json [keyframes=20000] [repeats=5] [file]
// With `file`, that JSON file is parsed instead of the made-up document.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "base/file_io.h"
#include "base/json.h"

namespace {

hull::Json MakeDocument(int keyframes) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  hull::Json root = hull::Json::Object();
  root.Set("version", 1);
  root.Set("solver", "max-mixture");
  hull::Json frames = hull::Json::Array();
  for (int i = 0; i < keyframes; ++i) {
    hull::Json f = hull::Json::Object();
    f.Set("step", i);
    f.Set("time", 0.1 * i + 1e-3 * n(rng));
    std::vector<double> pose(6), cov(36);
    for (double& v : pose) v = 10 * n(rng);
    for (double& v : cov) v = 1e-4 * n(rng);
    f.Set("x_gV", hull::Json::ArrayOf(pose));
    f.Set("covariance", hull::Json::ArrayOf(cov));
    f.Set("inlier", i % 7 != 0);
    f.Set("label", "keyframe " + std::to_string(i));
    frames.Push(std::move(f));
  }
  root.Set("keyframes", std::move(frames));
  return root;
}

template <typename F>
double MedianSeconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int keyframes = argc > 1 ? std::atoi(argv[1]) : 20000;
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  std::string text;
  double dump_s = 0;
  if (argc > 3) {
    text = hull::ReadFileToString(argv[3]);
  } else {
    const hull::Json doc = MakeDocument(keyframes);
    dump_s = MedianSeconds(repeats, [&] { text = doc.Dump(); });
  }
  std::size_t values = 0;
  const double parse_s = MedianSeconds(repeats, [&] {
    const hull::Json back = hull::Json::Parse(text, "bench.json");
    values = back.is_object() ? back.members().size() : 0;
  });
  std::printf("document %.3f MB%s, median of %d: parse %.3f ms (%.0f MB/s), dump %.3f ms (%zu top-level members)\n",
              text.size() / 1e6, argc > 3 ? "" : " (made up)", repeats, 1e3 * parse_s, text.size() / 1e6 / parse_s,
              1e3 * dump_s, values);
  return 0;
}
