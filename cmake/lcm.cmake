# LCM: the message types in lcm/ generated at build time with lcm-gen, the
# lcm_bridge node, the consumer example and their tests. LCM 1.3 ships no CMake config:
# pkg-config.
find_package(PkgConfig REQUIRED)
pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm)
find_program(LCM_GEN_EXECUTABLE lcm-gen REQUIRED)

set(BEARING_SIM_LCM_TYPES header_t vibration_chunk_t vibration_level_t ball_loads_t envelope_line_t
    defect_state_t bearing_health_t)
set(BEARING_SIM_LCM_GEN_DIR ${CMAKE_CURRENT_BINARY_DIR}/lcm_gen)
set(_lcm_sources "")
set(_lcm_headers "")
foreach(type ${BEARING_SIM_LCM_TYPES})
  list(APPEND _lcm_sources ${CMAKE_CURRENT_SOURCE_DIR}/lcm/${type}.lcm)
  list(APPEND _lcm_headers ${BEARING_SIM_LCM_GEN_DIR}/bearing_sim_lcm/${type}.hpp)
endforeach()
add_custom_command(
  OUTPUT ${_lcm_headers}
  COMMAND ${LCM_GEN_EXECUTABLE} --cpp --cpp-std c++11 --cpp-hpath ${BEARING_SIM_LCM_GEN_DIR} ${_lcm_sources}
  DEPENDS ${_lcm_sources}
  COMMENT "lcm-gen: C++ headers of the bearing_sim_lcm types"
  VERBATIM)
add_custom_target(bearing_sim_lcm_gen DEPENDS ${_lcm_headers})

# The generated headers and liblcm; linking it orders the generation first.
add_library(bearing_sim_lcm_types INTERFACE)
target_include_directories(bearing_sim_lcm_types INTERFACE ${BEARING_SIM_LCM_GEN_DIR})
target_link_libraries(bearing_sim_lcm_types INTERFACE PkgConfig::LCM)
add_dependencies(bearing_sim_lcm_types bearing_sim_lcm_gen)
install(DIRECTORY lcm/ DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/lcm FILES_MATCHING PATTERN "*.lcm")

# ROS -> LCM conversions and the publishing queue (no ROS master needed).
add_library(bearing_sim_lcm_ros STATIC src/ros/lcm_conversion.cpp src/ros/lcm_publish_queue.cpp)
add_dependencies(bearing_sim_lcm_ros ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
target_include_directories(bearing_sim_lcm_ros PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS}
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
target_link_libraries(bearing_sim_lcm_ros PUBLIC bearing_sim_lcm_types ${catkin_LIBRARIES} Threads::Threads)
bearing_sim_optimize(bearing_sim_lcm_ros)

add_executable(lcm_bridge src/nodes/lcm_bridge_node.cpp src/ros/lcm_bridge.cpp)
target_link_libraries(lcm_bridge bearing_sim_lcm_ros ${catkin_LIBRARIES})
bearing_sim_optimize(lcm_bridge)
set_target_properties(lcm_bridge PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS lcm_bridge RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# A consumer that knows nothing of ROS: L and RMS per second from the vibration channel.
add_executable(lcm_consumer_example examples/lcm_consumer.cpp)
target_link_libraries(lcm_consumer_example bearing_sim_lcm_types bearing_sim_core CLI11::CLI11)
bearing_sim_optimize(lcm_consumer_example)
set_target_properties(lcm_consumer_example PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
install(TARGETS lcm_consumer_example RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  # Conversions and LCM round trips (memq://, file:// logs), bit-exact; no ROS master.
  catkin_add_gtest(test_lcm_conversion test/ros/test_lcm_conversion.cpp TIMEOUT 300)
  if(TARGET gtest_main)  # catkin's gtest does not bring main()
    target_link_libraries(test_lcm_conversion bearing_sim_lcm_ros gtest_main)
  else()
    target_link_libraries(test_lcm_conversion bearing_sim_lcm_ros ${GTEST_MAIN_LIBRARIES})
  endif()
  bearing_sim_optimize(test_lcm_conversion)

  # bearing_sim_node (fast mode) + lcm_bridge writing a log, against what ROS delivered.
  find_package(rostest REQUIRED)
  add_rostest_gtest(test_lcm_bridge test/ros/lcm_bridge.test test/ros/test_lcm_bridge.cpp)
  add_dependencies(test_lcm_bridge bearing_sim_node lcm_bridge)
  target_link_libraries(test_lcm_bridge bearing_sim_lcm_ros ${catkin_LIBRARIES})
  bearing_sim_optimize(test_lcm_bridge)
endif()

# Per-message cost of the bridge's conversion and encoding.
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_lcm_bridge bench/bench_lcm_bridge.cpp)
  target_link_libraries(bench_lcm_bridge PRIVATE bearing_sim_lcm_ros benchmark::benchmark)
  bearing_sim_optimize(bench_lcm_bridge)
endif()

if(CATKIN_ENABLE_TESTING)
  # The consumer example on a log of a known sine: RMS, L, timing, gap report.
  catkin_add_gtest(test_lcm_consumer test/tools/test_lcm_consumer.cpp TIMEOUT 120)
  if(TARGET gtest_main)
    target_link_libraries(test_lcm_consumer bearing_sim_lcm_ros gtest_main)
  else()
    target_link_libraries(test_lcm_consumer bearing_sim_lcm_ros ${GTEST_MAIN_LIBRARIES})
  endif()
  target_compile_definitions(test_lcm_consumer PRIVATE LCM_CONSUMER_PATH="$<TARGET_FILE:lcm_consumer_example>")
  add_dependencies(test_lcm_consumer lcm_consumer_example)
  bearing_sim_optimize(test_lcm_consumer)
endif()
