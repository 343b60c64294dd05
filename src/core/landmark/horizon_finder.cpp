#include "rle_vision/landmark/horizon_finder.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "landmark/horizon_refine.h"
#include "landmark/horizon_regions.h"

namespace rle_vision {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kMinSideFraction = 0.01;  // a split leaves at least 1% of the frame on each side

// Tolerances in pixels for a width x height image.
struct PieceTolerances {
  double min_length, merge_distance, merge_angle, max_angle;
  PieceTolerances(const HorizonOptions& o, int width, int height) {
    const double diagonal = std::hypot(width, height);
    min_length = o.min_piece_pct / 100 * diagonal;
    merge_distance = o.merge_distance_pct / 100 * diagonal;
    merge_angle = o.merge_angle_deg * kDeg;
    max_angle = o.max_angle_deg * kDeg;
  }
};

bool collinear(const DetectedLine& a, const DetectedLine& b, const PieceTolerances& t) {
  if (lineAngleDifference(a.line.theta, b.line.theta) > t.merge_angle) return false;
  // Every end point of each piece lies near the other piece's line.
  return std::fabs(signedDistance(a.line, b.x1, b.y1)) <= t.merge_distance &&
         std::fabs(signedDistance(a.line, b.x2, b.y2)) <= t.merge_distance &&
         std::fabs(signedDistance(b.line, a.x1, a.y1)) <= t.merge_distance &&
         std::fabs(signedDistance(b.line, a.x2, a.y2)) <= t.merge_distance;
}

int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

double farthestEnd(const DetectedLine& piece, const ImageLine& line) {
  return std::max(std::fabs(signedDistance(line, piece.x1, piece.y1)), std::fabs(signedDistance(line, piece.x2, piece.y2)));
}

// A robust line through pieces: fitted on all their pixels, then the piece whose ends lie
// farthest from it is dropped while that is beyond `tolerance` (a piece chained in through a
// neighbour must not tilt the line), and the rest refitted. Leaves the kept pieces in `pieces`.
bool fitPieces(const std::vector<DetectedLine>& lines, double tolerance, std::vector<int>* pieces, ImageLine* line,
               double* rms) {
  while (!pieces->empty()) {
    PointSums sums;
    for (int i : *pieces) sums.add(lines[i].sums);
    if (!sums.fitLine(line, rms)) return false;
    const auto worst = std::max_element(pieces->begin(), pieces->end(), [&](int a, int b) {
      return farthestEnd(lines[a], *line) < farthestEnd(lines[b], *line);
    });
    if (farthestEnd(lines[*worst], *line) <= tolerance || pieces->size() == 1) return true;
    pieces->erase(worst);
  }
  return false;
}

// The merged line of a group of pieces as a horizon estimate (no region evidence).
HorizonEstimate mergedPieces(const std::vector<DetectedLine>& lines, std::vector<int> pieces, int width, int height,
                             double tolerance) {
  HorizonEstimate h;
  if (!fitPieces(lines, tolerance, &pieces, &h.line, &h.rms)) return h;
  double cx1, cy1, cx2, cy2;
  if (!clipLineToImage(h.line, width, height, &cx1, &cy1, &cx2, &cy2)) return h;
  // Extent: the outermost piece end points, projected on the merged line.
  const double dx = std::cos(h.line.theta), dy = std::sin(h.line.theta);
  double px, py;
  pointOnLine(h.line, &px, &py);
  double t_min = INFINITY, t_max = -INFINITY;
  for (int i : pieces) {
    const DetectedLine& piece = lines[i];
    h.length += piece.length;
    h.votes += piece.votes;
    h.support += piece.support;
    ++h.pieces;
    for (const double t : {(piece.x1 - px) * dx + (piece.y1 - py) * dy, (piece.x2 - px) * dx + (piece.y2 - py) * dy}) {
      t_min = std::min(t_min, t);
      t_max = std::max(t_max, t);
    }
  }
  h.coverage = std::min(1.0, h.length / std::hypot(cx2 - cx1, cy2 - cy1));
  h.x1 = px + t_min * dx;
  h.y1 = py + t_min * dy;
  h.x2 = px + t_max * dx;
  h.y2 = py + t_max * dy;
  h.confidence = h.coverage * std::min(1.0, 1.5 / std::max(h.rms, 1e-9));
  return h;
}

// The merged groups of collinear horizon pieces among the lines, longest first.
std::vector<HorizonEstimate> mergedGroups(const std::vector<DetectedLine>& lines, int width, int height,
                                          const HorizonOptions& o) {
  const PieceTolerances t(o, width, height);
  std::vector<int> candidates;
  for (int i = 0; i < static_cast<int>(lines.size()); ++i) {
    if (lines[i].length >= t.min_length && std::fabs(lines[i].line.theta) <= t.max_angle) candidates.push_back(i);
  }
  std::vector<int> parent(candidates.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (size_t j = i + 1; j < candidates.size(); ++j) {
      if (collinear(lines[candidates[i]], lines[candidates[j]], t)) parent[root(parent, i)] = root(parent, j);
    }
  }
  std::vector<HorizonEstimate> groups;
  for (size_t g = 0; g < candidates.size(); ++g) {
    if (root(parent, g) != static_cast<int>(g)) continue;
    std::vector<int> group;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (root(parent, i) == static_cast<int>(g)) group.push_back(candidates[i]);
    }
    HorizonEstimate h = mergedPieces(lines, group, width, height, t.merge_distance);
    if (h.pieces > 0 && h.coverage >= o.min_coverage) groups.push_back(h);
  }
  std::stable_sort(groups.begin(), groups.end(),
                   [](const HorizonEstimate& a, const HorizonEstimate& b) { return a.length > b.length; });
  return groups;
}

}  // namespace

