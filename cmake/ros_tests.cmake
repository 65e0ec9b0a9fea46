# Tests of bearing_sim_node: ROS-free unit tests of its helpers, and rostests
# that start the node (via launch/ct_gantry.launch) and check its outputs.
catkin_add_gtest(test_node_helpers test/ros/test_node_helpers.cpp TIMEOUT 300)
target_link_libraries(test_node_helpers bearing_sim_ros_helpers bearing_sim_core)
target_compile_definitions(test_node_helpers PRIVATE BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
bearing_sim_optimize(test_node_helpers)

find_package(rostest REQUIRED)
# One gtest node per rostest; each links the core for its reference values.
function(bearing_sim_node_rostest name)
  add_rostest_gtest(${name} test/ros/${ARGN}.test test/ros/${name}.cpp)
  add_dependencies(${name} ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS} bearing_sim_node)
  target_include_directories(${name} PRIVATE ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
  target_link_libraries(${name} bearing_sim_core ${catkin_LIBRARIES})
  bearing_sim_optimize(${name})
endfunction()
bearing_sim_node_rostest(test_node_steady_state node_steady_state)
bearing_sim_node_rostest(test_node_inputs node_inputs)
bearing_sim_node_rostest(test_node_realtime node_realtime)
bearing_sim_node_rostest(test_node_fast_mode node_fast_mode)
bearing_sim_node_rostest(test_node_divergence node_divergence)
bearing_sim_node_rostest(test_node_health node_health)
# Node as fast as possible vs generate's ScenarioSimulation (built in), same inputs and seed.
add_rostest_gtest(test_node_generate_equivalence test/ros/node_generate_equivalence.test
  test/ros/test_node_generate_equivalence.cpp src/tools/scenario_simulation.cpp src/ros/message_conversion.cpp)
add_dependencies(test_node_generate_equivalence ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS}
  bearing_sim_node)
target_include_directories(test_node_generate_equivalence PRIVATE
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION} ${CMAKE_CURRENT_SOURCE_DIR}/src/tools)
target_link_libraries(test_node_generate_equivalence bearing_sim_ros_helpers bearing_sim_core ${catkin_LIBRARIES})
bearing_sim_optimize(test_node_generate_equivalence)

# Health helpers (HealthMonitor, TriaxialSensor, chunk tilt), no ROS master.
catkin_add_gtest(test_health_monitor test/ros/test_health_monitor.cpp TIMEOUT 300)
target_link_libraries(test_health_monitor bearing_sim_ros_helpers bearing_sim_core)
target_compile_definitions(test_health_monitor PRIVATE BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
bearing_sim_optimize(test_health_monitor)
