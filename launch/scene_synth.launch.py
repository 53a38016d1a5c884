"""Start scene_synth_node, and RViz with the shipped view when asked.

    ros2 launch scene_synth_ros scene_synth.launch.py
    ros2 launch scene_synth_ros scene_synth.launch.py room_type:=office rviz:=true
    ros2 launch scene_synth_ros scene_synth.launch.py namespace:=sim use_sim_time:=true
    ros2 launch scene_synth_ros scene_synth.launch.py lifecycle_manager:=true
    ros2 launch scene_synth_ros scene_synth.launch.py --show-args

The parameters file is loaded first; room_type, marker_style, use_sim_time and autostart
(false under lifecycle_manager:=true) are set after it, so these arguments win over the file.
"""
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, NotSubstitution, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare('scene_synth_ros')
    namespace = LaunchConfiguration('namespace')
    use_sim_time = LaunchConfiguration('use_sim_time')

    arguments = [
        DeclareLaunchArgument(
            'room_type', default_value='bedroom',
            description='room type of layouts arriving on ~/room_polygon: bedroom, living, '
                        'office, bathroom, kitchen, dining or hallway (overrides params_file)'),
        DeclareLaunchArgument(
            'params_file',
            default_value=PathJoinSubstitution([share, 'config', 'scene_synth_node.yaml']),
            description='YAML file of node parameters, loaded before the other arguments'),
        DeclareLaunchArgument(
            'use_sim_time', default_value='false',
            description='follow the simulation clock on /clock (true) or the wall clock (false)'),
        DeclareLaunchArgument(
            'namespace', default_value='',
            description="namespace of the node (and of RViz); '' = the root namespace"),
        DeclareLaunchArgument(
            'marker_style', default_value='cube', choices=['cube', 'mesh'],
            description='objects drawn as boxes (cube) or catalog meshes (mesh) '
                        '(overrides params_file)'),
        DeclareLaunchArgument(
            'lifecycle_manager', default_value='false',
            description="start nav2's lifecycle manager, which configures and activates the "
                        'node (else it does so itself), where nav2 is installed'),
        DeclareLaunchArgument(
            'rviz', default_value='false',
            description='also start RViz with the shipped rviz/scene_synth.rviz, where '
                        'RViz is installed'),
    ]

    scene_synth = Node(
        package='scene_synth_ros',
        executable='scene_synth_node',
        name='scene_synth_node',
        namespace=namespace,
        output='screen',
        parameters=[
            LaunchConfiguration('params_file'),
            {
                # Strings stay strings whatever they look like to a YAML parser.
                'room_type': ParameterValue(LaunchConfiguration('room_type'), value_type=str),
                'marker_style': ParameterValue(LaunchConfiguration('marker_style'),
                                               value_type=str),
                'use_sim_time': use_sim_time,
                'autostart': NotSubstitution(LaunchConfiguration('lifecycle_manager')),
            },
        ],
    )

    # nav2's lifecycle manager where it is installed: lifecycle_manager.launch.py.
    manager = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(PathJoinSubstitution([share, 'launch',
                                                            'lifecycle_manager.launch.py'])),
        launch_arguments={'lifecycle_manager': LaunchConfiguration('lifecycle_manager'),
                          'namespace': namespace, 'use_sim_time': use_sim_time}.items(),
    )

    # RViz where it is installed (it is no dependency of the package): rviz.launch.py.
    rviz = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(PathJoinSubstitution([share, 'launch',
                                                            'rviz.launch.py'])),
        launch_arguments={'rviz': LaunchConfiguration('rviz'), 'namespace': namespace,
                          'use_sim_time': use_sim_time}.items(),
    )

    return LaunchDescription([*arguments, scene_synth, manager, rviz])
