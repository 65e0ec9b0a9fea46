# The Python package bearing_sim (docs/python.md): python/bearing_sim (campaigns, the
# re-export) through catkin_python_setup, and the compiled core bearing_sim._core (pybind11,
# Debian's pybind11-dev) beside the generated messages in the devel and install space.
# Included after the core and runtime object libraries, whose objects it links.
# catkin_python_setup() is called in CMakeLists.txt, before generate_messages() as catkin requires.

# Python3 is already found (Interpreter only) by a ROS package, which sends pybind11 to
# CMake's FindPython: it then needs the Development.Module component too.
find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
find_package(pybind11 CONFIG REQUIRED)
# The module carries the core's objects itself (the same position-independent objects as
# libbearing_sim_core.so, compiled once): that library is installed in lib/bearing_sim, where
# an installed module would not find it. Scenario generation is the runtime's
# ScenarioSimulation (bearing_tool generate's, through the node's per-sample pipeline), linked
# the same way: the module needs no ROS.
# A plain MODULE library with pybind11's extension naming (no link-time optimisation, so
# the module builds in the time of its objects; and a target catkin_lint can follow).
add_library(bearing_sim_python MODULE
  src/python/module.cpp
  src/python/bearing_binding.cpp
  src/python/scenario_binding.cpp
  src/python/analysis_binding.cpp
  $<TARGET_OBJECTS:bearing_sim_core_objects>
  $<TARGET_OBJECTS:bearing_sim_runtime_objects>
)
pybind11_extension(bearing_sim_python)
target_link_libraries(bearing_sim_python PRIVATE pybind11::module Eigen3::Eigen yaml-cpp hwy::hwy Threads::Threads)
bearing_sim_optimize(bearing_sim_python)
# Its four binding files in one translation unit (CMake's unity build): each instantiates
# pybind11's templates, which one by one cost 43 CPU-s, together 16.
set_target_properties(bearing_sim_python PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
set_target_properties(bearing_sim_python PROPERTIES OUTPUT_NAME _core
  LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_PYTHON_DESTINATION}/${PROJECT_NAME})
install(TARGETS bearing_sim_python LIBRARY DESTINATION ${CATKIN_GLOBAL_PYTHON_DESTINATION}/${PROJECT_NAME})
# (catkin_package() has not yet set CATKIN_PACKAGE_BIN_DESTINATION, lib/bearing_sim)
catkin_install_python(PROGRAMS scripts/bearing_campaign DESTINATION ${CATKIN_GLOBAL_LIBEXEC_DESTINATION}/${PROJECT_NAME})

if(CATKIN_ENABLE_TESTING)
  # pytest of the module and the campaigns (test/python), a JUnit file in test_results like
  # the gtests. Runs against the devel space (run_tests sources its environment).
  set(bearing_sim_pytest_xml ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/pytest-test_python.xml)
  catkin_run_tests_target(pytest test_python pytest-test_python.xml
    COMMAND "/usr/bin/python3 -m pytest -q -p no:cacheprovider ${CMAKE_CURRENT_SOURCE_DIR}/test/python --junitxml=${bearing_sim_pytest_xml}"
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  add_dependencies(tests bearing_sim_python)
endif()
