# Flags for the hot loops: vectorize the per-ball force loop (omp simd reductions) for
# this machine. The package is always built where it runs (catkin source build), so
# -march=native is safe; -fno-math-errno lets sqrt vectorize without changing results.
include(CheckCXXCompilerFlag)
check_cxx_compiler_flag(-march=native BEARING_SIM_HAS_MARCH_NATIVE)
option(BEARING_SIM_NATIVE "Optimize for the build machine's CPU" ON)

function(bearing_sim_optimize target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-maybe-uninitialized -fopenmp-simd -fno-math-errno)
  if(BEARING_SIM_NATIVE AND BEARING_SIM_HAS_MARCH_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
