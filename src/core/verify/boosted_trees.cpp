#include "rle_vision/verify/boosted_trees.h"

#include <opencv2/ml.hpp>

namespace rle_vision {

BoostedTrees::BoostedTrees(const cv::ml::Boost& model) {
  if (!model.isTrained()) return;
  const std::vector<cv::ml::DTrees::Node>& nodes = model.getNodes();
  const std::vector<cv::ml::DTrees::Split>& splits = model.getSplits();
  nodes_.reserve(nodes.size());
  for (const cv::ml::DTrees::Node& n : nodes) {
    Node flat{-1, 0.0f, n.left, n.right, n.value};
    if (n.split >= 0) {
      const cv::ml::DTrees::Split& s = splits[static_cast<size_t>(n.split)];
      if (s.inversed || s.varIdx < 0 || s.varIdx >= model.getVarCount()) {  // not what training makes: left to OpenCV
        nodes_.clear();
        return;
      }
      flat.variable = s.varIdx;
      flat.threshold = s.c;
    }
    nodes_.push_back(flat);
  }
  roots_ = model.getRoots();
}

float BoostedTrees::sum(const float* features) const {
  double total = 0;
  for (const int root : roots_) {
    const Node* node = &nodes_[static_cast<size_t>(root)];
    while (node->variable >= 0) {
      node = &nodes_[static_cast<size_t>(features[node->variable] <= node->threshold ? node->left : node->right)];
    }
    total += node->value;
  }
  return static_cast<float>(total);
}

}  // namespace rle_vision
