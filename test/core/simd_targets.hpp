#pragma once
// Runs a test body once per compiled Highway target the CPU supports, the dispatcher forced to
// that target, so that every SIMD kernel is checked on every instruction set this machine has
// (an AVX-512 machine checks the AVX2 and SSE4 variants too).
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <cstdint>
#include <iostream>
#include <string>

#include "../../src/core/contact_kernel.hpp"

namespace bearing_sim::test {

template <typename Body>
void for_each_simd_target(const Body& body) {
  hwy::SetSupportedTargetsForTest(0);
  const std::int64_t supported = hwy::SupportedTargets();
  int tested = 0;
  for (const std::int64_t target : detail::contact_kernel_compiled_targets()) {
    if ((target & supported) == 0) {
      std::cout << "[ SKIPPED  ] SIMD target " << hwy::TargetName(target) << ": this CPU cannot run it\n";
      continue;
    }
    hwy::SetSupportedTargetsForTest(target);
    const std::string name = detail::contact_kernel_target_name();
    std::cout << "[ TARGET   ] " << name << "\n";
    EXPECT_EQ(name, hwy::TargetName(target));
    SCOPED_TRACE("SIMD target " + name);
    body();
    ++tested;
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GT(tested, 0);
}

}  // namespace bearing_sim::test
