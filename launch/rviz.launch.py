"""RViz with the shipped view of scene_synth_node, when asked and when it is installed.

Included by scene_synth.launch.py and scene_synth.launch.xml (rviz:=true); RViz is not a
dependency of the package, so headless images do not pull in the GUI stack. Without it,
rviz:=true says so in one line and starts nothing, and the node serves alone.
"""
from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, LogInfo, OpaqueFunction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def _rviz_if_installed(context):
    try:
        get_package_share_directory('rviz2')
    except PackageNotFoundError:
        return [LogInfo(msg='rviz:=true, but RViz (the package rviz2) is not installed: '
                            'scene_synth_node runs without it (install ros-jazzy-rviz2 to '
                            'see the room)')]
    namespace = LaunchConfiguration('namespace')
    # The .rviz file names the node's topics absolutely; remapping them to relative names
    # makes RViz, started in the same namespace, follow the node into it (and changes
    # nothing in the root namespace). No name= here: it would rename every node RViz runs.
    return [Node(
        package='rviz2',
        executable='rviz2',
        namespace=namespace,
        output='screen',
        arguments=['-d', PathJoinSubstitution([FindPackageShare('scene_synth_ros'), 'rviz',
                                               'scene_synth.rviz'])],
        parameters=[{'use_sim_time': LaunchConfiguration('use_sim_time')}],
        remappings=[('/scene_synth_node/markers', 'scene_synth_node/markers'),
                    ('/scene_synth_node/poses', 'scene_synth_node/poses')],
    )]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('rviz', default_value='false',
                              description='start RViz with the shipped rviz/scene_synth.rviz'),
        DeclareLaunchArgument('namespace', default_value='',
                              description="namespace of RViz; '' = the root namespace"),
        DeclareLaunchArgument('use_sim_time', default_value='false',
                              description='follow the simulation clock on /clock'),
        OpaqueFunction(function=_rviz_if_installed,
                       condition=IfCondition(LaunchConfiguration('rviz'))),
    ])