HorizonEstimate findHorizon(const std::vector<DetectedLine>& lines, int width, int height, const HorizonOptions& o) {
  std::vector<HorizonEstimate> groups = mergedGroups(lines, width, height, o);
  if (groups.empty()) return HorizonEstimate();
  groups.front().found = true;
  return groups.front();
}

struct HorizonDetector::Impl {
  horizon::RegionGrid fine, coarse;
  horizon::HorizonRefiner refiner;

  HorizonEstimate detect(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain,
                         const std::vector<DetectedLine>& lines, const HorizonOptions& o);
  // Every candidate, in order (region splits, then merged Hough lines), up to the first whose
  // model probability reaches `stop_at` (INFINITY: all).
  std::vector<HorizonEstimate> candidates(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain, double stop_at,
                                          const std::vector<DetectedLine>& lines, const HorizonOptions& o);
  // Builds the grids; false when the frame is not one the region search can split.
  bool prepare(const cv::Mat& bgr, const cv::Mat& edges, const HorizonOptions& o);
  std::vector<horizon::Hypothesis> regionHypotheses(int width, int height, const horizon::RefineOptions& refine,
                                                    const HorizonOptions& o) const;
  static std::vector<horizon::Hypothesis> houghHypotheses(const std::vector<DetectedLine>& lines, int width,
                                                          int height, const HorizonOptions& o);
  // Refines the hypotheses in order into *best; true when one is convincing.
  bool weigh(const cv::Mat& edges, const std::vector<horizon::Hypothesis>& hypotheses,
             const horizon::RefineOptions& refine, const HorizonOptions& o, horizon::RefinedHorizon* best);
  static horizon::RefineOptions refineOptions(const HorizonOptions& o, double edge_gain);
  static HorizonEstimate estimate(const horizon::RefinedHorizon& r, const HorizonOptions& o, int width, int height);
  static HorizonFeatures features(const horizon::RefinedHorizon& r, bool from_regions, const HorizonOptions& o);
};

HorizonDetector::HorizonDetector() : impl_(std::make_unique<Impl>()) {}
HorizonDetector::~HorizonDetector() = default;
HorizonDetector::HorizonDetector(HorizonDetector&&) noexcept = default;
HorizonDetector& HorizonDetector::operator=(HorizonDetector&&) noexcept = default;

HorizonEstimate HorizonDetector::detect(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain,
                                        const std::vector<DetectedLine>& lines, const HorizonOptions& o) {
  return impl_->detect(bgr, edges, edge_gain, lines, o);
}

std::vector<HorizonEstimate> HorizonDetector::candidates(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain,
                                                         const std::vector<DetectedLine>& lines,
                                                         const HorizonOptions& o) {
  return impl_->candidates(bgr, edges, edge_gain, INFINITY, lines, o);
}

bool HorizonDetector::Impl::prepare(const cv::Mat& bgr, const cv::Mat& edges, const HorizonOptions& o) {
  const int width = bgr.cols, height = bgr.rows;
  if (bgr.type() != CV_8UC3 || edges.type() != CV_8UC1 || edges.size() != bgr.size()) return false;
  const int cell = std::clamp(static_cast<int>(std::lround(std::min(width, height) / static_cast<double>(o.grid_cells))), 1,
                              horizon::kMaxCell);
  if (width / cell < 4 || height / cell < 4) return false;  // too small for the region grids
  fine.build(bgr, cell);
  coarse.buildHalf(fine);
  refiner.sampleTexture(edges, fine);
  return true;
}

