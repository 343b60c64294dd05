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
  for (int f = 0; f < kHorizonFeatureCount; ++f) m.weights[f] = beta(f);
  m.bias = beta(kHorizonFeatureCount);
  m.valid = std::isfinite(m.bias) &&
            std::all_of(m.weights.begin(), m.weights.end(), [](double v) { return std::isfinite(v); });
  return m;
}

}  // namespace rle_vision
