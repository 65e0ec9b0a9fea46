# Flags for the hot loops. -fno-math-errno lets sqrt vectorize without changing results.
# No -march=native by default: binaries (Debian packages, Docker images, a build farm's
# output) must run on any x86-64, and the contact kernel, which is where SIMD pays, is built
# by Google Highway for SSE4, AVX2 and AVX-512 with target attributes and picked at run
# time. BEARING_SIM_NATIVE=ON still tunes the rest for the build machine (not portable).
include(CheckCXXCompilerFlag)
check_cxx_compiler_flag(-march=native BEARING_SIM_HAS_MARCH_NATIVE)
option(BEARING_SIM_NATIVE "Optimize for the build machine's CPU (binaries then need that CPU)" OFF)

function(bearing_sim_optimize target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-maybe-uninitialized -fopenmp-simd -fno-math-errno)
  if(BEARING_SIM_NATIVE AND BEARING_SIM_HAS_MARCH_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
