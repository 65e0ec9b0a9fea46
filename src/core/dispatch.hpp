#pragma once
// HWY_DYNAMIC_DISPATCH for the hot kernels, without its call into libhwy: the object that
// holds the chosen target (hwy::GetChosenTarget()) never moves, so it is looked up once;
// its mask is still read at every call, so a target changed later (DisableTargets,
// SetSupportedTargetsForTest) applies at once, and the table's first entry still makes the
// first call choose the target. Saves the call and a stack frame per kernel call: ~20
// instructions, 10 calls per output sample of a small bearing.
#include <hwy/highway.h>

namespace bearing_sim::detail {

namespace {
// Set as the library loads (null only for a call from another library's static initializer).
hwy::ChosenTarget* const chosen_target_at_load = &hwy::GetChosenTarget();
}  // namespace

inline hwy::ChosenTarget& chosen_target() {
  return chosen_target_at_load ? *chosen_target_at_load : hwy::GetChosenTarget();
}

}  // namespace bearing_sim::detail

#define BEARING_SIM_DISPATCH(FUNC_NAME) \
  (*(HWY_DISPATCH_TABLE(FUNC_NAME)[::bearing_sim::detail::chosen_target().GetIndex()]))
