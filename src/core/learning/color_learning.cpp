#include "rle_vision/learning/color_learning.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <opencv2/imgproc.hpp>

#include "rle_vision/landmark/param_range.h"
#include "rle_vision/color/color_convert.h"

namespace rle_vision {
namespace {

// Where a line crosses another, and whether that point lies on (or near the ends of) both
// segments.
bool meetNear(const DetectedLine& a, const DetectedLine& b, double reach, cv::Point2d* p) {
  double a1, b1, c1, a2, b2, c2;
  homogeneousFromLine(a.line, &a1, &b1, &c1);
  homogeneousFromLine(b.line, &a2, &b2, &c2);
  const double det = a1 * b2 - a2 * b1;
  if (std::fabs(det) < 1e-6) return false;
  p->x = (b1 * c2 - b2 * c1) / det;
  p->y = (a2 * c1 - a1 * c2) / det;
  auto within = [&](const DetectedLine& l) {
    const double dx = l.x2 - l.x1, dy = l.y2 - l.y1, length2 = dx * dx + dy * dy;
    const double t = ((p->x - l.x1) * dx + (p->y - l.y1) * dy) / length2;
    const double margin = reach / std::sqrt(length2);
    return t >= -margin && t <= 1 + margin;
  };
  return within(a) && within(b);
}

bool overlaps(const ColorStats& a, const ColorStats& b) {
  for (int ch = 0; ch < 3; ++ch) {
    if (a.hi[ch] < b.lo[ch] || b.hi[ch] < a.lo[ch]) return false;
  }
  return true;
}

// A smoothed range (lo and hi per channel) as whole levels, widened to them: what a class holds.
ColorStats byteRange(const double* lo, const double* hi) {
  ColorStats range;
  for (int ch = 0; ch < 3; ++ch) {
    range.lo[ch] = saturateToByte(static_cast<int>(std::floor(lo[ch])));
    range.hi[ch] = saturateToByte(static_cast<int>(std::ceil(hi[ch])));
  }
  return range;
}

bool holds(const ColorStats& range, const cv::Vec3b& p) {
  return p[0] >= range.lo[0] && p[0] <= range.hi[0] && p[1] >= range.lo[1] && p[1] <= range.hi[1] &&
         p[2] >= range.lo[2] && p[2] <= range.hi[2];
}

bool wrapped(const ColorClass& c) { return c.min[0] > c.max[0] || c.min[1] > c.max[1] || c.min[2] > c.max[2]; }
// Kept as configured: wrapped (hue) ranges, and a class with a verifier, whose range is the one
// its verifier was trained on (a learned range would feed it candidates it never saw).
bool notLearned(const ColorClass& c) { return wrapped(c) || !c.verifier_file.empty(); }

}  // namespace

std::vector<cv::Point2d> regionFromLines(const std::vector<const DetectedLine*>& lines) {
  if (lines.size() < 2) return {};
  std::vector<cv::Point2f> points;
  for (const DetectedLine* l : lines) {
    points.emplace_back(static_cast<float>(l->x1), static_cast<float>(l->y1));
    points.emplace_back(static_cast<float>(l->x2), static_cast<float>(l->y2));
  }
  // Corners where lines meet close the region where the segments fall short of them.
  for (size_t i = 0; i < lines.size(); ++i) {
    for (size_t j = i + 1; j < lines.size(); ++j) {
      cv::Point2d p;
      if (meetNear(*lines[i], *lines[j], 10.0, &p)) points.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
    }
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull);
  if (hull.size() < 3) return {};
  return std::vector<cv::Point2d>(hull.begin(), hull.end());
}

bool colorStats(const std::vector<Channels>& pixels, ColorStats* s, double outlier_distance,
                uint32_t large_object_px, double small_object_margin) {
  return weightedColorStats(pixels, nullptr, s, outlier_distance, large_object_px, small_object_margin);
}

bool weightedColorStats(const std::vector<Channels>& pixels, const std::vector<double>* weights, ColorStats* s,
                        double outlier_distance, uint32_t large_object_px, double small_object_margin) {
  if (pixels.empty()) return false;
  auto weight = [weights](size_t i) { return weights ? (*weights)[i] : 1.0; };
  double mean[3] = {0, 0, 0}, total = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) mean[ch] += weight(i) * pixels[i][ch];
    total += weight(i);
  }
  for (double& m : mean) m /= total;
  // Outliers (near edges, not the object's colour): more than outlier_distance from the mean.
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, kept_weight = 0;
  uint32_t kept = 0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Channels& p = pixels[i];
    bool inlier = true;
    for (int ch = 0; ch < 3; ++ch) inlier = inlier && std::fabs(p[ch] - mean[ch]) <= outlier_distance;
    if (!inlier) continue;
    ++kept;
    kept_weight += weight(i);
    for (int ch = 0; ch < 3; ++ch) {
      sum[ch] += weight(i) * p[ch];
      sum2[ch] += weight(i) * p[ch] * p[ch];
    }
  }
  if (kept == 0 || !(kept_weight > 0)) return false;
  s->pixels = kept;
  for (int ch = 0; ch < 3; ++ch) {
    s->mean[ch] = sum[ch] / kept_weight;
    s->sigma[ch] = std::sqrt(std::max(0.0, sum2[ch] / kept_weight - s->mean[ch] * s->mean[ch]));
    // The sigma of a small object is not reliable: a fixed margin instead.
    const double margin = kept > large_object_px ? 3 * s->sigma[ch] : small_object_margin;
    s->lo[ch] = saturateToByte(static_cast<int>(std::floor(s->mean[ch] - margin)));
    s->hi[ch] = saturateToByte(static_cast<int>(std::ceil(s->mean[ch] + margin)));
  }
  return true;
}

