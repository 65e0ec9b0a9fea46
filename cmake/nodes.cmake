# ROS nodes (issue 3 onwards).
