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

# ===================== BEGIN nodelets and node parameters =====================
# Parameter readers of the three nodes, the nodelet libraries (nodelet_plugins.xml), the
# install of nodelet_plugins.xml and config/nodes, and the parameters' gtest. The parts that
# use bearing_sim_viz, bearing_viz_node, bearing_sim_lcm_ros and lcm_bridge run at the end of
# the directory (cmake_language(DEFER)), so they hold whatever the order of the includes;
# without the LCM targets (LCM off) there is no LCM bridge nodelet.
find_package(nodelet REQUIRED)
find_package(pluginlib REQUIRED)

# Every node's read_*_parameters(): checks without a ROS master (only XmlRpcValue).
add_library(bearing_sim_node_parameters STATIC
  src/ros/parameter_reader.cpp
  src/ros/sim_node_parameters.cpp
  src/ros/lcm_bridge_parameters.cpp
  src/viz/viz_parameters.cpp)
target_include_directories(bearing_sim_node_parameters PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include ${catkin_INCLUDE_DIRS})
target_link_libraries(bearing_sim_node_parameters PUBLIC bearing_sim_core ${catkin_LIBRARIES})
bearing_sim_optimize(bearing_sim_node_parameters)
# Linked into the nodelets' shared libraries too.
set_target_properties(bearing_sim_node_parameters bearing_sim_ros_helpers PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(bearing_sim_node bearing_sim_node_parameters)

function(bearing_sim_add_nodelets)
  set(_nodelet_includes ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION} ${catkin_INCLUDE_DIRS}
      ${nodelet_INCLUDE_DIRS} ${pluginlib_INCLUDE_DIRS})
  set(_nodelet_libraries ${catkin_LIBRARIES} ${nodelet_LIBRARIES} ${pluginlib_LIBRARIES} Threads::Threads)
  target_link_libraries(bearing_viz_node bearing_sim_node_parameters)
  set_target_properties(bearing_sim_viz PROPERTIES POSITION_INDEPENDENT_CODE ON)
  # The simulation and the display (the same sources as their standalone nodes).
  add_library(bearing_sim_nodelets SHARED
    src/nodelets/bearing_sim_nodelet.cpp
    src/nodelets/viz_nodelet.cpp
    src/ros/bearing_sim_ros.cpp
    src/ros/message_conversion.cpp
    src/ros/node_diagnostics.cpp
    src/viz/viz_node.cpp)
  add_dependencies(bearing_sim_nodelets ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
  target_include_directories(bearing_sim_nodelets PRIVATE ${_nodelet_includes})
  target_link_libraries(bearing_sim_nodelets bearing_sim_node_parameters bearing_sim_ros_helpers bearing_sim_viz
    bearing_sim_core ${_nodelet_libraries})
  bearing_sim_optimize(bearing_sim_nodelets)
  install(TARGETS bearing_sim_nodelets LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  if(TARGET bearing_sim_lcm_ros AND TARGET lcm_bridge)
    target_link_libraries(lcm_bridge bearing_sim_node_parameters)
    set_target_properties(bearing_sim_lcm_ros PROPERTIES POSITION_INDEPENDENT_CODE ON)
    add_library(bearing_sim_lcm_nodelet SHARED src/nodelets/lcm_bridge_nodelet.cpp src/ros/lcm_bridge.cpp)
    add_dependencies(bearing_sim_lcm_nodelet ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})
    target_include_directories(bearing_sim_lcm_nodelet PRIVATE ${_nodelet_includes})
    target_link_libraries(bearing_sim_lcm_nodelet bearing_sim_node_parameters bearing_sim_lcm_ros ${_nodelet_libraries})
    bearing_sim_optimize(bearing_sim_lcm_nodelet)
    install(TARGETS bearing_sim_lcm_nodelet LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
  endif()
endfunction()
cmake_language(DEFER CALL bearing_sim_add_nodelets)

install(FILES nodelet_plugins.xml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
install(DIRECTORY config/nodes DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/config)

if(CATKIN_ENABLE_TESTING)
  # Every node's parameter reader: shipped files accepted as written, each bad key named.
  catkin_add_gtest(test_node_parameters test/ros/test_node_parameters.cpp TIMEOUT 60)
  if(TARGET gtest_main)
    target_link_libraries(test_node_parameters bearing_sim_node_parameters yaml-cpp gtest_main)
  else()
    target_link_libraries(test_node_parameters bearing_sim_node_parameters yaml-cpp ${GTEST_MAIN_LIBRARIES})
  endif()
  target_compile_definitions(test_node_parameters PRIVATE BEARING_SIM_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  bearing_sim_optimize(test_node_parameters)
endif()
# ====================== END nodelets and node parameters ======================