std::vector<std::vector<int>> colorModes(const std::vector<Channels>& pixels, double radius, size_t min_size,
                                         int max_modes) {
  std::vector<std::vector<int>> modes;
  std::vector<int> alive(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) alive[i] = static_cast<int>(i);
  auto within = [&](const Channels& p, const double* mean) {
    return std::fabs(p[0] - mean[0]) <= radius && std::fabs(p[1] - mean[1]) <= radius && std::fabs(p[2] - mean[2]) <= radius;
  };
  std::vector<int> histogram(16 * 16 * 16);
  for (int m = 0; m < max_modes && alive.size() >= min_size; ++m) {
    // The seed: the centre of the densest 16-level colour bin.
    std::fill(histogram.begin(), histogram.end(), 0);
    for (int i : alive) ++histogram[(pixels[i][0] >> 4) * 256 + (pixels[i][1] >> 4) * 16 + (pixels[i][2] >> 4)];
    const int bin = static_cast<int>(std::max_element(histogram.begin(), histogram.end()) - histogram.begin());
    double mean[3] = {(bin / 256) * 16 + 8.0, ((bin / 16) % 16) * 16 + 8.0, (bin % 16) * 16 + 8.0};
    std::vector<int> members;
    for (int iteration = 0; iteration < 5; ++iteration) {
      members.clear();
      double sum[3] = {0, 0, 0};
      for (int i : alive) {
        if (!within(pixels[i], mean)) continue;
        members.push_back(i);
        for (int ch = 0; ch < 3; ++ch) sum[ch] += pixels[i][ch];
      }
      if (members.empty()) break;
      for (int ch = 0; ch < 3; ++ch) mean[ch] = sum[ch] / members.size();
    }
    if (members.empty()) break;
    std::vector<int> rest;
    std::vector<char> taken(pixels.size(), 0);
    for (int i : members) taken[i] = 1;
    for (int i : alive) {
      if (!taken[i]) rest.push_back(i);
    }
    alive.swap(rest);
    if (members.size() >= min_size) modes.push_back(std::move(members));
  }
  return modes;
}

