// How likely a candidate line is the horizon, from the evidence measured for it: a logistic
// regression over a few features of colour, brightness, texture and edge support, learned from
// labelled frames with and without a horizon (rle_vision_eval_horizon --train; the package
// ships config/horizon_model.yaml). Without a model the horizon's confidence is the product of
// the region evidence, as before.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace rle_vision {

// The evidence for one candidate line. The parts of the evidence are log-probabilities (each
// part a share or a probability in (0, 1], floored at 0.01; ratios r through r / (1 + r)).
enum HorizonFeature {
  kSeparation,      // the colour separation of the two sides (1 - Bhattacharyya coefficient)
  kSkyBrighter,     // P(a sky cell is brighter than a ground cell)
  kGroundRougher,   // P(a ground edge value exceeds a sky one)
  kGroundTextured,  // the share of textured ground
  kGroundTexturedRelative,  // the same in contrast relative to brightness (Weber): a tone curve keeps it
  kCoverage,        // the share of scan lines whose edge point lies on the line
  kFitSpread,       // inlier tolerance / (tolerance + the inliers' rms distance)
  kEdgeContrast,    // the edge value at the line over the sky's own high edge values (a ratio)
  kLocalStep,       // the colour step across the line over the colour spread along it (a ratio)
  kSkyShare,        // logit of the share of the frame above the line
  kTilt,            // |angle| of the line / 90 deg
  kFromRegions,     // 1: a region split; 0: merged Hough lines
  kHorizonFeatureCount
};

using HorizonFeatures = std::array<double, kHorizonFeatureCount>;

// Feature names as the model file writes them.
const char* horizonFeatureName(int feature);

struct HorizonModel {
  HorizonFeatures mean{}, scale{}, weights{};  // features are standardised: (f - mean) / scale
  double bias = 0;
  // The candidates are weighed in order (region splits, then merged Hough lines) and the first
  // whose probability reaches this is taken, the rest not refined: a sure horizon costs one
  // refinement instead of a dozen. Chosen with the model (the stop that gets the most frames
  // right in its cross-validation); above 1: every candidate weighed, the most probable taken.
  double stop_probability = 2;
  bool valid = false;  // false: no model (the product of the region evidence is used)
  // P(the candidate is the horizon).
  double probability(const HorizonFeatures& features) const;
};

// Fits a model: L2-regularised logistic regression by Newton's method (IRLS), deterministic.
// `labels` 1 for candidates that are the horizon; `weights` per sample (e.g. to balance frames
// with and without a horizon); `l2` on the standardised weights (not the bias). The penalty
// chooses the weights' direction; their scale and the bias are then refitted without it, so the
// probability stays calibrated under a strong penalty. Returns an invalid model when there are
// no samples of one of the two labels.
HorizonModel fitHorizonModel(const std::vector<HorizonFeatures>& features, const std::vector<int>& labels,
                             const std::vector<double>& weights, double l2);

}  // namespace rle_vision
