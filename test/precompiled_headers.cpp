// The owner of the test suites' precompiled header (CMakeLists.txt, bearing_sim_test_pch): a
// target needs a source for CMake to build its header, which the suites then reuse.