std::vector<horizon::Hypothesis> HorizonDetector::Impl::regionHypotheses(int width, int height,
                                                                        const horizon::RefineOptions& refine,
                                                                        const HorizonOptions& o) const {
  horizon::SearchOptions search;
  search.max_angle_deg = o.max_angle_deg;
  search.hypotheses = o.hypotheses;
  search.noise_variance = refine.noise_variance;
  search.min_fraction = kMinSideFraction;
  return horizon::searchSplits(fine, coarse, width, height, search);
}

std::vector<horizon::Hypothesis> HorizonDetector::Impl::houghHypotheses(const std::vector<DetectedLine>& lines,
                                                                       int width, int height,
                                                                       const HorizonOptions& o) {
  std::vector<horizon::Hypothesis> candidates;
  for (const HorizonEstimate& group : mergedGroups(lines, width, height, o)) {
    if (static_cast<int>(candidates.size()) >= o.hypotheses) break;
    const horizon::SplitLine l = horizon::SplitLine::fromImageLine(group.line);
    candidates.push_back({l.angle_deg, l.centreDistance(width, height), 0});
  }
  return candidates;
}

HorizonEstimate HorizonDetector::Impl::detect(const cv::Mat& bgr, const cv::Mat& edges, double edge_gain,
                                              const std::vector<DetectedLine>& lines, const HorizonOptions& o) {
  if (o.model.valid) {
    // The candidates weighed by the model: the most probable one, or the first the model is
    // sure of (its stop_probability), the rest not refined.
    HorizonEstimate best;
    bool any = false;
    for (const HorizonEstimate& h : candidates(bgr, edges, edge_gain, o.model.stop_probability, lines, o)) {
      if (!any || h.confidence > best.confidence) best = h;
      any = true;
    }
    return best;
  }
  if (!prepare(bgr, edges, o)) return HorizonEstimate();
  const int width = bgr.cols, height = bgr.rows;
  const horizon::RefineOptions refine = refineOptions(o, edge_gain);
  // The splits into two regions of distinct colours first (hazy or broken horizons)...
  horizon::RefinedHorizon best;
  if (weigh(edges, regionHypotheses(width, height, refine, o), refine, o, &best)) {
    return estimate(best, o, width, height);
  }
  // ... then long straight edges across the image (merged Hough pieces): where objects in view
  // outweigh the sky in the colour statistics.
  weigh(edges, houghHypotheses(lines, width, height, o), refine, o, &best);
  return estimate(best, o, width, height);
}

std::vector<HorizonEstimate> HorizonDetector::Impl::candidates(const cv::Mat& bgr, const cv::Mat& edges,
                                                               double edge_gain, double stop_at,
                                                               const std::vector<DetectedLine>& lines,
                                                               const HorizonOptions& o) {
  std::vector<HorizonEstimate> out;
  if (!prepare(bgr, edges, o)) return out;
  const int width = bgr.cols, height = bgr.rows;
  // Each hypothesis refined against the sky's high edge values and, where the options ask,
  // again against its typical ones: under a cloud-textured sky a hazy ridge is fainter than the
  // clouds' edges, and the first refinement passes over it to the stronger step below. The
  // model weighs both (the evidence product, detect() without a model, refines once).
  const horizon::RefineOptions refine = refineOptions(o, edge_gain);
  std::vector<double> sky_percentiles = {o.sky_percentile};
  if (o.textured_sky_percentile < o.sky_percentile) sky_percentiles.push_back(o.textured_sky_percentile);
  bool sure = false;
  for (const bool from_regions : {true, false}) {
    const std::vector<horizon::Hypothesis> hypotheses =
        from_regions ? regionHypotheses(width, height, refine, o) : houghHypotheses(lines, width, height, o);
    for (const horizon::Hypothesis& hypothesis : hypotheses) {
      refiner.refineEach(edges, fine, hypothesis, refine, sky_percentiles, [&](const horizon::RefinedHorizon& r) {
        // The fit may turn a line past the steepest horizon the user allows: then it is not one.
        if (std::fabs(r.line.angle_deg) > o.max_angle_deg) return false;
        HorizonEstimate h = estimate(r, o, width, height);
        h.features = features(r, from_regions, o);
        if (o.model.valid) {
          h.confidence = o.model.probability(h.features);
          h.found = h.confidence >= o.min_confidence;
        }
        out.push_back(h);
        sure = o.model.valid && h.confidence >= stop_at;
        return sure;  // the candidate the model is sure of: the lower percentile not refined
      });
      if (sure) return out;
    }
  }
  return out;
}

