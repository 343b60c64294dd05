#include "rle_vision/learning/color_calibration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "rle_vision/color/color_convert.h"

namespace rle_vision {
namespace {

struct ModeColor {
  double mean[3] = {0, 0, 0};
  double sigma[3] = {0, 0, 0};
};

ModeColor modeColor(const std::vector<Channels>& pixels, const std::vector<int>& members) {
  ModeColor m;
  double sum2[3] = {0, 0, 0};
  for (int i : members) {
    for (int ch = 0; ch < 3; ++ch) {
      m.mean[ch] += pixels[i][ch];
      sum2[ch] += static_cast<double>(pixels[i][ch]) * pixels[i][ch];
    }
  }
  const double n = static_cast<double>(members.size());
  for (int ch = 0; ch < 3; ++ch) {
    m.mean[ch] /= n;
    m.sigma[ch] = std::sqrt(std::max(0.0, sum2[ch] / n - m.mean[ch] * m.mean[ch]));
  }
  return m;
}

bool nearMode(const Channels& p, const ModeColor& mode, double radius) {
  for (int ch = 0; ch < 3; ++ch) {
    if (std::fabs(p[ch] - mode.mean[ch]) > std::max(radius, 2.5 * mode.sigma[ch])) return false;
  }
  return true;
}

// The box grown by the ring, clipped to the image.
cv::Rect grownBox(const cv::Rect& box, const cv::Size& size, double ring_fraction) {
  const int ring = std::max(2, static_cast<int>(ring_fraction * std::min(box.width, box.height)));
  const cv::Rect grown(box.x - ring, box.y - ring, box.width + 2 * ring, box.height + 2 * ring);
  return grown & cv::Rect(0, 0, size.width, size.height);
}

// The ring's colour modes: what surrounds the object.
std::vector<ModeColor> surroundings(const cv::Mat& image, const cv::Rect& box, const CalibrationOptions& o) {
  const cv::Rect grown = grownBox(box, image.size(), o.ring_fraction);
  std::vector<Channels> ring;
  for (int y = grown.y; y < grown.br().y; ++y) {
    const cv::Vec3b* row = image.ptr<cv::Vec3b>(y);
    for (int x = grown.x; x < grown.br().x; ++x) {
      if (!box.contains(cv::Point(x, y))) ring.push_back(Channels{{row[x][0], row[x][1], row[x][2]}});
    }
  }
  std::vector<ModeColor> modes;
  const size_t min_size = std::max<size_t>(5, ring.size() / 10);
  for (const std::vector<int>& members : colorModes(ring, o.background_radius, min_size)) {
    modes.push_back(modeColor(ring, members));
  }
  return modes;
}


// Each box's object pixels counts once, however large the object: a weight per pixel.
struct WeightedPixels {
  std::vector<Channels> pixels;
  std::vector<double> weights;
};

// The examples whose mean colour lies within outlier_distance (on every channel) of the medoid
// box's: the box whose colour is nearest all the others' (the paper's outlier rule, one level
// up: a box around the wrong thing or an object hidden behind another is dropped as a whole).
// The medoid itself always stays, so at least one example is used.
WeightedPixels agreeingExamples(const std::vector<std::vector<Channels>>& objects, double outlier_distance,
                                int* used) {
  std::vector<std::array<double, 3>> means;
  for (const auto& pixels : objects) {
    std::array<double, 3> m{{0, 0, 0}};
    for (const Channels& p : pixels) {
      for (int ch = 0; ch < 3; ++ch) m[ch] += p[ch];
    }
    for (double& v : m) v /= static_cast<double>(pixels.size());
    means.push_back(m);
  }
  auto distance = [&](size_t a, size_t b) {
    double d = 0;
    for (int ch = 0; ch < 3; ++ch) d = std::max(d, std::fabs(means[a][ch] - means[b][ch]));
    return d;
  };
  size_t medoid = 0;
  double best = -1;
  for (size_t i = 0; i < means.size(); ++i) {
    double total = 0;
    for (size_t j = 0; j < means.size(); ++j) total += std::min(distance(i, j), 2 * outlier_distance);
    if (best < 0 || total < best) best = total, medoid = i;
  }
  WeightedPixels out;
  *used = 0;
  for (size_t i = 0; i < objects.size(); ++i) {
    if (distance(i, medoid) > outlier_distance) continue;
    ++*used;
    out.pixels.insert(out.pixels.end(), objects[i].begin(), objects[i].end());
    out.weights.insert(out.weights.end(), objects[i].size(), 1.0 / static_cast<double>(objects[i].size()));
  }
  return out;
}

// The paper's statistics with every example counting once.
ColorStats weightedStats(const WeightedPixels& w, const CalibrationOptions& o) {
  ColorStats s;
  if (!weightedColorStats(w.pixels, &w.weights, &s, o.outlier_distance, o.large_object_px, o.small_object_margin)) {
    throw std::invalid_argument("the objects' pixels spread more than the outlier distance around their mean: "
                                "give boxes of one colour");
  }
  return s;
}

// A colour histogram on a 64-level lattice with 3-D prefix sums: the weight inside any box of
// colours in constant time.
class BoxCounter {
 public:
  static constexpr int kShift = 2, kLevels = 256 >> kShift, kSide = kLevels + 1;
  BoxCounter() : sums_(kSide * kSide * kSide, 0.0) {}
  void add(const Channels& p, double weight) {
    at(1 + (p[0] >> kShift), 1 + (p[1] >> kShift), 1 + (p[2] >> kShift)) += weight;
  }
  void integrate() {
    for (int a = 1; a < kSide; ++a)
      for (int b = 1; b < kSide; ++b)
        for (int c = 1; c < kSide; ++c)
          at(a, b, c) += at(a - 1, b, c) + at(a, b - 1, c) + at(a, b, c - 1) - at(a - 1, b - 1, c) -
                         at(a - 1, b, c - 1) - at(a, b - 1, c - 1) + at(a - 1, b - 1, c - 1);
  }
  // Lattice cells lo..hi inclusive per channel.
  double inside(const int* lo, const int* hi) const {
    const int a0 = lo[0], b0 = lo[1], c0 = lo[2], a1 = hi[0] + 1, b1 = hi[1] + 1, c1 = hi[2] + 1;
    return get(a1, b1, c1) - get(a0, b1, c1) - get(a1, b0, c1) - get(a1, b1, c0) + get(a0, b0, c1) +
           get(a0, b1, c0) + get(a1, b0, c0) - get(a0, b0, c0);
  }

