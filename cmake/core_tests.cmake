# gtest suites of the ROS-free core. Each links only the core library.
file(GLOB BEARING_SIM_CORE_TESTS ${CMAKE_CURRENT_SOURCE_DIR}/test/core/test_*.cpp)
# test_support.cpp is the shared fixture, linked into every suite, not a suite itself.
list(FILTER BEARING_SIM_CORE_TESTS EXCLUDE REGEX "/test_support\\.cpp$")
foreach(test_source ${BEARING_SIM_CORE_TESTS})
  get_filename_component(test_name ${test_source} NAME_WE)
  catkin_add_gtest(${test_name} ${test_source} test/core/test_support.cpp
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} TIMEOUT 600)
  # catkin's gtest does not bring main(); gtest_main provides it.
  if(TARGET gtest_main)
    target_link_libraries(${test_name} bearing_sim_core gtest_main)
  else()
    target_link_libraries(${test_name} bearing_sim_core ${GTEST_MAIN_LIBRARIES})
  endif()
  target_compile_definitions(${test_name} PRIVATE
    BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  bearing_sim_optimize(${test_name})
endforeach()
# The kernel test forces the Highway dispatcher onto each SIMD target in turn.
if(TARGET test_contact_kernel)
  target_link_libraries(test_contact_kernel hwy::hwy)
endif()