HorizonFeatures HorizonDetector::Impl::features(const horizon::RefinedHorizon& r, bool from_regions,
                                                const HorizonOptions& o) {
  // The evidence as log-probabilities (every part in (0, 1], floored at 0.01): a model that
  // weighs them positively is a weighted product of the parts, which a strong part cannot
  // make up for a missing one in (a field line is a strong edge, but no sky above ground).
  auto log_part = [](double q) { return std::log(std::clamp(q, 0.01, 1.0)); };
  auto saturating = [](double ratio) { return ratio / (1 + ratio); };  // 0..1 for a ratio 0..inf
  HorizonFeatures f{};
  f[kSeparation] = log_part(r.evidence.separation);
  f[kSkyBrighter] = log_part(r.evidence.sky_brighter);
  f[kGroundRougher] = log_part(r.evidence.ground_rougher);
  f[kGroundTextured] = log_part(r.evidence.ground_textured);
  f[kGroundTexturedRelative] = log_part(r.evidence.ground_textured_relative);
  f[kCoverage] = log_part(r.scanlines > 0 ? static_cast<double>(r.inliers) / r.scanlines : 0);
  f[kFitSpread] = log_part(o.inlier_px / (o.inlier_px + r.rms));
  f[kEdgeContrast] = log_part(saturating((r.edge_at_line + 1) / (r.sky_edge_level + 1)));
  f[kLocalStep] = log_part(saturating(r.evidence.local_step));
  const double sky = std::clamp(r.evidence.sky_share, 0.01, 0.99);
  f[kSkyShare] = std::log(sky / (1 - sky));
  f[kTilt] = std::fabs(r.line.angle_deg) / 90;
  f[kFromRegions] = from_regions ? 1 : 0;
  return f;
}

horizon::RefineOptions HorizonDetector::Impl::refineOptions(const HorizonOptions& o, double edge_gain) {
  horizon::RefineOptions refine;
  refine.band_cells = o.band_cells;
  refine.sky_percentile = o.sky_percentile;
  refine.edge_floor = o.noise_grey * edge_gain;  // the edge value of a step of noise_grey grey levels
  refine.peak_ratio = o.peak_ratio;
  refine.inlier_px = o.inlier_px;
  refine.noise_variance = o.noise_grey * o.noise_grey;
  return refine;
}

HorizonEstimate HorizonDetector::Impl::estimate(const horizon::RefinedHorizon& r, const HorizonOptions& o, int width,
                                                int height) {
  HorizonEstimate h;
  if (r.scanlines == 0 && r.points == 0 && r.evidence.separation == 0) return h;  // nothing weighed
  h.line = r.line.imageLine();
  h.confidence = r.evidence.confidence();
  h.found = h.confidence >= o.min_confidence;
  h.separation = r.evidence.separation;
  h.sky_brighter = r.evidence.sky_brighter;
  h.ground_rougher = r.evidence.ground_rougher;
  h.ground_textured = r.evidence.ground_textured;
  h.support = static_cast<uint32_t>(r.inliers);
  h.length = r.inliers;
  h.rms = r.rms;
  h.coverage = r.scanlines > 0 ? static_cast<double>(r.inliers) / r.scanlines : 0;
  if (r.inliers > 0) {
    const double dx = r.line.ny, dy = -r.line.nx, px = r.line.rho * r.line.nx, py = r.line.rho * r.line.ny;
    h.x1 = px + r.t_min * dx;
    h.y1 = py + r.t_min * dy;
    h.x2 = px + r.t_max * dx;
    h.y2 = py + r.t_max * dy;
  } else {
    clipLineToImage(h.line, width, height, &h.x1, &h.y1, &h.x2, &h.y2);
  }
  return h;
}

bool HorizonDetector::Impl::weigh(const cv::Mat& edges, const std::vector<horizon::Hypothesis>& hypotheses,
                                  const horizon::RefineOptions& refine, const HorizonOptions& o,
                                  horizon::RefinedHorizon* best) {
  // In order: the first convincing one ends the search; else the most convincing so far stays.
  for (const horizon::Hypothesis& hypothesis : hypotheses) {
    horizon::RefinedHorizon r = refiner.refine(edges, fine, hypothesis, refine);
    // The fit may turn a line past the steepest horizon the user allows: then it is not one.
    if (std::fabs(r.line.angle_deg) > o.max_angle_deg) continue;
    const bool convincing = r.evidence.confidence() >= o.min_confidence;
    if (convincing || r.evidence.confidence() > best->evidence.confidence() || best->scanlines == 0) *best = r;
    if (convincing) return true;
  }
  return false;
}

}  // namespace rle_vision
