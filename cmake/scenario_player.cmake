# scenario_player: the ROS-free time line, the node, and their tests.
add_library(bearing_sim_scenario_timeline STATIC src/ros/scenario_timeline.cpp)
target_include_directories(bearing_sim_scenario_timeline PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(bearing_sim_scenario_timeline PUBLIC bearing_sim_core)
bearing_sim_optimize(bearing_sim_scenario_timeline)

add_executable(scenario_player src/nodes/scenario_player_node.cpp src/ros/scenario_player.cpp src/ros/message_conversion.cpp)
add_dependencies(scenario_player ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
target_include_directories(scenario_player PRIVATE ${catkin_INCLUDE_DIRS}
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_link_libraries(scenario_player bearing_sim_scenario_timeline bearing_sim_core ${catkin_LIBRARIES})
bearing_sim_optimize(scenario_player)
set_target_properties(scenario_player PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS scenario_player RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  # Which command goes out when (no ROS master).
  catkin_add_gtest(test_scenario_timeline test/ros/test_scenario_timeline.cpp TIMEOUT 120)
  target_link_libraries(test_scenario_timeline bearing_sim_scenario_timeline bearing_sim_core)
  target_compile_definitions(test_scenario_timeline PRIVATE BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  bearing_sim_optimize(test_scenario_timeline)

  # The node as fast as possible driven by a short scenario: speed, load and defects follow it.
  bearing_sim_node_rostest(test_scenario_player scenario_player)
  add_dependencies(test_scenario_player scenario_player)
  # The same checks in real time, with a tight bound on the input lag.
  add_rostest(test/ros/scenario_player_realtime.test DEPENDENCIES test_scenario_player)
endif()
