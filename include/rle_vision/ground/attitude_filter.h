// The camera's attitude from successive horizons, for a robot without joint encoders.
#pragma once

#include <cstddef>
#include <deque>
#include <string>

namespace rle_vision {

// smoothing (0: every horizon taken as it is; towards 1: smoother, slower), min_confidence,
// max_jump_deg (a horizon this far from the prediction is a glitch, ignored unless
// max_rejected come in a row: then the filter restarts), max_hold_s, max_gap_s (the longest gap
// between horizons an image's attitude is interpolated across): the ATTITUDE_FILTER group of
// ground_params.def, with their defaults and meanings.
struct AttitudeFilterOptions {
#define RLE_ATTITUDE_FILTER_PARAM(key, member, type, default_value, min, max, description) type member = default_value;
#include "rle_vision/params/ground_params.def"
};

// Reason the options are unusable, or "" when they are fine.
std::string validateAttitudeFilterOptions(const AttitudeFilterOptions& options);

// Camera roll and pitch from successive horizons: an alpha-beta filter per angle (it follows a
// swaying gait without the lag plain averaging has), gated against glitches.
class AttitudeFilter {
 public:
  explicit AttitudeFilter(const AttitudeFilterOptions& options = AttitudeFilterOptions()) : options_(options) {}
  void setOptions(const AttitudeFilterOptions& options) { options_ = options; }

  enum class Outcome { kAccepted, kLowConfidence, kJump, kNoHorizon };
  // One horizon (its roll and pitch, rad) at `stamp_s`. Out-of-order stamps are ignored.
  Outcome update(bool found, double roll, double pitch, double confidence, double stamp_s);

  bool valid(double stamp_s) const;  // an attitude exists and is not older than max_hold_s
  double roll() const { return roll_; }
  double pitch() const { return pitch_; }
  double rollRate() const { return roll_rate_; }
  double pitchRate() const { return pitch_rate_; }
  double lastStamp() const { return last_stamp_s_; }

 private:
  AttitudeFilterOptions options_;
  bool initialised_ = false;
  double roll_ = 0, pitch_ = 0, roll_rate_ = 0, pitch_rate_ = 0;
  double last_stamp_s_ = 0, last_accepted_s_ = 0;
  int rejected_in_a_row_ = 0;
};

// The camera attitude over time, from horizons (the GroundProjector's horizon mode): the
// filter above, and its state at each accepted horizon of the last seconds, so that an image
// between two of them (the low-priority landmark node skips frames under load, or a horizon
// was rejected) gets its attitude by cubic Hermite interpolation, with the angles' rates from
// the states on both sides of the gap: it follows the gait's sway across the gap, where a
// linear interpolation (tf's) cuts the corners.
class AttitudeTimeline {
 public:
  explicit AttitudeTimeline(const AttitudeFilterOptions& options = AttitudeFilterOptions());
  void setOptions(const AttitudeFilterOptions& options);

  struct Attitude {
    double roll = 0, pitch = 0;  // rad, REP 103
    double confidence = 0;       // the horizon's when it was accepted, else 0
  };
  struct Update {
    AttitudeFilter::Outcome outcome = AttitudeFilter::Outcome::kNoHorizon;
    bool restarted = false;  // time went backwards (a looped bag): everything was forgotten
    bool valid = false;      // an attitude exists at the horizon's stamp (then in `attitude`)
    bool recorded = false;   // ... from this horizon, accepted: images near it are placed by it
    Attitude attitude;
  };
  // One horizon message (roll and pitch as the landmark node computes them).
  Update addHorizon(bool found, double roll, double pitch, double confidence, double stamp_s);

  enum class Lookup { kFound, kNotYet, kLost };
  // The attitude at an image stamp: kFound (in *roll, *pitch) at a recorded horizon or between
  // two no more than max_gap_s apart; kNotYet after the newest one (a later horizon will cover
  // it, and one more for the rate at its end); kLost before the oldest kept one or inside a
  // longer gap.
  Lookup attitudeAt(double stamp_s, double* roll, double* pitch) const;

 private:
  struct State {
    double stamp_s, roll, pitch, roll_rate, pitch_rate;
  };
  double rate(size_t k, double State::*angle, double State::*filter_rate) const;
  AttitudeFilterOptions options_;
  AttitudeFilter filter_;
  std::deque<State> states_;  // by stamp, the last kKeepS seconds
};

}  // namespace rle_vision
