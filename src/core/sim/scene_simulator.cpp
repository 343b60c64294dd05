#include "rle_vision/sim/scene_simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "rle_vision/sim/sensor_noise.h"

namespace rle_vision {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kNearPlaneM = 0.02;
constexpr int kSubPixelBits = 8;  // fillConvexPoly's fixed-point vertex precision
constexpr int kTextureLattice = 256;  // the ground texture repeats every 256 blotches

// Sutherland-Hodgman clip of a convex polygon to the half-space inside(p) >= 0, where
// `inside` is affine in p.
template <typename Point, typename Inside>
std::vector<Point> clipPolygon(const std::vector<Point>& polygon, Inside inside) {
  std::vector<Point> out;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Point& a = polygon[i];
    const Point& b = polygon[(i + 1) % n];
    const double da = inside(a), db = inside(b);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// Light from above, behind the robot and a little to the left.
const Eigen::Vector3d kLightDirection = Eigen::Vector3d(-0.5, 0.3, 0.8).normalized();

double faceShade(const Eigen::Vector3d& normal) {
  return 0.75 + 0.25 * std::max(0.0, normal.dot(kLightDirection));
}

cv::Scalar litBgr(const Channels& rgb, double shade, double gain, const std::array<double, 3>& cast) {
  auto channel = [&](int c) {
    return std::min(255.0, std::max(0.0, std::round(rgb[c] * shade * gain * cast[c])));
  };
  return cv::Scalar(channel(2), channel(1), channel(0));
}

bool finite(double v) { return std::isfinite(v); }

// Largest channel difference between two BGR pixels.
double colourStep(const cv::Vec3b& a, const cv::Vec3b& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

// The visible stretches of the candidate segment (x1, y1) -> (x2, y2): sampled every pixel,
// a sample is visible when one side (2 px along the normal) shows `label` (or, for label < 0,
// when the two sides are sky and ground) and the colour step across is large enough.
void visibleStretches(const cv::Mat& clean, const cv::Mat& labels, double x1, double y1, double x2,
                      double y2, int label, int box, double min_contrast, std::vector<EdgeTruth>* out) {
  const double length = std::hypot(x2 - x1, y2 - y1);
  if (length < 1) return;
  const double ux = (x2 - x1) / length, uy = (y2 - y1) / length, nx = -uy, ny = ux;
  const cv::Rect inside(0, 0, clean.cols, clean.rows);
  const int steps = static_cast<int>(std::floor(length));
  int start = -1;
  double contrast = INFINITY;
  auto close = [&](int end) {
    if (start >= 0 && end - start >= 1) {
      out->push_back({x1 + start * ux, y1 + start * uy, x1 + end * ux, y1 + end * uy, box, contrast});
    }
    start = -1;
    contrast = INFINITY;
  };
  for (int s = 0; s <= steps; ++s) {
    const double px = x1 + s * ux, py = y1 + s * uy;
    const cv::Point a(cvRound(px + 2 * nx), cvRound(py + 2 * ny)), b(cvRound(px - 2 * nx), cvRound(py - 2 * ny));
    bool visible = inside.contains(a) && inside.contains(b);
    double step = 0;
    if (visible) {
      const int la = labels.at<uint8_t>(a), lb = labels.at<uint8_t>(b);
      visible = label >= 0 ? (la == label || lb == label)
                           : ((la == SceneSimulator::kSkyLabel && lb == SceneSimulator::kGroundLabel) ||
                              (lb == SceneSimulator::kSkyLabel && la == SceneSimulator::kGroundLabel));
      step = colourStep(clean.at<cv::Vec3b>(a), clean.at<cv::Vec3b>(b));
      visible = visible && step >= min_contrast;
    }
    if (visible) {
      if (start < 0) start = s;
      contrast = std::min(contrast, step);
    } else {
      close(s - 1);
    }
  }
  close(steps);
}

}  // namespace

std::string validateSceneConfig(const SceneConfig& c) {
  if (c.width <= 1 || c.height <= 1 || c.width > 8192 || c.height > 8192) {
    return "image size must be between 2x2 and 8192x8192, got " + std::to_string(c.width) + "x" +
           std::to_string(c.height);
  }
  if (!finite(c.hfov_deg) || c.hfov_deg <= 1 || c.hfov_deg >= 179) {
    return "hfov_deg must be in (1, 179)";
  }
  if (!finite(c.camera_height_m) || c.camera_height_m <= 0) return "camera height_m must be > 0";
  for (double v : {c.camera_pitch_deg, c.camera_roll_deg, c.camera_yaw_deg, c.gait_frequency_hz,
                   c.gait_roll_amplitude_deg, c.gait_pitch_amplitude_deg,
                   c.gait_yaw_amplitude_deg, c.gait_bob_amplitude_m, c.light_gain_start,
                   c.light_gain_end, c.light_drift_duration_s, c.noise_sigma, c.blur_sigma_px}) {
    if (!finite(v)) return "a camera, gait, lighting or noise value is not a finite number";
  }
  if (c.camera_height_m - std::fabs(c.gait_bob_amplitude_m) <= kNearPlaneM) {
    return "camera height_m minus gait bob_amplitude_m must stay above the ground";
  }
  if (c.light_gain_start < 0 || c.light_gain_end < 0) return "light gains must be >= 0";
  if (c.light_drift_duration_s < 0) return "light drift_duration_s must be >= 0";
  for (int i = 0; i < 3; ++i) {
    if (!finite(c.light_cast_start_rgb[i]) || !finite(c.light_cast_end_rgb[i]) ||
        c.light_cast_start_rgb[i] < 0 || c.light_cast_end_rgb[i] < 0) {
      return "light casts must be finite and >= 0";
    }
  }
  if (c.noise_sigma < 0 || c.noise_sigma > 1000) return "noise sigma must be in [0, 1000] levels";
  if (!finite(c.ground_texture_contrast) || c.ground_texture_contrast < 0 || c.ground_texture_contrast > 1) {
    return "ground_texture contrast must be in [0, 1]";
  }
  if (!finite(c.ground_texture_grain_m) || c.ground_texture_grain_m <= 0) return "ground_texture grain_m must be > 0";
  if (c.blur_sigma_px < 0 || c.blur_sigma_px > 20) return "blur_sigma_px must be in [0, 20]";
  if (c.has_field && !(c.field_x_min_m < c.field_x_max_m && c.field_y_min_m < c.field_y_max_m)) {
    return "field: x_min_m < x_max_m and y_min_m < y_max_m are needed";
  }
  if (c.boxes.size() > 255u - SceneSimulator::kFirstBoxLabel) return "too many boxes (at most 253)";
  for (const SceneBox& b : c.boxes) {
    for (double v : {b.x_m, b.y_m, b.depth_m, b.width_m, b.height_m, b.yaw_deg, b.vx_mps, b.vy_mps,
                     b.sway_x_m, b.sway_y_m, b.sway_period_s}) {
      if (!finite(v)) return "box '" + b.name + "' has a value that is not a finite number";
    }
    if (b.depth_m <= 0 || b.width_m <= 0 || b.height_m <= 0) {
      return "box '" + b.name + "' needs depth_m, width_m and height_m > 0";
    }
    if (b.sway_period_s < 0) return "box '" + b.name + "' has a negative sway period_s";
  }
  return "";
}

SceneSimulator::SceneSimulator(const SceneConfig& config) : config_(config) {
  const std::string problem = validateSceneConfig(config_);
  if (!problem.empty()) throw std::invalid_argument(problem);
  camera_ = PinholeCamera::fromHorizontalFov(config_.width, config_.height,
                                             config_.hfov_deg * kDegToRad);
  // The ground texture's lattice: one reproducible random value per blotch.
  cv::RNG rng(config_.seed * 0x2545F4914F6CDD1Dull + 1);
  texture_lattice_.resize(kTextureLattice * kTextureLattice);
  for (float& value : texture_lattice_) value = rng.uniform(-1.0f, 1.0f);
  if (config_.noise_sigma > 0) noise_table_ = roundedGaussianTable(config_.noise_sigma);
}

CameraPose SceneSimulator::poseAt(double t) const {
  const double phase = 2 * M_PI * config_.gait_frequency_hz * t;
  CameraPose pose;
  pose.roll = (config_.camera_roll_deg + config_.gait_roll_amplitude_deg * std::sin(phase)) * kDegToRad;
  pose.pitch =
      (config_.camera_pitch_deg + config_.gait_pitch_amplitude_deg * std::sin(2 * phase)) * kDegToRad;
  pose.yaw = (config_.camera_yaw_deg +
              config_.gait_yaw_amplitude_deg * std::sin(phase + M_PI / 2)) * kDegToRad;
  pose.height_m = config_.camera_height_m + config_.gait_bob_amplitude_m * std::sin(2 * phase);
  return pose;
}

double SceneSimulator::lightGainAt(double t) const {
  const double f = config_.light_drift_duration_s > 0
                       ? std::min(1.0, std::max(0.0, t / config_.light_drift_duration_s))
                       : 0.0;
  return config_.light_gain_start + f * (config_.light_gain_end - config_.light_gain_start);
}

Eigen::Vector2d SceneSimulator::boxPositionAt(const SceneBox& box, double t) const {
  Eigen::Vector2d p(box.x_m + box.vx_mps * t, box.y_m + box.vy_mps * t);
  if (box.sway_period_s > 0) {
    const double s = std::sin(2 * M_PI * t / box.sway_period_s);
    p += Eigen::Vector2d(box.sway_x_m, box.sway_y_m) * s;
  }
  return p;
}

namespace {

// What lights a frame: the gain and per-channel colour cast at its time.
struct Lighting {
  double gain = 1;
  std::array<double, 3> cast{{1, 1, 1}};
};

// A box face's outline as projected, for the straight-edge truth.
struct CandidateEdge {
  Eigen::Vector2d a, b;
  int box;
};

// Where the camera is and how it looks at the scene.
struct View {
  Eigen::Matrix3d optical_from_base;
  Eigen::Vector3d position;
};

struct Face {
  Eigen::Vector3d normal;
  std::vector<Eigen::Vector3d> corners;
};

// The five faces a box shows (the bottom never does), in the base frame.
std::vector<Face> boxFaces(const SceneBox& box, const Eigen::Vector2d& centre) {
  const Eigen::Matrix2d rot = Eigen::Rotation2Dd(box.yaw_deg * kDegToRad).toRotationMatrix();
  const Eigen::Vector2d ax = rot.col(0) * (0.5 * box.depth_m);
  const Eigen::Vector2d ay = rot.col(1) * (0.5 * box.width_m);
  auto corner = [&](double sx, double sy, double z) {
    const Eigen::Vector2d p = centre + sx * ax + sy * ay;
    return Eigen::Vector3d(p.x(), p.y(), z);
  };
  const double h = box.height_m;
  const Eigen::Vector3d nx(rot(0, 0), rot(1, 0), 0), ny(rot(0, 1), rot(1, 1), 0);
  return {
      {Eigen::Vector3d::UnitZ(), {corner(-1, -1, h), corner(1, -1, h), corner(1, 1, h), corner(-1, 1, h)}},
      {nx, {corner(1, -1, 0), corner(1, 1, 0), corner(1, 1, h), corner(1, -1, h)}},
      {-nx, {corner(-1, -1, 0), corner(-1, 1, 0), corner(-1, 1, h), corner(-1, -1, h)}},
      {ny, {corner(-1, 1, 0), corner(1, 1, 0), corner(1, 1, h), corner(-1, 1, h)}},
      {-ny, {corner(-1, -1, 0), corner(1, -1, 0), corner(1, -1, h), corner(-1, -1, h)}},
  };
}

// A face's outline in the image: clipped to the near plane and to a guard band around the
// image (which keeps fixed-point vertices far from overflow). Empty when it is not in view.
std::vector<Eigen::Vector2d> projectFace(const Face& face, const View& view, const PinholeCamera& camera, double guard) {
  std::vector<Eigen::Vector3d> in_camera;
  for (const auto& p : face.corners) in_camera.push_back(view.optical_from_base * (p - view.position));
  in_camera = clipPolygon(in_camera, [](const Eigen::Vector3d& p) { return p.z() - kNearPlaneM; });
  if (in_camera.size() < 3) return {};
  std::vector<Eigen::Vector2d> projected;
  for (const auto& p : in_camera) projected.push_back(camera.project(p));
  for (int axis = 0; axis < 2; ++axis) {
    projected = clipPolygon(projected, [&](const Eigen::Vector2d& p) { return p[axis] + guard; });
    projected = clipPolygon(projected, [&](const Eigen::Vector2d& p) { return guard - p[axis]; });
  }
  if (projected.size() < 3) return {};
  return projected;
}

// Ground truth of one box from the label image: its pixels, their pieces and what they touch.
void boxMaskTruth(const cv::Mat& labels, const std::vector<SceneBox>& boxes, size_t i, BoxTruth* truth) {
  // Within the bounding box (grown by one pixel to see neighbours): pieces of the mask, and
  // whether a same-class box's pixels touch it (8-neighbourhood).
  const cv::Rect roi = cv::Rect(truth->left - 1, truth->top - 1, truth->right - truth->left + 3,
                                truth->bottom - truth->top + 3) & cv::Rect(0, 0, labels.cols, labels.rows);
  const cv::Mat labels_roi = labels(roi);
  const cv::Mat mask = labels_roi == truth->label;
  cv::Mat components;
  truth->pieces = cv::connectedComponents(mask, components, 8, CV_32S) - 1;
  cv::Mat same_class = cv::Mat::zeros(roi.size(), CV_8UC1);
  for (size_t j = 0; j < boxes.size(); ++j) {
    if (j != i && boxes[j].color_class == boxes[i].color_class) {
      same_class |= labels_roi == static_cast<uint8_t>(SceneSimulator::kFirstBoxLabel + j);
    }
  }
  const cv::Mat other_box = (labels_roi >= SceneSimulator::kFirstBoxLabel) & (labels_roi != truth->label);
  cv::Mat grown;
  cv::dilate(mask, grown, cv::Mat());
  truth->touches_same_class = cv::countNonZero(grown & same_class) > 0;
  truth->touches_other_box = cv::countNonZero(grown & other_box) > 0;
}

constexpr float kMaxFootprintOverGrain = 1e4f;  // beyond, the texture's contrast is below 1e-4 of its own

// Smooth value noise in [-1, 1] at (x, y) (lattice units): the lattice's values interpolated
// with smoothstep weights.
inline float valueNoise(const float* lattice, float x, float y) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = static_cast<int>(fx) & (kTextureLattice - 1), iy = static_cast<int>(fy) & (kTextureLattice - 1);
  const int jx = (ix + 1) & (kTextureLattice - 1), jy = (iy + 1) & (kTextureLattice - 1);
  const float u = x - fx, v = y - fy, su = u * u * (3 - 2 * u), sv = v * v * (3 - 2 * v);
  const float* r0 = lattice + iy * kTextureLattice;
  const float* r1 = lattice + jy * kTextureLattice;
  const float top = r0[ix] + su * (r0[jx] - r0[ix]), bottom = r1[ix] + su * (r1[jx] - r1[ix]);
  return top + sv * (bottom - top);
}

// The ground's texture on the ground pixels of `frame` (labels still sky and ground only).
void textureGround(const SceneConfig& config, const PinholeCamera& camera, const View& view, const float* lattice,
                   SimFrame* frame) {
  const Eigen::Matrix3d base_from_optical = view.optical_from_base.transpose();
  const float inv_grain = static_cast<float>(1.0 / config.ground_texture_grain_m);
  const float grain_fx = static_cast<float>(config.ground_texture_grain_m * camera.fx);
  const float height = static_cast<float>(view.position.z()), px = static_cast<float>(view.position.x());
  const float py = static_cast<float>(view.position.y()), contrast = static_cast<float>(config.ground_texture_contrast);
  const Eigen::Vector3f step = (base_from_optical * Eigen::Vector3d(1.0 / camera.fx, 0, 0)).cast<float>();
  for (int v = 0; v < frame->image.rows; ++v) {
    const uint8_t* label = frame->labels.ptr<uint8_t>(v);
    uint8_t* pixel = frame->image.ptr<uint8_t>(v);
    // The ray through (u, v) in the base frame is linear in u.
    const Eigen::Vector3f start = (base_from_optical * camera.ray(0, v)).cast<float>();
    for (int u = 0; u < frame->image.cols; ++u) {
      if (label[u] != SceneSimulator::kGroundLabel) continue;
      const float dx = start.x() + u * step.x(), dy = start.y() + u * step.y(), dz = start.z() + u * step.z();
      if (dz >= -1e-9f) continue;
      const float t = -height / dz;
      // A pixel's footprint on the ground (t |d|^2 / (fx |dz|)); blotches smaller average out.
      const float footprint_over_grain = t * (dx * dx + dy * dy + dz * dz) / (grain_fx * -dz);
      // Near the horizon the texture averages out entirely (and the ground point runs off to
      // where the lattice coordinates would overflow an int).
      if (!(footprint_over_grain < kMaxFootprintOverGrain)) continue;
      const float x = (px + t * dx) * inv_grain, y = (py + t * dy) * inv_grain;
      const float c = contrast * std::min(1.0f, 1.0f / footprint_over_grain);
      const float n = 0.67f * valueNoise(lattice, x, y) + 0.33f * valueNoise(lattice, 0.25f * x, 0.25f * y);
      const float gain = 1 + c * n;
      for (int ch = 0; ch < 3; ++ch) pixel[3 * u + ch] = cv::saturate_cast<uint8_t>(pixel[3 * u + ch] * gain);
    }
  }
}

// With a field: the ground pixels whose ground point lies outside it take the surround's colour,
// and each column's topmost field row is the field boundary's truth (labels: sky and ground only).
void paintSurround(const SceneConfig& config, const PinholeCamera& camera, const View& view, const Lighting& light,
                   SimFrame* frame) {
  const Eigen::Matrix3d base_from_optical = view.optical_from_base.transpose();
  const cv::Vec3b surround = [&] {
    const cv::Scalar c = litBgr(config.surround_rgb, 1.0, light.gain, light.cast);
    return cv::Vec3b(cv::saturate_cast<uint8_t>(c[0]), cv::saturate_cast<uint8_t>(c[1]), cv::saturate_cast<uint8_t>(c[2]));
  }();
  frame->field_top.assign(frame->image.cols, std::numeric_limits<float>::quiet_NaN());
  for (int v = 0; v < frame->image.rows; ++v) {
    const uint8_t* label = frame->labels.ptr<uint8_t>(v);
    cv::Vec3b* pixel = frame->image.ptr<cv::Vec3b>(v);
    for (int u = 0; u < frame->image.cols; ++u) {
      if (label[u] != SceneSimulator::kGroundLabel) continue;
      const Eigen::Vector3d d = base_from_optical * camera.ray(u, v);
      if (d.z() >= -1e-12) continue;
      const double t = -view.position.z() / d.z();
      const double x = view.position.x() + t * d.x(), y = view.position.y() + t * d.y();
      const bool inside = x >= config.field_x_min_m && x <= config.field_x_max_m && y >= config.field_y_min_m &&
                          y <= config.field_y_max_m;
      if (!inside) {
        pixel[u] = surround;
      } else if (std::isnan(frame->field_top[u])) {
        frame->field_top[u] = static_cast<float>(v);
      }
    }
  }
}

// Sky and ground, split exactly at the horizon: a pixel sees the sky when its ray points up.
void paintSkyAndGround(const SceneConfig& config, const PinholeCamera& camera, const View& view, const Lighting& light,
                       const std::vector<float>& texture_lattice, SimFrame* frame) {
  const int width = config.width, height = config.height;
  frame->image.create(height, width, CV_8UC3);
  frame->labels.create(height, width, CV_8UC1);
  const cv::Scalar ground = litBgr(config.ground_rgb, 1.0, light.gain, light.cast);
  const cv::Scalar sky = litBgr(config.sky_rgb, 1.0, light.gain, light.cast);
  double a = 0, b = 0, c = 0;
  const bool has_horizon = horizonFromUp(camera, view.optical_from_base * Eigen::Vector3d::UnitZ(), &a, &b, &c);
  if (has_horizon) {
    frame->horizon = lineFromHomogeneous(a, b, c);
    double x1, y1, x2, y2;
    frame->horizon_visible = clipLineToImage(frame->horizon, width, height, &x1, &y1, &x2, &y2);
  }
  for (int v = 0; v < height; ++v) {
    // Sky where a*u + (b*v + c) > 0: one interval [sky_begin, sky_end) per row.
    const double offset = b * v + c;
    int sky_begin = 0, sky_end = 0;
    if (std::fabs(a) < 1e-15) {
      sky_end = offset > 0 ? width : 0;
    } else if (a > 0) {
      sky_begin = static_cast<int>(std::max(0.0, std::min<double>(width, std::floor(-offset / a) + 1)));
      sky_end = width;
    } else {
      sky_end = static_cast<int>(std::max(0.0, std::min<double>(width, std::ceil(-offset / a))));
    }
    cv::Mat image_row = frame->image.row(v);
    cv::Mat label_row = frame->labels.row(v);
    image_row.setTo(ground);
    label_row.setTo(SceneSimulator::kGroundLabel);
    if (sky_end > sky_begin) {
      image_row.colRange(sky_begin, sky_end).setTo(sky);
      label_row.colRange(sky_begin, sky_end).setTo(SceneSimulator::kSkyLabel);
    }
  }
  if (config.has_field) paintSurround(config, camera, view, light, frame);
  if (config.ground_texture_contrast > 0) textureGround(config, camera, view, texture_lattice.data(), frame);
}

// Boxes at `positions`, far to near (painter's algorithm; boxes standing apart on a plane sort
// correctly), with the outlines of their faces for the edge truth.
void paintBoxes(const SceneConfig& config, const PinholeCamera& camera, const View& view, const Lighting& light,
                const std::vector<Eigen::Vector2d>& positions, SimFrame* frame, std::vector<CandidateEdge>* candidate_edges) {
  std::vector<std::pair<double, size_t>> order;
  for (size_t i = 0; i < config.boxes.size(); ++i) {
    const Eigen::Vector2d& p = positions[i];
    order.emplace_back(-(Eigen::Vector3d(p.x(), p.y(), 0.5 * config.boxes[i].height_m) - view.position).norm(), i);
  }
  std::sort(order.begin(), order.end());
  const double guard = 4.0 * std::max(config.width, config.height);
  for (const auto& entry : order) {
    const SceneBox& box = config.boxes[entry.second];
    const uint8_t label = static_cast<uint8_t>(SceneSimulator::kFirstBoxLabel + entry.second);
    for (const Face& face : boxFaces(box, positions[entry.second])) {
      if ((view.position - face.corners[0]).dot(face.normal) <= 0) continue;  // back face
      const std::vector<Eigen::Vector2d> projected = projectFace(face, view, camera, guard);
      if (projected.empty()) continue;
      std::vector<cv::Point> points;
      for (const auto& p : projected) {
        points.emplace_back(static_cast<int>(std::lround(p.x() * (1 << kSubPixelBits))),
                            static_cast<int>(std::lround(p.y() * (1 << kSubPixelBits))));
      }
      const cv::Scalar colour = litBgr(box.rgb, faceShade(face.normal), light.gain, light.cast);
      cv::fillConvexPoly(frame->image, points, colour, config.antialias ? cv::LINE_AA : cv::LINE_8, kSubPixelBits);
      cv::fillConvexPoly(frame->labels, points, cv::Scalar(label), cv::LINE_8, kSubPixelBits);
      for (size_t k = 0; k < projected.size(); ++k) {
        candidate_edges->push_back({projected[k], projected[(k + 1) % projected.size()], static_cast<int>(entry.second)});
      }
    }
  }
}

// Straight-edge truth, from the clean image (before blur and noise). A fold shared by two
// faces is listed by both: keep it once.
void edgeTruth(const std::vector<CandidateEdge>& candidate_edges, SimFrame* frame) {
  const int width = frame->image.cols, height = frame->image.rows;
  for (size_t i = 0; i < candidate_edges.size(); ++i) {
    const CandidateEdge& e = candidate_edges[i];
    bool repeated = false;
    for (size_t j = 0; j < i && !repeated; ++j) {
      const CandidateEdge& f = candidate_edges[j];
      repeated = f.box == e.box && (((f.a - e.a).norm() < 1e-6 && (f.b - e.b).norm() < 1e-6) ||
                                    ((f.a - e.b).norm() < 1e-6 && (f.b - e.a).norm() < 1e-6));
    }
    if (repeated) continue;
    double x1 = e.a.x(), y1 = e.a.y(), x2 = e.b.x(), y2 = e.b.y();
    if (!clipLineToImage(lineThroughPoints(x1, y1, x2, y2), width, height, &x1, &y1, &x2, &y2)) continue;
    // Clip the segment (not just its line) to the image.
    const ImageLine l = lineThroughPoints(e.a.x(), e.a.y(), e.b.x(), e.b.y());
    const double dx = std::cos(l.theta), dy = std::sin(l.theta);
    const double ta = e.a.x() * dx + e.a.y() * dy, tb = e.b.x() * dx + e.b.y() * dy;
    const double tc = x1 * dx + y1 * dy, td = x2 * dx + y2 * dy;
    const double lo = std::max(std::min(ta, tb), std::min(tc, td)), hi = std::min(std::max(ta, tb), std::max(tc, td));
    if (hi <= lo) continue;
    const double ox = e.a.x() - ta * dx, oy = e.a.y() - ta * dy;  // line point at t = 0
    for (const auto& [min_contrast, out] : {std::make_pair(SceneSimulator::kMinEdgeContrast, &frame->edges),
                                            std::make_pair(SceneSimulator::kMinFaintContrast, &frame->faint_edges)}) {
      visibleStretches(frame->image, frame->labels, ox + lo * dx, oy + lo * dy, ox + hi * dx, oy + hi * dy,
                       SceneSimulator::kFirstBoxLabel + e.box, e.box, min_contrast, out);
    }
  }
  if (frame->horizon_visible) {
    double x1, y1, x2, y2;
    clipLineToImage(frame->horizon, width, height, &x1, &y1, &x2, &y2);
    visibleStretches(frame->image, frame->labels, x1, y1, x2, y2, -1, -1, SceneSimulator::kMinEdgeContrast, &frame->edges);
    visibleStretches(frame->image, frame->labels, x1, y1, x2, y2, -1, -1, SceneSimulator::kMinFaintContrast,
                     &frame->faint_edges);
  }
}

// Ground truth from the label image: exactly the pixels each box covers.
void boxTruth(const SceneConfig& config, const std::vector<Eigen::Vector2d>& positions, SimFrame* frame) {
  struct Sums {
    uint64_t area = 0, sx = 0, sy = 0;
    int left = INT32_MAX, top = INT32_MAX, right = -1, bottom = -1;
  };
  std::vector<Sums> sums(config.boxes.size());
  for (int v = 0; v < config.height; ++v) {
    const uint8_t* row = frame->labels.ptr<uint8_t>(v);
    for (int u = 0; u < config.width; ++u) {
      if (row[u] < SceneSimulator::kFirstBoxLabel) continue;
      Sums& s = sums[row[u] - SceneSimulator::kFirstBoxLabel];
      ++s.area;
      s.sx += u;
      s.sy += v;
      s.left = std::min(s.left, u);
      s.right = std::max(s.right, u);
      s.top = std::min(s.top, v);
      s.bottom = std::max(s.bottom, v);
    }
  }
  for (size_t i = 0; i < config.boxes.size(); ++i) {
    const SceneBox& box = config.boxes[i];
    BoxTruth truth;
    truth.name = box.name;
    truth.color_class = box.color_class;
    truth.label = static_cast<uint8_t>(SceneSimulator::kFirstBoxLabel + i);
    truth.area = static_cast<uint32_t>(sums[i].area);
    if (sums[i].area > 0) {
      truth.cx = static_cast<double>(sums[i].sx) / sums[i].area;
      truth.cy = static_cast<double>(sums[i].sy) / sums[i].area;
      truth.left = sums[i].left;
      truth.top = sums[i].top;
      truth.right = sums[i].right;
      truth.bottom = sums[i].bottom;
      boxMaskTruth(frame->labels, config.boxes, i, &truth);
    }
    truth.position_m = positions[i];
    truth.width_m = box.width_m;
    truth.depth_m = box.depth_m;
    truth.height_m = box.height_m;
    truth.yaw_rad = box.yaw_deg * kDegToRad;
    frame->boxes.push_back(truth);
  }
}

// Lens blur and sensor noise.
void applySensor(const SceneConfig& config, const std::vector<int16_t>& noise_table, uint64_t frame_index,
                 SimFrame* frame) {
  if (config.blur_sigma_px > 0) {
    cv::GaussianBlur(frame->image, frame->image, cv::Size(), config.blur_sigma_px, config.blur_sigma_px,
                     cv::BORDER_REPLICATE);
  }
  if (config.noise_sigma > 0) {
    // One reproducible noise field per (seed, frame).
    addGaussianNoise(noise_table, config.seed * 0x9E3779B97F4A7C15ull + frame_index + 1, &frame->image);
  }
}

}  // namespace

SimFrame SceneSimulator::render(uint64_t frame_index, double t) const {
  SimFrame frame;
  frame.frame_index = frame_index;
  frame.time_s = t;
  frame.pose = poseAt(t);
  frame.light_gain = lightGainAt(t);
  Lighting light;
  light.gain = frame.light_gain;
  const double drift = config_.light_drift_duration_s > 0
                           ? std::min(1.0, std::max(0.0, t / config_.light_drift_duration_s))
                           : 0.0;
  for (int c = 0; c < 3; ++c) {
    light.cast[c] = config_.light_cast_start_rgb[c] +
                    drift * (config_.light_cast_end_rgb[c] - config_.light_cast_start_rgb[c]);
  }
  const View view{opticalToBaseRotation(frame.pose.roll, frame.pose.pitch, frame.pose.yaw).transpose(),
                  Eigen::Vector3d(frame.pose.x_m, frame.pose.y_m, frame.pose.height_m)};
  std::vector<Eigen::Vector2d> positions;
  for (const SceneBox& box : config_.boxes) positions.push_back(boxPositionAt(box, t));
  paintSkyAndGround(config_, camera_, view, light, texture_lattice_, &frame);
  std::vector<CandidateEdge> candidate_edges;
  paintBoxes(config_, camera_, view, light, positions, &frame, &candidate_edges);
  edgeTruth(candidate_edges, &frame);
  boxTruth(config_, positions, &frame);
  applySensor(config_, noise_table_, frame_index, &frame);
  return frame;
}

}  // namespace rle_vision
