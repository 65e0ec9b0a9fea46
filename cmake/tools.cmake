find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)

add_executable(bearing_tool
  src/tools/bearing_tool_main.cpp
)
target_link_libraries(bearing_tool PRIVATE bearing_sim_core CLI11::CLI11 nlohmann_json::nlohmann_json)
bearing_sim_optimize(bearing_tool)
set_target_properties(bearing_tool PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS bearing_tool RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
