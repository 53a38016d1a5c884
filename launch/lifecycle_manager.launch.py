"""nav2's lifecycle manager for scene_synth_node, when asked and when it is installed.

Included by scene_synth.launch.py and scene_synth.launch.xml (lifecycle_manager:=true,
which also starts the node with autostart false): the manager configures and activates
the node, and deactivates, cleans up and shuts it down with the rest of a nav2 stack.
Without nav2 it says so in one line; the node then waits, unconfigured, for
`ros2 lifecycle set`.
"""
from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, LogInfo, OpaqueFunction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def _manager_if_installed(context):
    namespace = LaunchConfiguration('namespace').perform(context)
    node = '/'.join(p for p in (namespace.strip('/'), 'scene_synth_node') if p)
    try:
        get_package_share_directory('nav2_lifecycle_manager')
    except PackageNotFoundError:
        return [LogInfo(msg='lifecycle_manager:=true, but nav2_lifecycle_manager is not '
                            'installed: scene_synth_node waits unconfigured for '
                            f'`ros2 lifecycle set /{node} configure`, then activate')]
    return [Node(
        package='nav2_lifecycle_manager',
        executable='lifecycle_manager',
        name='lifecycle_manager_scene_synth',
        namespace=LaunchConfiguration('namespace'),
        output='screen',
        # The node keeps no bond with the manager: bond_timeout 0 turns the bond off.
        parameters=[{'autostart': True, 'node_names': ['scene_synth_node'],
                     'bond_timeout': 0.0,
                     'use_sim_time': LaunchConfiguration('use_sim_time')}],
    )]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('lifecycle_manager', default_value='false',
                              description="start nav2's lifecycle manager for the node"),
        DeclareLaunchArgument('namespace', default_value='',
                              description="namespace of the node; '' = the root namespace"),
        DeclareLaunchArgument('use_sim_time', default_value='false',
                              description='follow the simulation clock on /clock'),
        OpaqueFunction(function=_manager_if_installed,
                       condition=IfCondition(LaunchConfiguration('lifecycle_manager'))),
    ])
