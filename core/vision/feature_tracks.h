// Feature tracks across keyframes: union-find over the top-image features
// of all keyframes, linked by accepted temporal matches. A track never
// holds two features of the same image: a link that would merge two tracks
// sharing a keyframe is refused (links are offered best first, so the
// better match wins). Tracks seen in fewer than min_keyframes keyframes are
// dropped.
#pragma once

#include <utility>
#include <vector>

namespace hull {

class TrackBuilder {
 public:
  // features[k]: number of (top) features of keyframe index k.
  explicit TrackBuilder(const std::vector<int>& features);

  // Links feature fa of keyframe ka with feature fb of keyframe kb; false
  // when refused (the two tracks share a keyframe; also ka == kb).
  bool Link(int ka, int fa, int kb, int fb);
  int refused() const { return refused_; }

  // (keyframe index, feature index) per track, sorted by keyframe; tracks
  // with fewer than min_keyframes keyframes are left out (counted in
  // *dropped when given). Tracks are ordered by their first member.
  using Track = std::vector<std::pair<int, int>>;
  std::vector<Track> Tracks(int min_keyframes, int* dropped = nullptr) const;

 private:
  int Node(int k, int f) const { return offset_[static_cast<std::size_t>(k)] + f; }
  int Find(int x);
  std::vector<int> offset_;
  std::vector<int> parent_;
  std::vector<int> keyframe_of_;             // node -> keyframe index
  std::vector<std::vector<int>> keyframes_;  // root -> sorted keyframe indices of its track
  int refused_ = 0;
};

}  // namespace hull