std::string validateLearningOptions(const LearningOptions& o) {
  std::string problem;
  // Every parameter within the limits landmark_params.def gives it.
#define RLE_LEARNING_PARAM(key, member, type, default_value, min, max, description) \
  if (problem.empty()) problem = outOfRange(#key, o.member, min, max);
#include "rle_vision/params/landmark_params.def"
  return problem;
}

ColorLearner::ColorLearner(std::vector<ColorClass> configured, const LearningOptions& options)
    : configured_(std::move(configured)), classes_(configured_), options_(options) {
  for (const ColorClass& c : configured_) {
    ClassState s;
    for (int ch = 0; ch < 3; ++ch) {
      s.lo[ch] = c.min[ch];
      s.hi[ch] = c.max[ch];
    }
    state_.push_back(s);
  }
}

int ColorLearner::resume(const std::vector<ColorClass>& learned, double stamp_s) {
  int resumed = 0;
  for (size_t k = 0; k < configured_.size(); ++k) {
    for (const ColorClass& c : learned) {
      if (c.name != configured_[k].name || c.space != configured_[k].space || c.source != "learned") continue;
      for (int ch = 0; ch < 3; ++ch) {
        state_[k].lo[ch] = classes_[k].min[ch] = c.min[ch];
        state_[k].hi[ch] = classes_[k].max[ch] = c.max[ch];
      }
      classes_[k].source = "learned";
      state_[k].last_measured_s = stamp_s;
      ++resumed;
      break;
    }
  }
  if (resumed > 0) blob_table_.reset();  // blobs are segmented with the ranges the tracker uses
  return resumed;
}

const ColorStats* ColorLearner::groundStats(ColorSpace space) const {
  return have_ground_[static_cast<int>(space)] ? &ground_[static_cast<int>(space)] : nullptr;
}

const ColorStats* ColorLearner::skyStats(ColorSpace space) const {
  return have_sky_[static_cast<int>(space)] ? &sky_[static_cast<int>(space)] : nullptr;
}

void ColorLearner::measureBackground(const cv::Mat& bgr, const HorizonEstimate& horizon,
                                     const std::vector<cv::Rect>& objects, const Spaces& spaces) {
  // A sparse grid of pixels away from every edge object: below the horizon (ground) and
  // above it (sky); without a horizon, everything is ground.
  std::vector<cv::Point> ground, sky;
  constexpr int kStep = 4;
  for (int y = kStep / 2; y < bgr.rows; y += kStep) {
    for (int x = kStep / 2; x < bgr.cols; x += kStep) {
      const cv::Point p(x, y);
      if (std::any_of(objects.begin(), objects.end(), [&](const cv::Rect& r) { return r.contains(p); })) continue;
      const double d = horizon.found ? signedDistance(horizon.line, x, y) : 1e9;
      if (d > 8) {
        ground.push_back(p);
      } else if (d < -8) {
        sky.push_back(p);
      }
    }
  }
  for (int s = 0; s < kNumColorSpaces; ++s) {
    have_ground_[s] = have_sky_[s] = false;
    if (!spaces.used[s]) continue;
    const ColorSpace space = static_cast<ColorSpace>(s);
    auto measure = [&](const std::vector<cv::Point>& points, ColorStats* out) {
      if (points.size() < 50) return false;
      // The samples as one row, converted at once.
      cv::Mat row(1, static_cast<int>(points.size()), CV_8UC3);
      for (size_t i = 0; i < points.size(); ++i) row.at<cv::Vec3b>(0, static_cast<int>(i)) = bgr.at<cv::Vec3b>(points[i]);
      const cv::Mat converted = convertBgrImage(row, space);
      std::vector<Channels> pixels(points.size());
      for (size_t i = 0; i < points.size(); ++i) {
        const cv::Vec3b v = converted.at<cv::Vec3b>(0, static_cast<int>(i));
        pixels[i] = Channels{{v[0], v[1], v[2]}};
      }
      return colorStats(pixels, out, 40, 0, 0);
    };
    have_ground_[s] = measure(ground, &ground_[s]);
    have_sky_[s] = measure(sky, &sky_[s]);
  }
}

bool ColorLearner::publishable(int k, Channels* lo, Channels* hi) const {
  for (int ch = 0; ch < 3; ++ch) {
    (*lo)[ch] = saturateToByte(static_cast<int>(std::lround(state_[k].lo[ch])));
    (*hi)[ch] = saturateToByte(static_cast<int>(std::lround(state_[k].hi[ch])));
  }
  return *lo != configured_[k].min || *hi != configured_[k].max;
}

bool ColorLearner::isBackground(ColorSpace space, const ColorStats& stats) const {
  const ColorStats* g = groundStats(space);
  const ColorStats* sky = skyStats(space);
  return (g && overlaps(stats, *g)) || (sky && overlaps(stats, *sky));
}

void ColorLearner::reject(Measurement* m, Rejection why, int conflicting_class) const {
  m->rejection = why;
  m->conflicting_class = conflicting_class;
  switch (why) {
    case Rejection::kNone: m->rejected.clear(); break;
    case Rejection::kTooSmall: m->rejected = m->from_blob ? "no pixels near its class" : "too small"; break;
    case Rejection::kAboveHorizon: m->rejected = "at or above the horizon"; break;
    case Rejection::kMixedColours: m->rejected = "mixed colours (one channel spreads more than max_sigma)"; break;
    case Rejection::kBackground: m->rejected = "the ground's or the sky's colour"; break;
    case Rejection::kNotInRange: m->rejected = "its pixels lie mostly outside the nearest class's range"; break;
    case Rejection::kNoClass:
      m->rejected = m->from_blob ? "its colour left its class's match gate" : "matches no class";
      break;
    case Rejection::kOverlapsGround: m->rejected = "the range would overlap the ground's colour"; break;
    case Rejection::kOverlapsSky: m->rejected = "the range would overlap the sky's colour"; break;
    case Rejection::kOverlapsClass:
      m->rejected = "the range would overlap class '" + configured_[conflicting_class].name + "'";
      break;
    case Rejection::kTakesInBackground:
      m->rejected = "the range would take in more pixels away from its objects than on them";
      break;
  }
}

bool ColorLearner::takesInBackground(int k, const ColorStats& blended) {
  // The pixels of this frame the new range would add to the current one: an object that
  // changed colour adds its own (near where it was measured), a range creeping into the
  // background adds pixels elsewhere. Refused when most lie away from the measured objects.
  if (!frame_bgr_ || frame_bgr_->empty()) return false;
  const int s = static_cast<int>(configured_[k].space);
  if (frame_in_space_[s].empty()) frame_in_space_[s] = convertBgrImage(*frame_bgr_, configured_[k].space);
  const cv::Mat& image = frame_in_space_[s];
  const ColorStats now = byteRange(state_[k].lo, state_[k].hi);
  cv::Mat near_objects = cv::Mat::zeros(image.size(), CV_8UC1);
  for (const cv::Rect& box : measured_boxes_[k]) near_objects(box & cv::Rect(0, 0, image.cols, image.rows)).setTo(1);
  size_t added_near = 0, added_away = 0;
  for (int y = 0; y < image.rows; ++y) {
    const cv::Vec3b* p = image.ptr<cv::Vec3b>(y);
    const uint8_t* near = near_objects.ptr<uint8_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      if (!holds(blended, p[x]) || holds(now, p[x])) continue;
      (near[x] ? added_near : added_away) += 1;
    }
  }
  return added_away > added_near;
}

