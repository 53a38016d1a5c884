"""``scene-synth ros ...``: the node's clients (publish a layout, call its services, echo its
topics, get and set its parameters) and the node demo, on rclpy."""
from __future__ import annotations

import json
import os
from pathlib import Path
import random
import signal
import time

from .common import WEIGHTS_DIR_HELP, UserError, object_table, write_scene

DEMO_NODE_START_TIMEOUT = 90.0


def add_parser(sub) -> None:
    ros = sub.add_parser('ros', help='talk to a running scene_synth_node without the ros2 '
                         'tools, or run the node demo')
    ros.add_argument('--node', default='/scene_synth_node', help='the node to talk to')
    ros.add_argument('--domain-id', type=int,
                     help='ROS domain (default: $ROS_DOMAIN_ID, else 0)')
    ros.add_argument('--timeout', type=float, default=60.0, help='seconds to wait for answers')
    rsub = ros.add_subparsers(dest='ros_command', required=True)

    c = rsub.add_parser('publish-layout', help='publish a room layout JSON and print the room '
                        'the node answers with')
    c.add_argument('layout')
    c.add_argument('--no-wait', action='store_true', help='publish and return')
    c.add_argument('--out', help='write the scene JSON here')
    c.add_argument('--png', help='write a top-down picture here')
    c.set_defaults(func=cmd_publish_layout)

    c = rsub.add_parser('next-object', help='insert one object into the current room')
    c.add_argument('--category', help='of this category (sets the parameter next_category; '
                   'without it the category module chooses)')
    c.set_defaults(func=cmd_service, service='next_object')
    c = rsub.add_parser('generate', help='furnish the current room again from empty')
    c.add_argument('--seed', type=int, help='with this seed (sets the parameter seed; '
                   'default: the node\'s next one)')
    c.set_defaults(func=cmd_service, service='generate')
    c = rsub.add_parser('suggest', help='print proposals for the next object; the room does '
                        'not change')
    c.add_argument('-k', type=int, help='how many (sets the parameter suggestions)')
    c.set_defaults(func=cmd_service, service='suggest')
    c = rsub.add_parser('reset', help='remove all objects from the current room')
    c.set_defaults(func=cmd_service, service='reset')

    c = rsub.add_parser('echo', help='print the latest message of a topic')
    c.add_argument('topic', choices=('scene', 'markers', 'poses', 'map', 'diagnostics'))
    c.add_argument('--count', type=int, default=1, help='messages to print (diagnostics: '
                   'one per second)')
    c.set_defaults(func=cmd_echo)

    c = rsub.add_parser('param', help='get or set node parameters')
    c.add_argument('action', choices=('get', 'set'))
    c.add_argument('name')
    c.add_argument('value', nargs='?', help='set: a YAML scalar (true, 3, 0.5, office)')
    c.set_defaults(func=cmd_param)

    c = rsub.add_parser('demo', help='start the node, furnish an example room, complete a '
                        'partial one object at a time, stop the node')
    c.add_argument('--out', default='demo_out')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.set_defaults(func=cmd_demo)


def _client(args):
    from ..ros_client import SceneSynthClient
    domain = args.domain_id
    if domain is None:
        domain = int(os.environ.get('ROS_DOMAIN_ID', '0') or 0)
    if not 0 <= domain <= 232:
        raise UserError(f'--domain-id must be between 0 and 232, got {domain}')
    return SceneSynthClient(args.node, domain)


def _show_scene(d: dict, out: str | None, png: str | None, title: str) -> None:
    """Print the node's room as a table, and write it where asked."""
    from ..schema import parse_scene
    scene = parse_scene(d)
    print(object_table(scene.objects, f'{scene.room.room_type}, {scene.room.area:.1f} m², '
                       f'{len(scene)} objects (seed {scene.meta.get("seed")})'))
    write_scene(scene, out, png, title)


def cmd_publish_layout(args) -> int:
    try:
        text = Path(args.layout).read_text(encoding='utf-8')
    except OSError as e:
        raise UserError(f'{args.layout}: {e.strerror}') from None
    with _client(args) as client:
        d = client.publish_layout(text, wait=not args.no_wait, timeout=args.timeout)
        if d is None:
            print(f'published {args.layout}')
            return 0
        _show_scene(d, args.out, args.png, Path(args.layout).stem)
    return 0


def cmd_service(args) -> int:
    from ..ros_client import ClientError
    with _client(args) as client:
        try:
            if args.service == 'next_object':
                answer = client.next_object(args.category, timeout=args.timeout)
            elif args.service == 'generate':
                answer = client.generate(args.seed, args.timeout)
            elif args.service == 'suggest':
                answer = {'objects': client.suggest(args.k, timeout=args.timeout)}
            else:
                answer = client.reset(args.timeout)
        except ClientError as e:
            raise UserError(str(e)) from None
    print(json.dumps(answer))
    return 0


def _wait_for_next(client, topic: str, timeout: float) -> None:
    """Spin until a message of ``topic`` newer than the latest one arrives."""
    seen = client.count(topic)
    client.spin_until(lambda: client.count(topic) > seen, timeout, topic)


