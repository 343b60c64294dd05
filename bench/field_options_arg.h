// The evals' --non-field-penalty P: the field stage's field_non_field_penalty for every frame
// (landmark_params.def's range), so that how the boundary trades robots against the rest can be
// measured for other values (docs/performance.md) with the tools CI runs.
#pragma once

#include <string>

#include "harness.h"
#include "rle_vision/field/field_detector.h"

namespace rle_vision {
namespace bench {

// Sets options->boundary.non_field_penalty from `text`; false (and `problem` says why) when it
// is not one finite number within the parameter's range.
inline bool parseNonFieldPenalty(const char* text, FieldOptions* options, std::string* problem) {
  double value = 0;
  if (!isFiniteNumber(text, &value)) {
    *problem = std::string("--non-field-penalty needs a number, not '") + text + "'";
    return false;
  }
  FieldOptions changed = *options;
  changed.boundary.non_field_penalty = value;
  *problem = validateFieldOptions(changed);
  if (!problem->empty()) return false;
  *options = changed;
  return true;
}

}  // namespace bench
}  // namespace rle_vision
