"""launch/ and rviz/, read (Python AST, XML, YAML) and held against the node they start: its
executable, parameters, topics, QoS and frame. These run everywhere; `ros2 launch` itself
runs them in tests/test_ros2_tools.py where the real ros2 tools are installed (RViz is not:
it is no dependency of the package)."""
import ast
from pathlib import Path
import re
import xml.etree.ElementTree as ET

import yaml

from scene_synth_ros.node import NODE_NAME
from scene_synth_ros.ros_client import LATCHED, TOPICS
from scene_synth_ros.server import PARAMETERS, ServerConfig

ROOT = Path(__file__).resolve().parent.parent
ARGUMENTS = {'room_type', 'params_file', 'use_sim_time', 'namespace', 'marker_style', 'rviz',
             'lifecycle_manager'}
SHARE = '$(find-pkg-share scene_synth_ros)/'
RVIZ_TOPICS = [f'/{NODE_NAME}/markers', f'/{NODE_NAME}/poses']


# ---- the Python launch file, read as a syntax tree ------------------------------------------
def _launch_py(name: str = 'scene_synth.launch.py'):
    return ast.parse((ROOT / 'launch' / name).read_text())


def _name(call: ast.Call) -> str:
    return call.func.attr if isinstance(call.func, ast.Attribute) else call.func.id


def _calls(tree, name: str) -> list[ast.Call]:
    return [n for n in ast.walk(tree) if isinstance(n, ast.Call) and _name(n) == name]


def _kw(call: ast.Call, name: str):
    return next((k.value for k in call.keywords if k.arg == name), None)


def _each(call: ast.Call, name: str) -> list:
    """The elements of a list given as keyword name; none without it."""
    value = _kw(call, name)
    return [] if value is None else value.elts


def _text(node, names) -> str:
    """A value of the launch file written as the XML frontend would write it."""
    if isinstance(node, ast.Name):
        return _text(names[node.id], names)
    if isinstance(node, ast.Constant):
        return node.value
    if _name(node) == 'FindPackageShare':
        return f'$(find-pkg-share {_text(node.args[0], names)})'
    if _name(node) == 'PathJoinSubstitution':
        return '/'.join(_text(e, names) for e in node.args[0].elts)
    assert _name(node) == 'LaunchConfiguration', ast.dump(node)
    return f'$(var {_text(node.args[0], names)})'


def _arguments_in(node, names) -> set[str]:
    """The launch arguments a value is made of."""
    if isinstance(node, ast.Name):
        node = names[node.id]
    return {_text(c.args[0], names) for c in _calls(node, 'LaunchConfiguration')}


def _py(name: str = 'scene_synth.launch.py'):
    """What the .py declares, starts and includes, in plain values."""
    tree = _launch_py(name)
    names = {t.id: a.value for a in ast.walk(tree) if isinstance(a, ast.Assign)
             for t in a.targets if isinstance(t, ast.Name)}
    args = {_text(c.args[0], names): c for c in _calls(tree, 'DeclareLaunchArgument')}
    nodes = {}
    for call in _calls(tree, 'Node'):
        params = _each(call, 'parameters')
        condition = _kw(call, 'condition')
        nodes[_text(_kw(call, 'package'), names)] = {
            'exec': _text(_kw(call, 'executable'), names),
            'name': _text(_kw(call, 'name'), names) if _kw(call, 'name') else None,
            'namespace': _text(_kw(call, 'namespace'), names),
            'files': [_text(p, names) for p in params if not isinstance(p, ast.Dict)],
            'order': ['dict' if isinstance(p, ast.Dict) else 'file' for p in params],
            'params': {_text(k, names): _arguments_in(v, names)
                       for p in params if isinstance(p, ast.Dict)
                       for k, v in zip(p.keys, p.values, strict=True)},
            'if': None if condition is None else _text(condition.args[0], names),
            'args': [_text(a, names) for a in _each(call, 'arguments')],
            'remaps': [tuple(_text(e, names) for e in r.elts)
                       for r in _each(call, 'remappings')],
        }
    return {
        'defaults': {n: _text(_kw(c, 'default_value'), names) for n, c in args.items()},
        'descriptions': {n: _text(_kw(c, 'description'), names) for n, c in args.items()},
        'choices': {n: [e.value for e in _kw(c, 'choices').elts]
                    for n, c in args.items() if _kw(c, 'choices')},
        'used': {_text(c.args[0], names) for c in _calls(tree, 'LaunchConfiguration')},
        'paths': {_text(c, names) for c in _calls(tree, 'PathJoinSubstitution')},
        'nodes': nodes,
        # included file -> {its argument: the launch arguments its value is made of}
        'includes': {_text(c.args[0].args[0], names): {
            _text(k, names): _arguments_in(v, names)
            for k, v in zip(_kw(c, 'launch_arguments').func.value.keys,
                            _kw(c, 'launch_arguments').func.value.values, strict=True)}
            for c in _calls(tree, 'IncludeLaunchDescription')},
    }