ColorLearner::Rejection ColorLearner::apply(int k, const ColorStats& measured, double stamp_s, int* conflicting_class) {
  const ColorSpace space = configured_[k].space;
  ClassState next = state_[k];
  for (int ch = 0; ch < 3; ++ch) {
    next.lo[ch] += options_.blend * (measured.lo[ch] - next.lo[ch]);
    next.hi[ch] += options_.blend * (measured.hi[ch] - next.hi[ch]);
  }
  // Never let a class grow over the ground or the sky as measured now.
  const ColorStats blended = byteRange(next.lo, next.hi);
  if (const ColorStats* g = groundStats(space)) {
    if (overlaps(blended, *g)) return Rejection::kOverlapsGround;
  }
  if (const ColorStats* sky = skyStats(space)) {
    if (overlaps(blended, *sky)) return Rejection::kOverlapsSky;
  }
  // Nor over another class of the same space: two classes would claim the same pixels.
  for (size_t j = 0; j < configured_.size(); ++j) {
    if (static_cast<int>(j) == k || configured_[j].space != space || wrapped(configured_[j])) continue;
    if (overlaps(blended, byteRange(state_[j].lo, state_[j].hi))) {
      *conflicting_class = static_cast<int>(j);
      return Rejection::kOverlapsClass;
    }
  }
  // Nor over whatever else the frame holds (without a horizon there is no sky to compare).
  if (takesInBackground(k, blended)) return Rejection::kTakesInBackground;
  next.last_measured_s = stamp_s;
  state_[k] = next;
  return Rejection::kNone;
}

bool ColorLearner::driftBack(double stamp_s) {
  bool moved = false;
  for (size_t k = 0; k < configured_.size(); ++k) {
    ClassState& s = state_[k];
    if (s.last_measured_s < 0 || stamp_s - s.last_measured_s < options_.stale_after_s) continue;
    for (int ch = 0; ch < 3; ++ch) {
      s.lo[ch] += options_.blend * (configured_[k].min[ch] - s.lo[ch]);
      s.hi[ch] += options_.blend * (configured_[k].max[ch] - s.hi[ch]);
    }
    moved = true;
  }
  return moved;
}

ColorLearner::Spaces ColorLearner::usedSpaces() const {
  Spaces spaces;
  for (const ColorClass& c : configured_) spaces.used[static_cast<int>(c.space)] = true;
  spaces.used[static_cast<int>(ColorSpace::YUV)] = spaces.used[static_cast<int>(ColorSpace::YUV)] || options_.create_classes;
  return spaces;
}

bool ColorLearner::update(const cv::Mat& bgr, const LandmarkResult& landmarks, const EdgeObjectFinder& objects,
                          double stamp_s) {
  measurements_.clear();
  if (bgr.empty() || bgr.type() != CV_8UC3) return false;
  frame_bgr_ = &bgr;
  for (cv::Mat& converted : frame_in_space_) converted.release();
  measured_boxes_.assign(configured_.size(), {});
  const cv::Rect image(0, 0, bgr.cols, bgr.rows);
  // The background away from every edge object.
  std::vector<cv::Rect> object_boxes;
  for (const EdgeObject& o : objects.objects()) {
    object_boxes.push_back(cv::Rect(o.left - 3, o.top - 3, o.right - o.left + 7, o.bottom - o.top + 7) & image);
  }
  const Spaces spaces = usedSpaces();
  measureBackground(bgr, landmarks.horizon, object_boxes, spaces);
  // Regions: the lines of each edge object.
  std::map<int, std::vector<const DetectedLine*>> by_object;
  for (const DetectedLine& l : landmarks.lines) by_object[l.object].push_back(&l);
  std::vector<std::vector<ColorStats>> matched(configured_.size());
  for (const auto& entry : by_object) measureRegion(bgr, entry.second, landmarks.horizon, spaces, &matched);
  if (options_.from_blobs) measureBlobs(bgr, landmarks.horizon, &matched);
  applyMatched(matched, stamp_s);
  frame_bgr_ = nullptr;
  driftBack(stamp_s);
  if (options_.create_classes) createClasses(stamp_s);
  return updateClassSet();
}

