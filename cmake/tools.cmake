# bearing_tool: the command-line front end (src/tools), built into the devel space so
# that `rosrun bearing_sim bearing_tool` finds it. One source file per subcommand.
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)

add_executable(bearing_tool
  src/tools/bearing_tool_main.cpp
  src/tools/tool_common.cpp
  src/tools/command_static.cpp
  src/tools/command_frequencies.cpp
  src/tools/command_simulate.cpp
  src/tools/command_analyze.cpp
  src/tools/command_sweep.cpp
  src/tools/command_modes.cpp
  src/tools/command_generate.cpp
  src/tools/scenario_simulation.cpp
  src/tools/dataset_info_json.cpp
  src/tools/dataset_bag_writer.cpp
  src/tools/dataset_plain_writer.cpp
  src/tools/npy_file.cpp
  src/tools/job_size.cpp
  src/ros/message_conversion.cpp
)
target_link_libraries(bearing_tool PRIVATE bearing_sim_core CLI11::CLI11 nlohmann_json::nlohmann_json)
# generate: rosbags without a ROS master (rosbag_storage and the generated messages), and
# the node's ROS-free helpers (chunking, sensor, health).
find_package(rosbag_storage REQUIRED)
find_package(roscpp_serialization REQUIRED)
find_package(rostime REQUIRED)
find_package(Threads REQUIRED)
target_include_directories(bearing_tool PRIVATE ${catkin_INCLUDE_DIRS} ${rosbag_storage_INCLUDE_DIRS}
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_link_libraries(bearing_tool PRIVATE bearing_sim_ros_helpers ${rosbag_storage_LIBRARIES}
  ${roscpp_serialization_LIBRARIES} ${rostime_LIBRARIES} Threads::Threads)
add_dependencies(bearing_tool ${${PROJECT_NAME}_EXPORTED_TARGETS})
bearing_sim_optimize(bearing_tool)
set_target_properties(bearing_tool PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS bearing_tool RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  # Runs the built binary and parses its JSON; compares with the core library directly.
  catkin_add_gtest(test_bearing_tool test/tools/test_bearing_tool.cpp
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} TIMEOUT 600)
  target_link_libraries(test_bearing_tool bearing_sim_core nlohmann_json::nlohmann_json)
  target_compile_definitions(test_bearing_tool PRIVATE
    BEARING_TOOL_PATH="$<TARGET_FILE:bearing_tool>"
    BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  add_dependencies(test_bearing_tool bearing_tool)
  bearing_sim_optimize(test_bearing_tool)
  # bearing_tool analyze on a simulate --csv file, against the core library.
  catkin_add_gtest(test_bearing_tool_analyze test/tools/test_bearing_tool_analyze.cpp
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} TIMEOUT 600)
  target_link_libraries(test_bearing_tool_analyze bearing_sim_core nlohmann_json::nlohmann_json)
  target_compile_definitions(test_bearing_tool_analyze PRIVATE BEARING_TOOL_PATH="$<TARGET_FILE:bearing_tool>")
  add_dependencies(test_bearing_tool_analyze bearing_tool)
  bearing_sim_optimize(test_bearing_tool_analyze)
endif()

if(CATKIN_ENABLE_TESTING)
  # bearing_tool generate: reads the bags back with rosbag::View, and the NPY/CSV/JSON files.
  catkin_add_gtest(test_bearing_tool_generate test/tools/test_bearing_tool_generate.cpp
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} TIMEOUT 600)
  target_include_directories(test_bearing_tool_generate PRIVATE ${catkin_INCLUDE_DIRS} ${rosbag_storage_INCLUDE_DIRS}
    ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
  target_link_libraries(test_bearing_tool_generate nlohmann_json::nlohmann_json ${rosbag_storage_LIBRARIES}
    ${roscpp_serialization_LIBRARIES} ${rostime_LIBRARIES})
  target_compile_definitions(test_bearing_tool_generate PRIVATE BEARING_TOOL_PATH="$<TARGET_FILE:bearing_tool>"
    BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  add_dependencies(test_bearing_tool_generate bearing_tool ${${PROJECT_NAME}_EXPORTED_TARGETS})
endif()

if(CATKIN_ENABLE_TESTING)
  # bearing_tool fed bad files, bad options and absurd runs: exit 2 naming the cause.
  catkin_add_gtest(test_bearing_tool_inputs test/tools/test_bearing_tool_inputs.cpp
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} TIMEOUT 600)
  target_compile_definitions(test_bearing_tool_inputs PRIVATE BEARING_TOOL_PATH="$<TARGET_FILE:bearing_tool>"
    BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  add_dependencies(test_bearing_tool_inputs bearing_tool)
endif()
