#include "rle_vision/landmark/horizon_model.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace rle_vision {
namespace {

constexpr const char* kNames[kHorizonFeatureCount] = {
    "separation", "sky_brighter", "ground_rougher", "ground_textured", "ground_textured_relative",
    "coverage", "fit_spread",
    "edge_contrast", "local_step", "sky_share", "tilt", "from_regions"};

constexpr int kNewtonSteps = 50;

double sigmoid(double z) { return z >= 0 ? 1 / (1 + std::exp(-z)) : std::exp(z) / (1 + std::exp(z)); }

// log(1 + e^s) without overflow.
double softplus(double s) { return s > 0 ? s + std::log1p(std::exp(-s)) : std::log1p(std::exp(s)); }

// The weighted mean and standard deviation of every feature (scale 1 for a constant one).
void standardisation(const std::vector<HorizonFeatures>& x, const std::vector<double>& w, HorizonModel* m) {
  double total = 0;
  for (double v : w) total += v;
  for (int f = 0; f < kHorizonFeatureCount; ++f) {
    double sum = 0, squares = 0;
    for (size_t i = 0; i < x.size(); ++i) sum += w[i] * x[i][f];
    const double mean = sum / total;
    for (size_t i = 0; i < x.size(); ++i) squares += w[i] * (x[i][f] - mean) * (x[i][f] - mean);
    const double sd = std::sqrt(squares / total);
    m->mean[f] = mean;
    m->scale[f] = sd > 1e-9 ? sd : 1.0;
  }
}

// The scale a and offset c of the fitted score z (the weighted features, without the bias) that
// maximise the weighted likelihood of sigmoid(a z + c), unpenalised: two parameters, by Newton's
// method. The penalty picks the direction of the weights; this keeps the probability calibrated
// however strongly it shrank them. The targets are Platt's, (n1 + 1) / (n1 + 2) and 1 / (n0 + 2)
// rather than 1 and 0, so a direction that separates the training samples gets a finite scale;
// n1 and n0 count samples, not their weights: how sure the number of examples lets us be. Starts
// from the penalised fit: a = 1 and c as it comes in (that fit's bias). False when the scores do
// not vary.
bool calibrateScale(const Eigen::VectorXd& z, const std::vector<int>& y, const std::vector<double>& w, double* a,
                    double* c) {
  if (z.size() == 0 || z.maxCoeff() - z.minCoeff() < 1e-12) return false;
  const double positives = static_cast<double>(std::count(y.begin(), y.end(), 1));
  const double negatives = static_cast<double>(y.size()) - positives;
  const double target_positive = (positives + 1) / (positives + 2), target_negative = 1 / (negatives + 2);
  auto target = [&](int i) { return y[i] == 1 ? target_positive : target_negative; };
  // The weighted cross-entropy to the targets, in softplus form so that saturated scores stay finite.
  auto loss = [&](const Eigen::Vector2d& theta) {
    double sum = 0;
    for (int i = 0; i < z.size(); ++i) {
      const double s = theta(0) * z(i) + theta(1);
      sum += w[i] * (target(i) * softplus(-s) + (1 - target(i)) * softplus(s));
    }
    return sum;
  };
  Eigen::Vector2d theta(1, *c);
  double current = loss(theta);
  for (int step = 0; step < kNewtonSteps; ++step) {
    Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
    Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();
    for (int i = 0; i < z.size(); ++i) {
      const Eigen::Vector2d row(z(i), 1);
      const double p = sigmoid(theta.dot(row));
      gradient += w[i] * (target(i) - p) * row;
      hessian += w[i] * std::max(p * (1 - p), 1e-9) * row * row.transpose();
    }
    // Newton's step, halved until the loss falls: an undamped step from a poor start can overshoot
    // into saturation, where the tiny curvature sends the next one to infinity.
    Eigen::Vector2d delta = hessian.ldlt().solve(gradient);
    double next = loss(theta + delta);
    for (int halving = 0; halving < 30 && !(next <= current); ++halving) {
      delta /= 2;
      next = loss(theta + delta);
    }
    if (!(next <= current)) break;
    theta += delta;
    current = next;
    if (delta.cwiseAbs().maxCoeff() < 1e-9 * (1 + theta.cwiseAbs().maxCoeff())) break;
  }
  *a = theta(0);
  *c = theta(1);
  return std::isfinite(*a) && std::isfinite(*c) && *a > 0;
}

}  // namespace

const char* horizonFeatureName(int feature) {
  return feature >= 0 && feature < kHorizonFeatureCount ? kNames[feature] : "";
}

double HorizonModel::probability(const HorizonFeatures& features) const {
  double z = bias;
  for (int f = 0; f < kHorizonFeatureCount; ++f) z += weights[f] * (features[f] - mean[f]) / scale[f];
  return sigmoid(z);
}

HorizonModel fitHorizonModel(const std::vector<HorizonFeatures>& x, const std::vector<int>& y,
                             const std::vector<double>& w, double l2) {
  HorizonModel m;
  const int n = static_cast<int>(x.size());
  if (n == 0 || y.size() != x.size() || w.size() != x.size()) return m;
  if (std::none_of(y.begin(), y.end(), [](int v) { return v == 1; }) ||
      std::none_of(y.begin(), y.end(), [](int v) { return v == 0; })) {
    return m;
  }
  standardisation(x, w, &m);
  const int d = kHorizonFeatureCount + 1;  // the bias last
  Eigen::MatrixXd design(n, d);
  for (int i = 0; i < n; ++i) {
    for (int f = 0; f < kHorizonFeatureCount; ++f) design(i, f) = (x[i][f] - m.mean[f]) / m.scale[f];
    design(i, kHorizonFeatureCount) = 1;
  }
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(d), prior = Eigen::VectorXd::Constant(d, l2);
  prior(kHorizonFeatureCount) = 0;
  for (int step = 0; step < kNewtonSteps; ++step) {
    const Eigen::VectorXd z = design * beta;
    Eigen::VectorXd gradient = -prior.cwiseProduct(beta);
    Eigen::MatrixXd hessian = Eigen::MatrixXd(prior.asDiagonal());
    for (int i = 0; i < n; ++i) {
      const double p = sigmoid(z(i));
      gradient += w[i] * (y[i] - p) * design.row(i).transpose();
      hessian += w[i] * std::max(p * (1 - p), 1e-9) * design.row(i).transpose() * design.row(i);
    }
    const Eigen::VectorXd delta = hessian.ldlt().solve(gradient);
    beta += delta;
    if (delta.cwiseAbs().maxCoeff() < 1e-9) break;
  }
  double scale = 1, offset = beta(kHorizonFeatureCount);
  const Eigen::VectorXd z = design.leftCols(kHorizonFeatureCount) * beta.head(kHorizonFeatureCount);
  if (!calibrateScale(z, y, w, &scale, &offset)) scale = 1, offset = beta(kHorizonFeatureCount);
  for (int f = 0; f < kHorizonFeatureCount; ++f) m.weights[f] = scale * beta(f);
  m.bias = offset;
  m.valid = std::isfinite(m.bias) &&
            std::all_of(m.weights.begin(), m.weights.end(), [](double v) { return std::isfinite(v); });
  return m;
}

}  // namespace rle_vision
