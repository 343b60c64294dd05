#include "rle_vision/ground/attitude_filter.h"

#include <algorithm>
#include <cmath>

namespace rle_vision {
namespace {

constexpr double kNominalFramePeriodS = 1.0 / 30;  // the smoothing is given per such frame

}  // namespace

std::string validateAttitudeFilterOptions(const AttitudeFilterOptions& o) {
  if (!std::isfinite(o.smoothing) || o.smoothing < 0 || o.smoothing >= 1) return "smoothing must be in [0, 1)";
  if (!std::isfinite(o.min_confidence) || o.min_confidence < 0 || o.min_confidence > 1) {
    return "min_confidence must be in [0, 1]";
  }
  if (!std::isfinite(o.max_jump_deg) || o.max_jump_deg <= 0) return "max_jump_deg must be positive";
  if (o.max_rejected < 1) return "max_rejected must be at least 1";
  if (!std::isfinite(o.max_hold_s) || o.max_hold_s <= 0) return "max_hold_s must be positive";
  if (!std::isfinite(o.max_gap_s) || o.max_gap_s <= 0) return "max_gap_s must be positive";
  return "";
}

AttitudeFilter::Outcome AttitudeFilter::update(bool found, double roll, double pitch, double confidence,
                                               double stamp_s) {
  if (initialised_ && stamp_s <= last_stamp_s_) return Outcome::kNoHorizon;  // old or repeated
  if (!found || !std::isfinite(roll) || !std::isfinite(pitch)) return Outcome::kNoHorizon;
  if (!(confidence >= options_.min_confidence)) return Outcome::kLowConfidence;
  const bool restart = !initialised_ || stamp_s - last_accepted_s_ > options_.max_hold_s;
  if (restart) {
    roll_ = roll;
    pitch_ = pitch;
    roll_rate_ = pitch_rate_ = 0;
  } else {
    const double dt = stamp_s - last_stamp_s_;
    const double roll_predicted = roll_ + roll_rate_ * dt, pitch_predicted = pitch_ + pitch_rate_ * dt;
    const double roll_residual = roll - roll_predicted, pitch_residual = pitch - pitch_predicted;
    const double max_jump = options_.max_jump_deg * M_PI / 180;
    // The gate: against the prediction, but across a gap over max_gap_s (the gait turns within
    // it: the rate carried that far overshoots) against the last attitude itself.
    const bool rate_holds = dt <= options_.max_gap_s;
    const double roll_off = rate_holds ? roll_residual : roll - roll_, pitch_off = rate_holds ? pitch_residual : pitch - pitch_;
    if ((std::abs(roll_off) > max_jump || std::abs(pitch_off) > max_jump) && ++rejected_in_a_row_ < options_.max_rejected) {
      return Outcome::kJump;
    }
    if (rejected_in_a_row_ >= options_.max_rejected) {  // the glitch persists: it is the truth now
      roll_ = roll;
      pitch_ = pitch;
      roll_rate_ = pitch_rate_ = 0;
    } else {
      // Alpha-beta filter; beta = alpha^2 / (2 - alpha) damps it critically (alpha = 1: no smoothing).
      // The smoothing is the prediction's weight over one nominal frame; a prediction over a
      // longer gap (skipped horizons) is less sure, and weighs less.
      const double smoothing = std::pow(options_.smoothing, dt / kNominalFramePeriodS);
      const double alpha = 1.0 - smoothing, beta = alpha * alpha / (2.0 - alpha);
      roll_ = roll_predicted + alpha * roll_residual;
      pitch_ = pitch_predicted + alpha * pitch_residual;
      roll_rate_ += beta * roll_residual / dt;
      pitch_rate_ += beta * pitch_residual / dt;
    }
  }
  rejected_in_a_row_ = 0;
  initialised_ = true;
  last_stamp_s_ = last_accepted_s_ = stamp_s;
  return Outcome::kAccepted;
}

bool AttitudeFilter::valid(double stamp_s) const {
  return initialised_ && std::abs(stamp_s - last_accepted_s_) <= options_.max_hold_s;
}

namespace {

constexpr double kKeepS = 3.0;  // states kept for images that come late

// Cubic Hermite interpolation of a value with its rate, from (t0, v0, r0) to (t1, v1, r1).
double hermite(double t, double t0, double v0, double r0, double t1, double v1, double r1) {
  const double h = t1 - t0;
  const double s = (t - t0) / h, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * h * r0 + (-2 * s3 + 3 * s2) * v1 + (s3 - s2) * h * r1;
}

}  // namespace

AttitudeTimeline::AttitudeTimeline(const AttitudeFilterOptions& options) : options_(options), filter_(options) {}

void AttitudeTimeline::setOptions(const AttitudeFilterOptions& options) {
  options_ = options;
  filter_.setOptions(options);
}

AttitudeTimeline::Update AttitudeTimeline::addHorizon(bool found, double roll, double pitch, double confidence,
                                                      double stamp_s) {
  Update update;
  if (stamp_s < filter_.lastStamp() - 1.0) {  // a looped bag, or a restarted simulation
    filter_ = AttitudeFilter(options_);
    states_.clear();
    update.restarted = true;
  }
  update.outcome = filter_.update(found, roll, pitch, confidence, stamp_s);
  if (!filter_.valid(stamp_s) || (!states_.empty() && stamp_s <= states_.back().stamp_s)) return update;
  // After a rejected horizon the attitude is the last accepted one moved on at the filter's
  // rate (reported, with confidence 0), but not recorded: an extrapolation across the gait's
  // sway is off by far more than the interpolation between the accepted horizons on both sides
  // (gtest AttitudeTimeline.RejectedHorizonsAreBridgedNotExtrapolated), so images there wait
  // for the next accepted horizon, within max_gap_s of the last.
  const double dt = stamp_s - filter_.lastStamp();
  const State state{stamp_s, filter_.roll() + filter_.rollRate() * dt, filter_.pitch() + filter_.pitchRate() * dt,
                    filter_.rollRate(), filter_.pitchRate()};
  const bool accepted = update.outcome == AttitudeFilter::Outcome::kAccepted;
  if (accepted) {
    states_.push_back(state);
    while (states_.front().stamp_s < stamp_s - kKeepS) states_.pop_front();
  }
  update.valid = true;
  update.recorded = accepted;
  update.attitude.roll = state.roll;
  update.attitude.pitch = state.pitch;
  update.attitude.confidence = accepted ? confidence : 0.0;
  return update;
}

double AttitudeTimeline::rate(size_t k, double State::*angle, double State::*filter_rate) const {
  // The three-point (second-order) derivative through the neighbouring states, which sees the
  // curve on both sides; where a neighbour is missing or too far away, the filter's own rate.
  if (k == 0 || k + 1 >= states_.size()) return states_[k].*filter_rate;
  const State &a = states_[k - 1], &b = states_[k], &c = states_[k + 1];
  const double h0 = b.stamp_s - a.stamp_s, h1 = c.stamp_s - b.stamp_s;
  if (h0 > options_.max_gap_s || h1 > options_.max_gap_s) return b.*filter_rate;
  return (h0 * h0 * (c.*angle - b.*angle) + h1 * h1 * (b.*angle - a.*angle)) / (h0 * h1 * (h0 + h1));
}

AttitudeTimeline::Lookup AttitudeTimeline::attitudeAt(double stamp_s, double* roll, double* pitch) const {
  if (states_.empty() || stamp_s > states_.back().stamp_s) return Lookup::kNotYet;
  if (stamp_s < states_.front().stamp_s) return Lookup::kLost;
  const auto after = std::lower_bound(states_.begin(), states_.end(), stamp_s,
                                      [](const State& s, double t) { return s.stamp_s < t; });
  if (after->stamp_s == stamp_s) {
    *roll = after->roll;
    *pitch = after->pitch;
    return Lookup::kFound;
  }
  const size_t k = static_cast<size_t>(after - states_.begin()) - 1;
  const State& a = states_[k];
  const State& b = states_[k + 1];
  if (b.stamp_s - a.stamp_s > options_.max_gap_s) return Lookup::kLost;
  if (k + 2 >= states_.size()) return Lookup::kNotYet;  // the rate at b needs the state after it
  *roll = hermite(stamp_s, a.stamp_s, a.roll, rate(k, &State::roll, &State::roll_rate), b.stamp_s, b.roll,
                  rate(k + 1, &State::roll, &State::roll_rate));
  *pitch = hermite(stamp_s, a.stamp_s, a.pitch, rate(k, &State::pitch, &State::pitch_rate), b.stamp_s, b.pitch,
                   rate(k + 1, &State::pitch, &State::pitch_rate));
  return Lookup::kFound;
}

}  // namespace rle_vision
