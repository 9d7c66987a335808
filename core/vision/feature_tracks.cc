#include "vision/feature_tracks.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <stdexcept>

namespace hull {

TrackBuilder::TrackBuilder(const std::vector<int>& features) {
  offset_.reserve(features.size() + 1);
  int total = 0;
  for (std::size_t k = 0; k < features.size(); ++k) {
    offset_.push_back(total);
    total += features[k];
  }
  offset_.push_back(total);
  parent_.resize(static_cast<std::size_t>(total));
  keyframe_of_.resize(static_cast<std::size_t>(total));
  keyframes_.resize(static_cast<std::size_t>(total));
  for (std::size_t k = 0; k < features.size(); ++k) {
    for (int n = offset_[k]; n < offset_[k + 1]; ++n) {
      parent_[static_cast<std::size_t>(n)] = n;
      keyframe_of_[static_cast<std::size_t>(n)] = static_cast<int>(k);
      keyframes_[static_cast<std::size_t>(n)] = {static_cast<int>(k)};
    }
  }
}

int TrackBuilder::Find(int x) {
  while (parent_[static_cast<std::size_t>(x)] != x) {
    int& p = parent_[static_cast<std::size_t>(x)];
    p = parent_[static_cast<std::size_t>(p)];  // path halving
    x = p;
  }
  return x;
}

bool TrackBuilder::Link(int ka, int fa, int kb, int fb) {
  const int nk = static_cast<int>(offset_.size()) - 1;
  if (ka < 0 || kb < 0 || ka >= nk || kb >= nk || fa < 0 || fb < 0 ||
      fa >= offset_[static_cast<std::size_t>(ka) + 1] - offset_[static_cast<std::size_t>(ka)] ||
      fb >= offset_[static_cast<std::size_t>(kb) + 1] - offset_[static_cast<std::size_t>(kb)])
    throw std::out_of_range("TrackBuilder::Link: no such feature");
  int ra = Find(Node(ka, fa)), rb = Find(Node(kb, fb));
  if (ra == rb) return true;  // already one track
  auto& A = keyframes_[static_cast<std::size_t>(ra)];
  auto& B = keyframes_[static_cast<std::size_t>(rb)];
  // Refuse when the tracks share a keyframe (two features of one image).
  for (auto i = A.begin(), j = B.begin(); i != A.end() && j != B.end();) {
    if (*i == *j) {
      ++refused_;
      return false;
    }
    if (*i < *j)
      ++i;
    else
      ++j;
  }
  if (A.size() < B.size()) std::swap(ra, rb);  // attach the smaller track
  auto& big = keyframes_[static_cast<std::size_t>(ra)];
  auto& small = keyframes_[static_cast<std::size_t>(rb)];
  std::vector<int> merged;
  merged.reserve(big.size() + small.size());
  std::merge(big.begin(), big.end(), small.begin(), small.end(), std::back_inserter(merged));
  big = std::move(merged);
  small.clear();
  small.shrink_to_fit();
  parent_[static_cast<std::size_t>(rb)] = ra;
  return true;
}

std::vector<TrackBuilder::Track> TrackBuilder::Tracks(int min_keyframes, int* dropped) const {
  // Group nodes by root (a const Find without compression).
  auto root = [&](int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) x = parent_[static_cast<std::size_t>(x)];
    return x;
  };
  std::map<int, Track> by_root;  // ordered by root; re-sorted by first member below
  const int nk = static_cast<int>(offset_.size()) - 1;
  for (int k = 0; k < nk; ++k) {
    for (int n = offset_[static_cast<std::size_t>(k)]; n < offset_[static_cast<std::size_t>(k) + 1]; ++n) {
      const int r = root(n);
      if (keyframes_[static_cast<std::size_t>(r)].size() < 2) continue;  // a lone feature is no track
      by_root[r].emplace_back(k, n - offset_[static_cast<std::size_t>(k)]);
    }
  }
  std::vector<Track> out;
  int drop = 0;
  for (auto& [r, t] : by_root) {
    if (static_cast<int>(t.size()) < min_keyframes) {
      ++drop;
      continue;
    }
    out.push_back(std::move(t));
  }
  std::sort(out.begin(), out.end(), [](const Track& a, const Track& b) { return a.front() < b.front(); });
  if (dropped) *dropped = drop;
  return out;
}

}  // namespace hull
