#include "rle_vision/verify/boosted_trees.h"

#include <algorithm>

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
  makeDepthTwo();
}

void BoostedTrees::makeDepthTwo() {
  depth_two_.clear();
  for (const int root : roots_) {
    DepthTwoTree tree{{0, 0, 0}, {0, 0, 0}, {0, 0, 0, 0}};
    const Node& top = nodes_[static_cast<size_t>(root)];
    const int children[2] = {top.variable >= 0 ? top.left : root, top.variable >= 0 ? top.right : root};
    tree.variable[0] = std::max(0, top.variable);
    tree.threshold[0] = top.threshold;
    for (int side = 0; side < 2; ++side) {
      const Node& child = nodes_[static_cast<size_t>(children[side])];
      const Node* leaves[2] = {&child, &child};
      if (child.variable >= 0) {
        leaves[0] = &nodes_[static_cast<size_t>(child.left)];
        leaves[1] = &nodes_[static_cast<size_t>(child.right)];
        if (leaves[0]->variable >= 0 || leaves[1]->variable >= 0) {  // deeper: the walk below
          depth_two_.clear();
          return;
        }
      }
      tree.variable[1 + side] = std::max(0, child.variable);
      tree.threshold[1 + side] = child.threshold;
      tree.leaf[2 * side] = leaves[0]->value;
      tree.leaf[2 * side + 1] = leaves[1]->value;
    }
    depth_two_.push_back(tree);
  }
}

float BoostedTrees::sum(const float* features) const {
  double total = 0;
  if (!depth_two_.empty()) {
    for (const DepthTwoTree& tree : depth_two_) {
      // Left when the feature is <= the threshold (a NaN goes right, as in the walk below).
      const int right = !(features[tree.variable[0]] <= tree.threshold[0]);
      const int then_right = !(features[tree.variable[1 + right]] <= tree.threshold[1 + right]);
      total += tree.leaf[2 * right + then_right];
    }
    return static_cast<float>(total);
  }
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
