# Ball-load display: ROS-light drawing library, bearing_viz_node, their tests.
add_library(bearing_sim_viz STATIC
  src/viz/colour_map.cpp
  src/viz/bearing_scene.cpp
  src/viz/marker_builder.cpp
)
add_dependencies(bearing_sim_viz ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
target_include_directories(bearing_sim_viz PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(bearing_sim_viz PUBLIC bearing_sim_core ${catkin_LIBRARIES})
bearing_sim_optimize(bearing_sim_viz)

add_executable(bearing_viz_node src/nodes/bearing_viz_node.cpp src/viz/viz_node.cpp)
add_dependencies(bearing_viz_node ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
target_include_directories(bearing_viz_node PRIVATE ${catkin_INCLUDE_DIRS})
target_link_libraries(bearing_viz_node bearing_sim_viz bearing_sim_core ${catkin_LIBRARIES})
bearing_sim_optimize(bearing_viz_node)
set_target_properties(bearing_viz_node PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS bearing_viz_node RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  # Unit tests of the colour map, scene geometry and marker layout (no ROS master).
  catkin_add_gtest(test_viz_scene test/viz/test_viz_scene.cpp
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  add_dependencies(test_viz_scene ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
  target_include_directories(test_viz_scene PRIVATE ${catkin_INCLUDE_DIRS})
  if(TARGET gtest_main)
    target_link_libraries(test_viz_scene bearing_sim_viz bearing_sim_core ${catkin_LIBRARIES} gtest_main)
  else()
    target_link_libraries(test_viz_scene bearing_sim_viz bearing_sim_core ${catkin_LIBRARIES} ${GTEST_MAIN_LIBRARIES})
  endif()
  target_compile_definitions(test_viz_scene PRIVATE BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  bearing_sim_optimize(test_viz_scene)

  # Stand-in for bearing_sim_node in the rostest and for screenshots without it.
  add_executable(viz_fake_ball_loads_publisher test/viz/fake_ball_loads_publisher.cpp)
  add_dependencies(viz_fake_ball_loads_publisher ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
  target_include_directories(viz_fake_ball_loads_publisher PRIVATE ${catkin_INCLUDE_DIRS})
  target_link_libraries(viz_fake_ball_loads_publisher bearing_sim_core ${catkin_LIBRARIES})
  bearing_sim_optimize(viz_fake_ball_loads_publisher)
  set_target_properties(viz_fake_ball_loads_publisher PROPERTIES
    RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})

  # The node against the fake publisher: TF, ring speed, sphere count, colours, load zone.
  find_package(rostest REQUIRED)
  add_rostest_gtest(test_viz_node test/viz/viz_node.test test/viz/test_viz_node.cpp)
  add_dependencies(test_viz_node bearing_viz_node viz_fake_ball_loads_publisher
    ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
  target_include_directories(test_viz_node PRIVATE ${catkin_INCLUDE_DIRS})
  target_link_libraries(test_viz_node bearing_sim_viz bearing_sim_core ${catkin_LIBRARIES})
  target_compile_definitions(test_viz_node PRIVATE BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  bearing_sim_optimize(test_viz_node)
endif()