bool ColorLearner::regionPixels(const cv::Mat& bgr, const std::vector<cv::Point2d>& region,
                                RegionPixels* pixels) const {
  std::vector<cv::Point> polygon;
  for (const cv::Point2d& p : region) polygon.emplace_back(cvRound(p.x), cvRound(p.y));
  // Padded so the erosion also bites at the region's bounding box (outside a Mat, erode
  // sees set pixels).
  const int pad = static_cast<int>(std::ceil(options_.shrink_px)) + 1;
  const cv::Rect bounds = cv::boundingRect(polygon);
  const cv::Rect roi = cv::Rect(bounds.x - pad, bounds.y - pad, bounds.width + 2 * pad, bounds.height + 2 * pad) &
                       cv::Rect(0, 0, bgr.cols, bgr.rows);
  if (roi.area() == 0) return false;
  cv::Mat mask = cv::Mat::zeros(roi.size(), CV_8UC1);
  for (cv::Point& p : polygon) p -= roi.tl();
  cv::fillConvexPoly(mask, polygon, cv::Scalar(255));
  if (options_.shrink_px > 0) {
    const int k = 2 * static_cast<int>(std::ceil(options_.shrink_px)) + 1;
    cv::erode(mask, mask, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  }
  for (int y = 0; y < roi.height; ++y) {
    const uint8_t* row = mask.ptr<uint8_t>(y);
    const cv::Vec3b* p = bgr.ptr<cv::Vec3b>(roi.y + y) + roi.x;
    for (int x = 0; x < roi.width; ++x) {
      if (!row[x]) continue;
      pixels->positions.emplace_back(roi.x + x, roi.y + y);
      pixels->yuv.push_back(yuvFromRgb(p[x][2], p[x][1], p[x][0]));
    }
  }
  return true;
}

void ColorLearner::measureRegion(const cv::Mat& bgr, const std::vector<const DetectedLine*>& lines,
                                 const HorizonEstimate& horizon, const Spaces& spaces,
                                 std::vector<std::vector<ColorStats>>* matched) {
  Measurement m;
  m.region = regionFromLines(lines);
  if (m.region.empty()) return;
  RegionPixels pixels;
  if (!regionPixels(bgr, m.region, &pixels)) return;
  if (static_cast<uint32_t>(pixels.positions.size()) < options_.min_region_px) {
    reject(&m, Rejection::kTooSmall);
    measurements_.push_back(m);
    return;
  }
  // The region may hold several objects (boxes touching in the image make one edge object):
  // each colour mode in it is measured on its own.
  for (const std::vector<int>& mode : colorModes(pixels.yuv, options_.mode_radius, options_.min_region_px)) {
    Measurement mm = m;
    measureMode(bgr, pixels, mode, horizon, spaces, &mm);
    if (mm.matched_class >= 0) {
      (*matched)[mm.matched_class].push_back(mm.stats[static_cast<int>(configured_[mm.matched_class].space)]);
      const int pad = static_cast<int>(std::ceil(options_.shrink_px)) + 1;  // the eroded rim
      const cv::Rect& b = mm.pixels_box;
      measured_boxes_[mm.matched_class].push_back(cv::Rect(b.x - pad, b.y - pad, b.width + 2 * pad, b.height + 2 * pad));
    }
    measurements_.push_back(mm);
  }
}

void ColorLearner::measureMode(const cv::Mat& bgr, const RegionPixels& pixels, const std::vector<int>& mode,
                               const HorizonEstimate& horizon, const Spaces& spaces, Measurement* m) {
  std::vector<cv::Point> where;
  for (int i : mode) where.push_back(pixels.positions[i]);
  m->pixels_box = cv::boundingRect(where);
  if (horizon.found && std::any_of(where.begin(), where.end(), [&](const cv::Point& p) {
        return signedDistance(horizon.line, p.x, p.y) < options_.horizon_margin_px;
      })) {
    return reject(m, Rejection::kAboveHorizon);
  }
  bool consistent = true;
  std::vector<Channels> colours_in_space[kNumColorSpaces];
  for (int s = 0; s < kNumColorSpaces; ++s) {
    if (!spaces.used[s]) continue;
    std::vector<Channels>& colours = colours_in_space[s];
    if (s == static_cast<int>(ColorSpace::YUV)) {
      for (int i : mode) colours.push_back(pixels.yuv[i]);
    } else {
      cv::Mat row(1, static_cast<int>(where.size()), CV_8UC3);
      for (size_t i = 0; i < where.size(); ++i) row.at<cv::Vec3b>(0, static_cast<int>(i)) = bgr.at<cv::Vec3b>(where[i]);
      const cv::Mat converted = convertBgrImage(row, static_cast<ColorSpace>(s));
      for (size_t i = 0; i < where.size(); ++i) {
        const cv::Vec3b v = converted.at<cv::Vec3b>(0, static_cast<int>(i));
        colours.push_back(Channels{{v[0], v[1], v[2]}});
      }
    }
    colorStats(colours, &m->stats[s]);
    for (int ch = 0; ch < 3; ++ch) consistent = consistent && m->stats[s].sigma[ch] <= options_.max_sigma;
  }
  if (!consistent) return reject(m, Rejection::kMixedColours);
  const int k = nearestClass(*m);
  // The class must already hold most of the mode: learning follows an object the tracker
  // sees as this class while its colour drifts; a colour beside the class (a white line next
  // to a cream ball's range) would otherwise pull the range over itself, step by step.
  if (k < 0) return reject(m, Rejection::kNoClass);
  if (!mostlyInRange(k, colours_in_space[static_cast<int>(configured_[k].space)])) {
    return reject(m, Rejection::kNotInRange);
  }
  // A mode of the ground's or the sky's colour is background between boxes, not an object.
  if (isBackground(configured_[k].space, m->stats[static_cast<int>(configured_[k].space)])) {
    return reject(m, Rejection::kBackground);
  }
  m->matched_class = k;
}

double ColorLearner::distanceToClass(int k, const ColorStats& measured) const {
  // From the centre of the class's current range to the measured mean.
  double d2 = 0;
  for (int ch = 0; ch < 3; ++ch) {
    const double centre = 0.5 * (state_[k].lo[ch] + state_[k].hi[ch]);
    d2 += (measured.mean[ch] - centre) * (measured.mean[ch] - centre);
  }
  return std::sqrt(d2);
}

bool ColorLearner::mostlyInRange(int k, const std::vector<Channels>& colours) const {
  size_t in = 0;
  for (const Channels& p : colours) {
    bool inside = true;
    for (int ch = 0; ch < 3; ++ch) inside = inside && p[ch] >= state_[k].lo[ch] && p[ch] <= state_[k].hi[ch];
    in += inside;
  }
  return 2 * in > colours.size();
}

int ColorLearner::nearestClass(const Measurement& m) const {
  // The nearest class (centre of its current range) within the gate.
  double best = options_.match_gate;
  int nearest = -1;
  for (size_t k = 0; k < configured_.size(); ++k) {
    if (notLearned(configured_[k])) continue;
    const double d = distanceToClass(static_cast<int>(k), m.stats[static_cast<int>(configured_[k].space)]);
    if (d <= best) {
      best = d;
      nearest = static_cast<int>(k);
    }
  }
  return nearest;
}

void ColorLearner::applyMatched(const std::vector<std::vector<ColorStats>>& matched, double stamp_s) {
  // One update per class: the union of this frame's measurements of it, blended in.
  for (size_t k = 0; k < configured_.size(); ++k) {
    if (matched[k].empty()) continue;
    ColorStats all = matched[k][0];
    for (const ColorStats& st : matched[k]) {
      for (int ch = 0; ch < 3; ++ch) {
        all.lo[ch] = std::min(all.lo[ch], st.lo[ch]);
        all.hi[ch] = std::max(all.hi[ch], st.hi[ch]);
      }
    }
    int conflicting = -1;
    const Rejection rejection = apply(static_cast<int>(k), all, stamp_s, &conflicting);
    if (rejection == Rejection::kNone) continue;
    for (Measurement& m : measurements_) {
      if (m.matched_class == static_cast<int>(k)) reject(&m, rejection, conflicting);
    }
  }
}

void ColorLearner::createClasses(double stamp_s) {
  // New classes from persistent unmatched regions.
  const int yuv = static_cast<int>(ColorSpace::YUV);
  for (const Measurement& m : measurements_) {
    // A blob that left its class's gate is that class drifting, not a new colour.
    if (m.from_blob || m.rejection != Rejection::kNoClass || m.stats[yuv].pixels < options_.min_new_class_px) continue;
    const ColorStats& st = m.stats[yuv];
    if (isBackground(ColorSpace::YUV, st)) continue;
    Candidate* same = nullptr;
    for (Candidate& c : candidates_) {
      double d2 = 0;
      for (int ch = 0; ch < 3; ++ch) d2 += (c.mean[ch] - st.mean[ch]) * (c.mean[ch] - st.mean[ch]);
      if (std::sqrt(d2) <= options_.match_gate) same = &c;
    }
    if (!same) {
      candidates_.push_back(Candidate{{st.mean[0], st.mean[1], st.mean[2]}, st, 0, stamp_s});
      same = &candidates_.back();
    }
    ++same->frames;
    same->last_seen_s = stamp_s;
    same->stats = st;
    for (int ch = 0; ch < 3; ++ch) same->mean[ch] = st.mean[ch];
  }
  candidates_.erase(std::remove_if(candidates_.begin(), candidates_.end(),
                                   [&](const Candidate& c) { return stamp_s - c.last_seen_s > 2.0; }),
                    candidates_.end());
  for (auto it = candidates_.begin(); it != candidates_.end();) {
    if (it->frames < options_.persist_frames || configured_.size() >= static_cast<size_t>(kMaxColorClasses)) {
      ++it;
      continue;
    }
    addClass(*it, stamp_s);
    it = candidates_.erase(it);
  }
}

void ColorLearner::addClass(const Candidate& candidate, double stamp_s) {
  ColorClass c;
  c.name = "learned_" + std::to_string(++created_);
  c.space = ColorSpace::YUV;
  c.min = candidate.stats.lo;
  c.max = candidate.stats.hi;
  cv::Mat yuv_pixel(1, 1, CV_8UC3, cv::Scalar(candidate.mean[0], candidate.mean[1], candidate.mean[2])), rgb;
  cv::cvtColor(yuv_pixel, rgb, cv::COLOR_YUV2RGB);
  c.display_rgb = Channels{{rgb.at<cv::Vec3b>(0, 0)[0], rgb.at<cv::Vec3b>(0, 0)[1], rgb.at<cv::Vec3b>(0, 0)[2]}};
  c.min_area_px = options_.min_new_class_px / 4;
  c.source = "learned";
  configured_.push_back(c);
  ClassState s;
  for (int ch = 0; ch < 3; ++ch) {
    s.lo[ch] = c.min[ch];
    s.hi[ch] = c.max[ch];
  }
  s.last_measured_s = stamp_s;
  state_.push_back(s);
}

bool ColorLearner::updateClassSet() {
  // The set to publish; changed when any range moved by a whole step.
  std::vector<ColorClass> next = configured_;
  for (size_t k = 0; k < configured_.size(); ++k) {
    Channels lo, hi;
    if (publishable(static_cast<int>(k), &lo, &hi)) {
      next[k].min = lo;
      next[k].max = hi;
      next[k].source = "learned";
    }
  }
  bool changed = next.size() != classes_.size();
  for (size_t k = 0; k < next.size() && !changed; ++k) {
    changed = next[k].min != classes_[k].min || next[k].max != classes_[k].max || next[k].source != classes_[k].source;
  }
  classes_ = std::move(next);
  if (changed) blob_table_.reset();
  return changed;
}

void ColorLearner::measureBlobs(const cv::Mat& bgr, const HorizonEstimate& horizon,
                                std::vector<std::vector<ColorStats>>* matched) {
  // The blobs the tracker sees with the current classes (it gets them on color_ranges).
  if (!blob_table_) blob_table_ = std::make_unique<ColorTable>(classes_);
  blob_segmenter_.segment(bgr, PixelFormat::BGR8, *blob_table_, &blob_regions_);
  // One measurement per class: its blobs' pixels pooled. Not the union of each blob's range:
  // a small blob's range is its mean +- small_object_margin, which reaches past the class's
  // range, so a union (and the next frame's blobs in the wider range) would only ever widen it.
  std::vector<std::vector<Channels>> pooled(configured_.size());
  std::vector<std::vector<cv::Rect>> blob_boxes(configured_.size());  // with the ring
  std::vector<Channels> pixels;
  const size_t first = measurements_.size();
  const int ring = options_.blob_ring_px;
  for (const Region& region : blob_regions_) {
    const int k = region.label - 1;
    if (k >= static_cast<int>(configured_.size()) || notLearned(configured_[k]) || region.area < options_.blob_min_px) {
      continue;
    }
    Measurement m;
    m.pixels_box = cv::Rect(region.left, region.top, region.right - region.left + 1, region.bottom - region.top + 1);
    m.region = {cv::Point2d(region.left, region.top), cv::Point2d(region.right, region.top),
                cv::Point2d(region.right, region.bottom), cv::Point2d(region.left, region.bottom)};
    pixels.clear();
    measureBlob(bgr, region, horizon, &m, &pixels);
    if (m.matched_class >= 0) {
      pooled[k].insert(pooled[k].end(), pixels.begin(), pixels.end());
      const cv::Rect& b = m.pixels_box;
      blob_boxes[k].push_back(cv::Rect(b.x - ring, b.y - ring, b.width + 2 * ring, b.height + 2 * ring));
    }
    measurements_.push_back(m);
  }
  for (size_t k = 0; k < pooled.size(); ++k) {
    if (pooled[k].empty()) continue;
    ColorStats all;
    bool consistent = colorStats(pooled[k], &all);
    for (int ch = 0; ch < 3; ++ch) consistent = consistent && all.sigma[ch] <= options_.max_sigma;
    if (consistent) {
      // The blobs of one frame are the objects seen now (one close ball, say), mixed with
      // their rims: not the spread the class must hold (the far ball of the next frame, and
      // not the field next to it). They tell where the class's colour is now; the configured
      // range, calibrated on examples, keeps its width about their mean.
      for (int ch = 0; ch < 3; ++ch) {
        const int width = configured_[k].max[ch] - configured_[k].min[ch];
        const long lo = std::min<long>(255 - width, std::max<long>(0, std::lround(all.mean[ch] - width / 2.0)));
        all.lo[ch] = static_cast<uint8_t>(lo);
        all.hi[ch] = static_cast<uint8_t>(lo + width);
      }
      (*matched)[k].push_back(all);
      measured_boxes_[k].insert(measured_boxes_[k].end(), blob_boxes[k].begin(), blob_boxes[k].end());
      continue;
    }
    // Blobs of different colours together: none teaches the class.
    for (size_t i = first; i < measurements_.size(); ++i) {
      if (measurements_[i].matched_class == static_cast<int>(k)) {
        measurements_[i].matched_class = -1;
        reject(&measurements_[i], Rejection::kMixedColours);
      }
    }
  }
}

void ColorLearner::measureBlob(const cv::Mat& bgr, const Region& region, const HorizonEstimate& horizon,
                               Measurement* m, std::vector<Channels>* pixels) {
  const int k = region.label - 1;
  m->from_blob = true;
  // The whole measured box, ring included, must lie below the horizon.
  const int top = region.top - options_.blob_ring_px, left = region.left - options_.blob_ring_px,
            right = region.right + options_.blob_ring_px;
  if (horizon.found && std::min(signedDistance(horizon.line, left, top), signedDistance(horizon.line, right, top)) <
                           options_.horizon_margin_px) {
    return reject(m, Rejection::kAboveHorizon);
  }
  blobPixels(bgr, region, k, pixels);
  ColorStats& stats = m->stats[static_cast<int>(configured_[k].space)];
  if (!colorStats(*pixels, &stats)) return reject(m, Rejection::kTooSmall);
  for (int ch = 0; ch < 3; ++ch) {
    if (stats.sigma[ch] > options_.max_sigma) return reject(m, Rejection::kMixedColours);
  }
  // Still its own class's colour (a blob is in range; with the ring it may have moved).
  if (distanceToClass(k, stats) > options_.match_gate) return reject(m, Rejection::kNoClass);
  if (isBackground(configured_[k].space, stats)) return reject(m, Rejection::kBackground);
  m->matched_class = k;
}

void ColorLearner::blobPixels(const cv::Mat& bgr, const Region& region, int k, std::vector<Channels>* pixels) const {
  // The object's pixels: in the blob's box and a ring of blob_ring_px around it, those whose
  // colour lies in the class's range or within blob_ring_margin of it. Not only the blob's
  // own pixels: those are cut at the range, so their spread would only ever shrink it, and an
  // object whose colour drifts out of the range would be lost instead of followed.
  const int ring = options_.blob_ring_px;
  const cv::Rect box = cv::Rect(region.left - ring, region.top - ring, region.right - region.left + 1 + 2 * ring,
                                region.bottom - region.top + 1 + 2 * ring) &
                       cv::Rect(0, 0, bgr.cols, bgr.rows);
  const cv::Mat colours = convertBgrImage(bgr(box), configured_[k].space);
  const double margin = options_.blob_ring_margin;
  for (int y = 0; y < box.height; ++y) {
    const cv::Vec3b* c = colours.ptr<cv::Vec3b>(y);
    for (int x = 0; x < box.width; ++x) {
      bool near_class = true;
      for (int ch = 0; ch < 3; ++ch) {
        near_class = near_class && c[x][ch] >= state_[k].lo[ch] - margin && c[x][ch] <= state_[k].hi[ch] + margin;
      }
      if (near_class) pixels->push_back(Channels{{c[x][0], c[x][1], c[x][2]}});
    }
  }
}

}  // namespace rle_vision