def _console_scripts() -> set[str]:
    tree = ast.parse((ROOT / 'setup.py').read_text())
    for d in (n for n in ast.walk(tree) if isinstance(n, ast.Dict)):
        for k, v in zip(d.keys, d.values, strict=True):
            if isinstance(k, ast.Constant) and k.value == 'console_scripts':
                return {e.value.split('=')[0].strip() for e in v.elts}
    raise AssertionError('setup.py has no console_scripts')


def test_python_launch_declares_exactly_the_arguments_it_uses_each_described():
    tree = _launch_py()
    assert any(isinstance(f, ast.FunctionDef) and f.name == 'generate_launch_description'
               for f in tree.body)
    py = _py()
    assert set(py['defaults']) == py['used'] == ARGUMENTS
    assert all(len(d) > 10 for d in py['descriptions'].values()), py['descriptions']
    assert set(py['choices']['marker_style']) == set(PARAMETERS['marker_style'][1])


def test_python_launch_starts_the_real_node_with_its_real_parameters():
    py = _py()
    node = py['nodes']['scene_synth_ros']
    assert node['exec'] == node['name'] == NODE_NAME
    assert node['exec'] in _console_scripts()
    assert node['namespace'] == '$(var namespace)'
    # The file first, the explicit arguments after it (the later value wins).
    assert node['files'] == ['$(var params_file)'] and node['order'] == ['file', 'dict']
    assert set(node['params']) <= set(PARAMETERS) | {'use_sim_time'}
    # Each parameter is set from the launch argument of its own name; autostart unless a
    # lifecycle manager starts it.
    assert node['params'] == {**{n: {n} for n in ('room_type', 'marker_style', 'use_sim_time')},
                              'autostart': {'lifecycle_manager'}}
    for path in py['paths']:
        assert path.startswith(SHARE) and (ROOT / path.removeprefix(SHARE)).is_file(), path
    assert py['defaults']['params_file'] == SHARE + 'config/scene_synth_node.yaml'


def test_launch_defaults_are_the_shipped_parameters():
    # A plain `ros2 launch` must furnish as `ros2 run ... --params-file` with the shipped
    # file does, although the explicit arguments override that file.
    shipped = yaml.safe_load((ROOT / 'config' / 'scene_synth_node.yaml').read_text())
    (params,) = [v['ros__parameters'] for v in shipped.values()]
    defaults = _py()['defaults']
    for name in ('room_type', 'marker_style'):
        assert defaults[name] == params[name] == getattr(ServerConfig(), name)
    assert defaults['use_sim_time'] == 'false' and defaults['rviz'] == 'false'
    assert defaults['namespace'] == ''


def test_python_launch_starts_rviz_only_when_asked_with_the_shipped_config():
    # Both launch files include rviz.launch.py (and lifecycle_manager.launch.py), passing
    # the three arguments each reads.
    passed = {n: {n} for n in ('rviz', 'namespace', 'use_sim_time')}
    assert _py()['includes'] == {
        SHARE + 'launch/rviz.launch.py': passed,
        SHARE + 'launch/lifecycle_manager.launch.py': {
            n: {n} for n in ('lifecycle_manager', 'namespace', 'use_sim_time')}}
    managed = _py('lifecycle_manager.launch.py')
    assert set(managed['defaults']) == managed['used'] == {'lifecycle_manager', 'namespace',
                                                           'use_sim_time'}
    rviz_launch = _py('rviz.launch.py')
    assert set(rviz_launch['defaults']) == rviz_launch['used'] == set(passed)
    (only_if,) = _calls(_launch_py('rviz.launch.py'), 'OpaqueFunction')
    assert _text(_kw(only_if, 'condition').args[0], {}) == '$(var rviz)'
    rviz = rviz_launch['nodes']['rviz2']
    assert rviz['exec'] == 'rviz2'
    assert rviz['args'] == ['-d', SHARE + 'rviz/scene_synth.rviz']
    assert rviz['namespace'] == '$(var namespace)'
    assert rviz['params'] == {'use_sim_time': {'use_sim_time'}}
    # The config's absolute topics made relative, so RViz follows the node's namespace.
    assert rviz['remaps'] == [(t, t.lstrip('/')) for t in RVIZ_TOPICS]