 private:
  double& at(int a, int b, int c) { return sums_[(a * kSide + b) * kSide + c]; }
  double get(int a, int b, int c) const { return sums_[(a * kSide + b) * kSide + c]; }
  std::vector<double> sums_;
};

// Pixels of the images outside every (grown) box: colours the class must not take.
BoxCounter otherPixels(const std::vector<CalibrationExample>& examples, const std::vector<cv::Mat>& converted,
                       const CalibrationOptions& o) {
  BoxCounter counter;
  for (size_t i = 0; i < examples.size(); ++i) {
    cv::Mat outside(converted[i].size(), CV_8U, cv::Scalar(1));
    for (const cv::Rect& box : examples[i].boxes) outside(grownBox(box, outside.size(), o.ring_fraction)).setTo(0);
    for (int y = 0; y < outside.rows; ++y) {
      const cv::Vec3b* row = converted[i].ptr<cv::Vec3b>(y);
      const uint8_t* keep = outside.ptr<uint8_t>(y);
      for (int x = 0; x < outside.cols; ++x) {
        if (keep[x]) counter.add(Channels{{row[x][0], row[x][1], row[x][2]}}, 1.0);
      }
    }
  }
  counter.integrate();
  return counter;
}

struct Tightening {
  BoxCounter objects, others;
  double box_count = 0, mean_object_px = 0, images = 0;
  // F1 of "object pixels in, other pixels out", each box weighing the same; an image's other
  // pixels weigh against one mean object.
  double score(const int* lo, const int* hi, double* recall, double* others_per_image) const {
    *recall = objects.inside(lo, hi) / box_count;
    *others_per_image = others.inside(lo, hi) / images;
    const double true_px = *recall * mean_object_px;
    const double precision = true_px / std::max(1e-9, true_px + *others_per_image);
    return 2 * *recall * precision / std::max(1e-9, *recall + precision);
  }
};

// Coordinate ascent from the statistics' range: the one-level move of one bound that raises
// the score most, until none does. Bounds never moved keep their exact value.
void tighten(const Tightening& t, Channels* lo, Channels* hi, double* recall, double* others_per_image) {
  int bounds[6];
  for (int ch = 0; ch < 3; ++ch) {
    bounds[ch] = (*lo)[ch] >> BoxCounter::kShift;
    bounds[3 + ch] = (*hi)[ch] >> BoxCounter::kShift;
  }
  const int* l = bounds;
  const int* h = bounds + 3;
  bool moved[6] = {false, false, false, false, false, false};
  double best = t.score(l, h, recall, others_per_image);
  for (int step = 0; step < 4 * BoxCounter::kLevels; ++step) {
    int best_bound = -1, best_move = 0;
    for (int bound = 0; bound < 6; ++bound) {
      for (int move : {-1, 1}) {
        const int ch = bound % 3;
        bounds[bound] += move;
        double r, o;
        const bool valid = l[ch] >= 0 && h[ch] < BoxCounter::kLevels && l[ch] <= h[ch];
        const double s = valid ? t.score(l, h, &r, &o) : -1;
        bounds[bound] -= move;
        if (s > best + 1e-9) best = s, best_bound = bound, best_move = move;
      }
    }
    if (best_bound < 0) break;
    bounds[best_bound] += best_move;
    moved[best_bound] = true;
  }
  t.score(l, h, recall, others_per_image);
  for (int ch = 0; ch < 3; ++ch) {
    if (moved[ch]) (*lo)[ch] = static_cast<uint8_t>(l[ch] << BoxCounter::kShift);
    if (moved[3 + ch]) (*hi)[ch] = static_cast<uint8_t>((h[ch] << BoxCounter::kShift) + (1 << BoxCounter::kShift) - 1);
  }
}

Channels displayRgb(const ColorStats& s, ColorSpace space) {
  cv::Mat pixel(1, 1, CV_8UC3, cv::Scalar(s.mean[0], s.mean[1], s.mean[2]));
  cv::Mat bgr;
  if (space == ColorSpace::YUV) cv::cvtColor(pixel, bgr, cv::COLOR_YUV2BGR);
  else if (space == ColorSpace::HSV) cv::cvtColor(pixel, bgr, cv::COLOR_HSV2BGR);
  else cv::cvtColor(pixel, bgr, cv::COLOR_RGB2BGR);
  const cv::Vec3b v = bgr.at<cv::Vec3b>(0, 0);
  return Channels{{v[2], v[1], v[0]}};
}

}  // namespace

void checkCalibrationExample(const CalibrationExample& e) {
  if (e.bgr.empty()) throw std::invalid_argument(e.name + ": empty or unreadable image");
  if (e.bgr.type() != CV_8UC3) throw std::invalid_argument(e.name + ": the image must be 8-bit, 3 channels (BGR)");
  const cv::Rect image(0, 0, e.bgr.cols, e.bgr.rows);
  for (const cv::Rect& box : e.boxes) {
    std::ostringstream where;
    where << e.name << ": box " << box.x << "," << box.y << "," << box.br().x << "," << box.br().y;
    if (box.width <= 0 || box.height <= 0) throw std::invalid_argument(where.str() + " is empty");
    if ((box & image) != box) {
      where << " lies outside the " << e.bgr.cols << "x" << e.bgr.rows << " image";
      throw std::invalid_argument(where.str());
    }
  }
}

std::vector<Channels> objectPixelsInBox(const cv::Mat& image, const cv::Rect& box, const CalibrationOptions& o) {
  const std::vector<ModeColor> background = surroundings(image, box, o);
  // The object is round or boxy; the inscribed ellipse leaves out the corners of a round one.
  const double cx = box.x + (box.width - 1) / 2.0, cy = box.y + (box.height - 1) / 2.0;
  const double rx = box.width / 2.0, ry = box.height / 2.0;
  std::vector<Channels> candidates;
  std::vector<char> central;
  for (int y = box.y; y < box.br().y; ++y) {
    const cv::Vec3b* row = image.ptr<cv::Vec3b>(y);
    for (int x = box.x; x < box.br().x; ++x) {
      const double r2 = ((x - cx) / rx) * ((x - cx) / rx) + ((y - cy) / ry) * ((y - cy) / ry);
      const Channels p{{row[x][0], row[x][1], row[x][2]}};
      if (r2 > 1.0) continue;
      bool is_background = false;
      for (const ModeColor& m : background) is_background = is_background || nearMode(p, m, o.background_radius);
      if (is_background) continue;
      candidates.push_back(p);
      central.push_back(r2 <= 0.25);
    }
  }
  // Of what differs from the surroundings, the colour that fills the centre: not an
  // occluding robot at the side, nor a highlight.
  const std::vector<std::vector<int>> modes = colorModes(candidates, o.object_mode_radius, 1);
  const std::vector<int>* object = nullptr;
  size_t best_central = 0, best_size = 0;
  for (const std::vector<int>& members : modes) {
    size_t in_centre = 0;
    for (int i : members) in_centre += central[i];
    if (!object || in_centre > best_central || (in_centre == best_central && members.size() > best_size)) {
      object = &members, best_central = in_centre, best_size = members.size();
    }
  }
  std::vector<Channels> pixels;
  if (object) {
    for (int i : *object) pixels.push_back(candidates[i]);
  }
  return pixels;
}

CalibrationResult calibrateColorClass(const std::vector<CalibrationExample>& examples, const std::string& name,
                                      const CalibrationOptions& o) {
  std::vector<cv::Mat> converted;
  std::vector<std::vector<Channels>> objects;
  CalibrationResult result;
  for (const CalibrationExample& e : examples) {
    checkCalibrationExample(e);
    converted.push_back(convertBgrImage(e.bgr, o.space));
    for (const cv::Rect& box : e.boxes) {
      std::vector<Channels> pixels = objectPixelsInBox(converted.back(), box, o);
      if (pixels.empty()) ++result.boxes_dropped;
      else objects.push_back(std::move(pixels));
    }
  }
  if (objects.empty()) throw std::invalid_argument("no box holds object pixels: give boxes around the object");
  const WeightedPixels agreeing = agreeingExamples(objects, o.outlier_distance, &result.boxes_used);
  result.boxes_dropped += static_cast<int>(objects.size()) - result.boxes_used;
  result.stats = weightedStats(agreeing, o);
  ColorClass& c = result.color_class;
  c.name = name;
  c.space = o.space;
  c.min = result.stats.lo;
  c.max = result.stats.hi;
  c.display_rgb = displayRgb(result.stats, o.space);
  c.min_area_px = o.min_area_px;
  Tightening t;
  for (size_t i = 0; i < agreeing.pixels.size(); ++i) t.objects.add(agreeing.pixels[i], agreeing.weights[i]);
  t.objects.integrate();
  t.others = otherPixels(examples, converted, o);
  t.box_count = result.boxes_used;
  t.mean_object_px = static_cast<double>(agreeing.pixels.size()) / result.boxes_used;
  t.images = static_cast<double>(examples.size());
  if (o.exclude_background) {
    tighten(t, &c.min, &c.max, &result.object_recall, &result.other_pixels_per_image);
  } else {
    int l[3], h[3];
    for (int ch = 0; ch < 3; ++ch) l[ch] = c.min[ch] >> BoxCounter::kShift, h[ch] = c.max[ch] >> BoxCounter::kShift;
    t.score(l, h, &result.object_recall, &result.other_pixels_per_image);
  }
  return result;
}


}  // namespace rle_vision
