# Live recording: record.launch runs scripts/record_bag; its rostest.
install(PROGRAMS scripts/record_bag DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
if(CATKIN_ENABLE_TESTING)
  # Real time with rosbag record: the bag has every sample and every topic at its rate (~20 s).
  bearing_sim_node_rostest(test_live_recording live_recording)
  add_dependencies(test_live_recording bearing_viz_node)
endif()
