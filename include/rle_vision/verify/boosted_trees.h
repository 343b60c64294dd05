// A trained OpenCV Boost model's trees copied into flat arrays, evaluated without OpenCV's
// per-call overhead (a Mat header, a range, buffers, a virtual call per model): the verifier
// scores up to 50 candidates a frame with several models each. The sum is the one
// Boost::predict(PREDICT_SUM) returns, bit for bit (gtest BoostedTrees.*).
#pragma once

#include <vector>

namespace cv {
namespace ml {
class Boost;
}  // namespace ml
}  // namespace cv

namespace rle_vision {

class BoostedTrees {
 public:
  // Copies `model`'s trees: a model on ordered variables, all of them (as BlobVerifier trains
  // them; BlobVerifier::load refuses other files). A model with an inverted split leaves it
  // empty (!usable()), for OpenCV to evaluate.
  explicit BoostedTrees(const cv::ml::Boost& model);

  bool usable() const { return !roots_.empty(); }
  // The sum of the leaf values `features` reach in every tree (as PREDICT_SUM), for features
  // without a missing value (OpenCV's FLT_MAX, which OpenCV reads in its own way).
  float sum(const float* features) const;

 private:
  struct Node {
    int variable;      // -1: a leaf
    float threshold;   // go left when the feature is <= threshold
    int left, right;   // node indices
    double value;      // a leaf's value
  };
  // A tree of depth 2 at most, made complete (a leaf above depth 2 repeated below its place):
  // walked without a branch, two comparisons and an index. Candidates differ from one another, so
  // the walk's branches were mispredicted half the time: most of the score's cost.
  struct DepthTwoTree {
    int variable[3];   // the root, its left child, its right child
    float threshold[3];
    double leaf[4];    // left-left, left-right, right-left, right-right
  };
  // Fills depth_two_ when every tree has depth 2 at most (as BlobVerifier trains them).
  void makeDepthTwo();

  std::vector<Node> nodes_;
  std::vector<int> roots_;
  std::vector<DepthTwoTree> depth_two_;
};

}  // namespace rle_vision