def cmd_echo(args) -> int:
    from ..ros_client import format_map, format_markers, format_poses
    formats = {'scene': lambda msg: msg.data, 'markers': format_markers,
               'poses': format_poses, 'map': format_map}
    with _client(args) as client:
        for k in range(args.count):
            if k:
                _wait_for_next(client, args.topic, args.timeout)
            if args.topic == 'diagnostics':
                d = client.diagnostics(args.timeout)
                print('\n'.join(f'{name}: {value}' for name, value in d.items()))
                continue
            print(formats[args.topic](client.latest(args.topic, args.timeout)))
            if k + 1 < args.count:
                print('---')
    return 0


def cmd_param(args) -> int:
    import yaml
    with _client(args) as client:
        if args.action == 'get':
            values = client.get_parameters([args.name], args.timeout)
            print(f'{args.name}: {values[args.name]!r}')
            return 0
        if args.value is None:
            raise UserError('param set needs a value')
        value = yaml.safe_load(args.value)
        if value is None:
            value = ''
        current = client.get_parameters([args.name], args.timeout)
        if isinstance(current[args.name], float) and type(value) is int:
            value = float(value)        # `param set location_temperature 1` means 1.0
        refused = client.set_parameters({args.name: value}, args.timeout)
    if refused:
        raise UserError(f'the node refused {refused[0]}')
    print(f'{args.name} set to {value!r}')
    return 0


# ---- the demo -----------------------------------------------------------------------------
def _demo_layout(client, out: Path, timeout: float) -> None:
    """Publish the example bedroom layout and show the room the node furnishes."""
    from ..paths import examples_dir
    layout = examples_dir() / 'bedroom_layout.json'
    t = time.perf_counter()
    d = client.publish_layout(layout.read_text(), timeout=timeout)
    latency = time.perf_counter() - t
    markers = client.latest('markers')
    poses = client.latest('poses')
    print(f'\npublished {layout.name}; the room arrived after {latency:.2f} s '
          f'({len(markers.markers)} markers, {len(poses.poses)} poses)')
    _show_scene(d, str(out / 'ros_bedroom.json'), str(out / 'ros_bedroom.png'),
                f'{layout.stem} via scene_synth_node (seed {d["meta"]["seed"]})')


def _demo_next_object(client, out: Path, timeout: float) -> None:
    """Publish the example partial room unfurnished and ask the node for one more object."""
    from ..paths import examples_dir
    from ..scene import PlacedObject
    refused = client.set_parameters({'auto_generate': False})
    if refused:
        raise UserError(f'the node refused {refused[0]}')
    partial = examples_dir() / 'partial_bedroom.json'
    d = client.publish_layout(partial.read_text(), timeout=timeout)
    print(f'\nauto_generate set to false; published {partial.name} '
          f'({len(d["objects"])} objects); calling ~/next_object')
    before = client.count('scene')
    t = time.perf_counter()
    ok, message = client.call('next_object', timeout)
    if not ok:
        raise UserError(f'next_object refused: {message}')
    print(f'next_object answered in {time.perf_counter() - t:.2f} s:')
    print(object_table([PlacedObject.from_dict(json.loads(message))]))
    d = client.wait_scene(before, timeout)
    _show_scene(d, str(out / 'ros_partial_next.json'), str(out / 'ros_partial_next.png'),
                f'{partial.stem} + next_object via scene_synth_node')


def cmd_demo(args) -> int:
    """Start the node in a child process, publish an example layout, show the room, ask for
    one more object in a partial room, and stop the node with SIGINT."""
    from ..ros_client import ClientError, SceneSynthClient, start_node, stop_node
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    domain = args.domain_id
    if domain is None:      # a domain of its own, so the demo never meets someone's robots
        domain = random.Random(os.getpid()).randrange(100, 200)
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    log_path = out / 'node.log'
    params = {'weights_dir': args.weights_dir} if args.weights_dir else {}
    t0 = time.perf_counter()
    with open(log_path, 'w') as log:
        proc = start_node(domain, params, log)
    print(f'started scene_synth_node (pid {proc.pid}, ROS_DOMAIN_ID={domain}, log {log_path})')
    try:
        with SceneSynthClient(args.node, domain) as client:
            try:
                client.spin_until(lambda: proc.poll() is not None or client.ready(),
                                  DEMO_NODE_START_TIMEOUT, 'services')
                if proc.poll() is not None:
                    raise UserError(f'the node exited with code {proc.returncode} at start-up; '
                                    f'see {log_path}')
                print(f'node ready after {time.perf_counter() - t0:.1f} s')
                _demo_layout(client, out, args.timeout)
                _demo_next_object(client, out, args.timeout)
            except ClientError as e:
                # The node's log says why it did not answer; the client cannot.
                raise UserError(f'{e} (node log: {log_path})') from None
    finally:
        code = stop_node(proc, signal.SIGINT)
    print(f'\nstopped the node with SIGINT: exit code {code}')
    if code != 0:
        raise UserError(f'the node exited with code {code}; see {log_path}')
    return 0
