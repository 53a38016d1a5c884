"""scene_synth_ros: indoor scene synthesis (Ritchie, Wang, Lin, CVPR 2019) for ROS 2.

The core library has no ROS import; ``scene_synth_ros.node`` is the only module that
imports rclpy.
"""
__version__ = '0.1.0'
