
#include "rle_vision/config_files.h"
#include "yaml_reader.h"

namespace rle_vision {
namespace {

// Every key of a landmark parameters file: the landmark step's, colour learning's, and the
// ROS-only ones (low_priority, learning, learning_publish_period_s).
const std::initializer_list<const char*> kLandmarkFileKeys = {
    "edge_gain", "gray_threshold", "sharp_threshold", "min_object_px", "thin_edges", "min_votes",
    "min_line_length_px", "sampling_margin", "max_samples_per_object", "max_rounds", "max_failed_peaks",
    "min_pair_distance_px", "theta_bin_deg", "intercept_bin_px", "peak_angle_deg", "peak_distance_px",
    "fit_distance_px", "max_gap_px", "min_support_ratio", "seed", "horizon_min_piece_px", "horizon_max_angle_deg",
    "horizon_merge_angle_deg", "horizon_merge_distance_px", "horizon_min_coverage", "low_priority", "learning",
    "learning_blend", "learning_match_gate", "learning_max_sigma", "learning_mode_radius", "learning_min_region_px",
    "learning_shrink_px", "learning_horizon_margin_px", "learning_stale_after_s", "learning_create_classes",
    "learning_persist_frames", "learning_min_new_class_px", "learning_publish_period_s"};

bool boolean(const std::string& origin, const YAML::Node& map, const char* key, bool fallback) {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  try {
    return node.as<bool>();
  } catch (const YAML::Exception&) {
    yaml_reader::fail(origin, node, std::string("'") + key + "' must be true or false");
  }
}

}  // namespace

LandmarkOptions parseLandmarkParams(const std::string& text, const std::string& origin) {
  using namespace yaml_reader;
  LandmarkOptions o;
  const YAML::Node root = parse(text, origin);
  if (!root || root.IsNull()) return o;
  checkKeys(origin, root, kLandmarkFileKeys);
  o.edge_gain = number(origin, root, "edge_gain", o.edge_gain, 0.05, 50);
  o.objects.gray_threshold = static_cast<uint8_t>(number(origin, root, "gray_threshold", o.objects.gray_threshold, 1, 255));
  o.objects.sharp_threshold = static_cast<uint8_t>(number(origin, root, "sharp_threshold", o.objects.sharp_threshold, 1, 255));
  o.objects.min_object_px = static_cast<uint32_t>(number(origin, root, "min_object_px", o.objects.min_object_px, 1, 1e6));
  o.objects.thin = boolean(origin, root, "thin_edges", o.objects.thin);
  HoughOptions& h = o.hough;
  h.min_votes = static_cast<int>(number(origin, root, "min_votes", h.min_votes, 1, 1000));
  h.min_line_length_px = number(origin, root, "min_line_length_px", h.min_line_length_px, 5, 2000);
  h.sampling_margin = number(origin, root, "sampling_margin", h.sampling_margin, 0.1, 100);
  h.max_samples_per_object = static_cast<int>(number(origin, root, "max_samples_per_object", h.max_samples_per_object, 10, 1e6));
  h.max_rounds = static_cast<int>(number(origin, root, "max_rounds", h.max_rounds, 1, 20));
  h.max_failed_peaks = static_cast<int>(number(origin, root, "max_failed_peaks", h.max_failed_peaks, 1, 1000));
  h.min_pair_distance_px = number(origin, root, "min_pair_distance_px", h.min_pair_distance_px, 0, 500);
  h.theta_bin_deg = number(origin, root, "theta_bin_deg", h.theta_bin_deg, 0.1, 10);
  h.intercept_bin_px = number(origin, root, "intercept_bin_px", h.intercept_bin_px, 0.25, 50);
  h.peak_angle_deg = number(origin, root, "peak_angle_deg", h.peak_angle_deg, 0.1, 30);
  h.peak_distance_px = number(origin, root, "peak_distance_px", h.peak_distance_px, 0.1, 100);
  h.fit_distance_px = number(origin, root, "fit_distance_px", h.fit_distance_px, 0.5, 50);
  h.max_gap_px = number(origin, root, "max_gap_px", h.max_gap_px, 0.5, 500);
  h.min_support_ratio = number(origin, root, "min_support_ratio", h.min_support_ratio, 0, 20);
  h.seed = static_cast<uint64_t>(number(origin, root, "seed", static_cast<double>(h.seed), 0, 2147483647));
  HorizonOptions& z = o.horizon;
  z.min_piece_length_px = number(origin, root, "horizon_min_piece_px", z.min_piece_length_px, 1, 5000);
  z.max_angle_deg = number(origin, root, "horizon_max_angle_deg", z.max_angle_deg, 1, 89);
  z.merge_angle_deg = number(origin, root, "horizon_merge_angle_deg", z.merge_angle_deg, 0.05, 45);
  z.merge_distance_px = number(origin, root, "horizon_merge_distance_px", z.merge_distance_px, 0.1, 200);
  z.min_coverage = number(origin, root, "horizon_min_coverage", z.min_coverage, 0, 1);
  const std::string problem = validateLandmarkOptions(o);
  if (!problem.empty()) fail(origin, root, problem);
  return o;
}

LandmarkOptions loadLandmarkParams(const std::string& path) { return parseLandmarkParams(yaml_reader::readFile(path), path); }

LearningOptions parseLearningParams(const std::string& text, const std::string& origin) {
  using namespace yaml_reader;
  LearningOptions o;
  const YAML::Node root = parse(text, origin);
  if (!root || root.IsNull()) return o;
  checkKeys(origin, root, kLandmarkFileKeys);
  o.blend = number(origin, root, "learning_blend", o.blend, 0.01, 1);
  o.match_gate = number(origin, root, "learning_match_gate", o.match_gate, 1, 255);
  o.max_sigma = number(origin, root, "learning_max_sigma", o.max_sigma, 1, 128);
  o.mode_radius = number(origin, root, "learning_mode_radius", o.mode_radius, 2, 128);
  o.min_region_px = static_cast<uint32_t>(number(origin, root, "learning_min_region_px", o.min_region_px, 1, 1e6));
  o.shrink_px = number(origin, root, "learning_shrink_px", o.shrink_px, 0, 20);
  o.horizon_margin_px = number(origin, root, "learning_horizon_margin_px", o.horizon_margin_px, 0, 100);
  o.stale_after_s = number(origin, root, "learning_stale_after_s", o.stale_after_s, 0, 3600);
  o.create_classes = boolean(origin, root, "learning_create_classes", o.create_classes);
  o.persist_frames = static_cast<int>(number(origin, root, "learning_persist_frames", o.persist_frames, 1, 10000));
  o.min_new_class_px = static_cast<uint32_t>(number(origin, root, "learning_min_new_class_px", o.min_new_class_px, 1, 1e6));
  const std::string problem = validateLearningOptions(o);
  if (!problem.empty()) fail(origin, root, problem);
  return o;
}

LearningOptions loadLearningParams(const std::string& path) { return parseLearningParams(yaml_reader::readFile(path), path); }

}  // namespace rle_vision
