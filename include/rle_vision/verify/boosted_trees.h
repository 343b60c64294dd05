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
  std::vector<Node> nodes_;
  std::vector<int> roots_;
};

}  // namespace rle_vision
