"""The typed messages of ``scene_synth_msgs`` and the JSON forms of ``msg_schemas/``, each
into the other. The JSON forms are what the library parses and writes, so the node converts
here and the library never sees a message.

Like ``node.py`` this is an adapter: it imports ROS message types; the library does not.
"""
from __future__ import annotations

from array import array
import json
import math
from typing import Any

from geometry_msgs.msg import Point, Point32, Pose, Vector3
from nav_msgs.msg import OccupancyGrid as OccupancyGridMsg
from scene_synth_msgs.msg import (
    Door,
    HouseDoor,
    PlacedObject,
    Robot,
    RoomLayout,
    Scene,
    Window,
)


def yaw_quaternion(yaw: float) -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation by ``yaw`` about +z."""
    return 0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)


def quaternion_yaw(q) -> float:
    """The rotation about +z of quaternion ``q`` (its heading; a tilt is dropped). The
    all-zero quaternion of a message left unset reads as yaw 0."""
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def occupancy_message(grid, frame_id: str, stamp) -> OccupancyGridMsg:
    """``grid`` (``occupancy.OccupancyGrid``) as nav_msgs/OccupancyGrid: rows from the
    origin's, row-major, 100 occupied, 0 free, -1 unknown, as map_server publishes a map."""
    msg = OccupancyGridMsg()
    msg.header.frame_id, msg.header.stamp = frame_id, stamp
    msg.info.map_load_time = stamp
    msg.info.resolution = float(grid.resolution)
    msg.info.width, msg.info.height = grid.width, grid.height
    msg.info.origin = pose((grid.origin[0], grid.origin[1], 0.0), 0.0)
    # an array of int8 is taken whole; a list would be checked value by value
    msg.data = array('b', grid.data.tobytes())
    return msg


def pose(position, yaw: float) -> Pose:
    p = Pose()
    p.position.x, p.position.y, p.position.z = (float(v) for v in position)
    (p.orientation.x, p.orientation.y, p.orientation.z,
     p.orientation.w) = yaw_quaternion(float(yaw))
    return p


# ---- messages -> the JSON forms the library parses ------------------------------------------
def object_dict(msg: PlacedObject) -> dict[str, Any]:
    """A ``placed_object.schema.json`` object of ``msg``; empty id and model id are left for
    the parser to fill, an empty support is none (the object stands on the floor)."""
    p = msg.pose.position
    d: dict[str, Any] = {'category': msg.category, 'position': [p.x, p.y, p.z],
                         'yaw': quaternion_yaw(msg.pose.orientation),
                         'size': [msg.size.x, msg.size.y, msg.size.z]}
    for key, value in (('id', msg.id), ('model_id', msg.model_id), ('support', msg.support)):
        if value:
            d[key] = value
    return d


def layout_dict(msg: RoomLayout) -> dict[str, Any]:
    """A ``room_layout.schema.json`` layout of ``msg`` (its ``id`` is a house's: a single
    room has none)."""
    d: dict[str, Any] = {
        'room_type': msg.room_type,
        'floor': [[p.x, p.y] for p in msg.floor.points],
        'doors': [{'position': [o.position.x, o.position.y], 'width': o.width,
                   'height': o.height} for o in msg.doors],
        'windows': [{'position': [o.position.x, o.position.y], 'width': o.width,
                     'height': o.height, 'sill': o.sill} for o in msg.windows]}
    if msg.wall_height:
        d['wall_height'] = msg.wall_height
    if msg.objects:
        d['objects'] = [object_dict(o) for o in msg.objects]
    if msg.request_id:
        d['request_id'] = msg.request_id
    return d


def robot_radius_reach_clearance(msg: Robot) -> tuple[float, float, float] | None:
    """The robot a goal states, or None when it is left all zero (the node's own)."""
    values = (msg.radius, msg.reach, msg.clearance)
    return None if not any(values) else values


# ---- the JSON forms the library writes -> messages -------------------------------------------
def object_msg(d: dict[str, Any], room: str = '') -> PlacedObject:
    """The message of a ``placed_object.schema.json`` object."""
    return PlacedObject(id=d.get('id', ''), category=d['category'],
                        model_id=d.get('model_id', ''), pose=pose(d['position'], d['yaw']),
                        size=Vector3(x=float(d['size'][0]), y=float(d['size'][1]),
                                     z=float(d['size'][2])),
                        support=d.get('support') or '', room=room)


def room_msg(d: dict[str, Any]) -> RoomLayout:
    """The message of a scene's ``room`` (a layout without objects)."""
    msg = RoomLayout(room_type=d['room_type'], wall_height=float(d.get('wall_height', 0.0)))
    msg.floor.points = [Point32(x=float(x), y=float(y), z=0.0) for x, y in d['floor']]
    msg.doors = [door_msg(o) for o in d.get('doors', ())]
    msg.windows = [Window(position=Point(x=float(o['position'][0]),
                                         y=float(o['position'][1])),
                          width=float(o['width']), height=float(o['height']),
                          sill=float(o['sill'])) for o in d.get('windows', ())]
    return msg


def door_msg(d: dict[str, Any]) -> Door:
    return Door(position=Point(x=float(d['position'][0]), y=float(d['position'][1])),
                width=float(d['width']), height=float(d['height']))


def house_door_msg(d: dict[str, Any]) -> HouseDoor:
    """The message of a house's door (``house_layout.schema.json``): ``room_b`` empty for
    an entrance."""
    rooms = list(d['rooms']) + ['']
    return HouseDoor(room_a=rooms[0], room_b=rooms[1], door=door_msg(d))


def scene_msg(scene_json: str, frame_id: str, stamp) -> Scene:
    """The message of a scene as published on ``~/scene``: a room's
    (``scene.schema.json``) or a house's (``house_scene.schema.json``: every room with its
    id, the doors between them, each object naming its room)."""
    d = json.loads(scene_json)
    meta = dict(d.get('meta', {}))
    seed = meta.pop('seed', None)
    if 'rooms' in d:
        rooms, objects = [], []
        for r in d['rooms']:
            msg = room_msg(r)
            msg.id = r['id']
            rooms.append(msg)
            objects += [object_msg(o, r['id']) for o in r.get('objects', ())]
        doors = [house_door_msg(dd) for dd in d.get('doors', ())]
    else:
        rooms, doors = [room_msg(d['room'])], []
        objects = [object_msg(o) for o in d.get('objects', ())]
    msg = Scene(rooms=rooms, doors=doors, objects=objects,
                seed=-1 if seed is None else int(seed),
                meta_json=json.dumps(meta, separators=(',', ':')))
    msg.header.frame_id, msg.header.stamp = frame_id, stamp
    return msg