# ---- the XML twin -----------------------------------------------------------------------------
def test_xml_launch_is_the_twin_of_the_python_one():
    root = ET.parse(ROOT / 'launch' / 'scene_synth.launch.xml').getroot()
    assert root.tag == 'launch'
    py = _py()
    args = root.findall('arg')
    assert {a.get('name'): a.get('default') for a in args} == py['defaults']
    assert all(len(a.get('description', '')) > 10 for a in args)
    assert {a.get('name'): [c.get('value') for c in a.findall('choice')]
            for a in args if a.findall('choice')} == py['choices']
    used = {v for e in root.iter() for a in e.attrib.values()
            for v in re.findall(r'\$\(var (\w+)\)', a)}
    assert used == ARGUMENTS

    includes = {i.get('file'): {a.get('name'): set(re.findall(r'\$\(var (\w+)\)',
                                                               a.get('value')))
                                for a in i.findall('arg')} for i in root.findall('include')}
    assert includes == py['includes']
    nodes = {n.get('pkg'): n for n in root.findall('node')}
    assert set(nodes) == set(py['nodes'])
    for pkg, node in nodes.items():
        want = py['nodes'][pkg]
        params = node.findall('param')
        assert [p.get('from') for p in params if p.get('from')] == want['files']
        assert {p.get('name'): set(re.findall(r'\$\(var (\w+)\)', p.get('value')))
                for p in params if p.get('name')} == want['params']
        # The same order of files and single parameters as in the .py.
        order = ['file' if p.get('from') else 'dict' for p in params]
        assert [k for i, k in enumerate(order) if order[i - 1:i] != [k]] == want['order']
        assert (node.get('exec'), node.get('name')) == (want['exec'], want['name'])
        assert node.get('namespace') == want['namespace']
        assert node.get('if') == want['if']
        # Words of args, a $(...) substitution being part of one word.
        assert re.findall(r'(?:\$\([^)]*\)|[^\s$])+', node.get('args', '')) == want['args']
        assert [(r.get('from'), r.get('to')) for r in node.findall('remap')] == want['remaps']


# ---- the RViz config ----------------------------------------------------------------------------
def _qos_name(policy) -> str:
    return policy.name.replace('_', ' ').title()     # TRANSIENT_LOCAL -> Transient Local


def test_rviz_config_shows_the_node_outputs_with_the_node_qos_in_its_frame():
    config = yaml.safe_load((ROOT / 'rviz' / 'scene_synth.rviz').read_text())
    assert {'Panels', 'Visualization Manager', 'Window Geometry'} <= set(config)
    manager = config['Visualization Manager']
    assert manager['Global Options']['Fixed Frame'] == ServerConfig().frame_id
    shown = {d['Topic']['Value']: d for d in manager['Displays'] if 'Topic' in d}
    assert set(shown) == set(RVIZ_TOPICS)
    for topic in RVIZ_TOPICS:
        display = shown[topic]
        kind = topic.rsplit('/', 1)[1]
        assert display['Class'] == 'rviz_default_plugins/' + TOPICS[kind].__name__
        assert display['Enabled'] is True
        qos = display['Topic']
        assert qos['Depth'] == LATCHED.depth
        assert qos['History Policy'] == _qos_name(LATCHED.history)
        assert qos['Reliability Policy'] == _qos_name(LATCHED.reliability) == 'Reliable'
        assert qos['Durability Policy'] == _qos_name(LATCHED.durability) == 'Transient Local'
