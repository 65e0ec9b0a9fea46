# ROS nodes. The ROS-free helpers (pacer, chunker, validator, ...) are a
find_package(Threads REQUIRED)
# separate library so that their gtests need no ROS master.
add_library(bearing_sim_ros_helpers STATIC
  src/ros/realtime_pacer.cpp
  src/ros/chunk_assembler.cpp
  src/ros/input_validator.cpp
  src/ros/sample_source.cpp
  src/ros/sample_divider.cpp
  src/ros/timing_stats.cpp
  src/ros/health_monitor.cpp
  src/ros/triaxial_sensor.cpp
  src/ros/sample_pipeline.cpp
)
target_include_directories(bearing_sim_ros_helpers PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(bearing_sim_ros_helpers PUBLIC bearing_sim_core)
bearing_sim_optimize(bearing_sim_ros_helpers)

include_directories(${catkin_INCLUDE_DIRS})
add_executable(bearing_sim_node
  src/nodes/bearing_sim_node.cpp
  src/ros/bearing_sim_ros.cpp
  src/ros/message_conversion.cpp
  src/ros/node_diagnostics.cpp
)
add_dependencies(bearing_sim_node ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
target_include_directories(bearing_sim_node PRIVATE ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_link_libraries(bearing_sim_node bearing_sim_ros_helpers bearing_sim_core ${catkin_LIBRARIES} Threads::Threads)
bearing_sim_optimize(bearing_sim_node)
set_target_properties(bearing_sim_node PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS bearing_sim_node RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
