"""The validity checks themselves must catch each kind of fault."""
import math

from scene_synth_ros import geometry
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene

ROOM = Room('bedroom', ((0, 0), (4, 0), (4, 3), (0, 3)), 2.6,
            (Opening('door', (1.0, 0.0), 0.9, 2.05), Opening('door', (4.0, 2.2), 0.8, 2.05)))


def obj(oid, cat, x, y, w, d, h=0.8, yaw=0.0, z=0.0, support=None):
    return PlacedObject(oid, cat, 'm', (x, y, z), yaw, (w, d, h), support)


def test_empty_room_is_valid():
    assert geometry.check_scene(Scene(ROOM)).ok


def test_overlap_beyond_one_centimetre_is_a_collision():
    a = obj('a', 'dresser', 2.0, 1.5, 1.0, 0.5)                  # depth along x: 1.75..2.25
    touching = obj('b', 'dresser', 2.5, 1.5, 1.0, 0.5)           # shares an edge
    slight = obj('b', 'dresser', 2.492, 1.5, 1.0, 0.5)           # 8 mm into a
    deep = obj('b', 'dresser', 2.45, 1.5, 1.0, 0.5)              # 5 cm into a
    assert geometry.collisions(Scene(ROOM, [a, touching])) == []
    assert geometry.collisions(Scene(ROOM, [a, slight])) == []
    assert geometry.collisions(Scene(ROOM, [a, deep])) == [('a', 'b')]


def test_second_tier_objects_do_not_collide_with_their_parent():
    table = obj('t', 'desk', 2.0, 1.5, 1.2, 0.6, h=0.75)
    lamp = obj('l', 'table lamp', 2.0, 1.5, 0.3, 0.3, z=0.75, support='t')
    assert geometry.check_scene(Scene(ROOM, [table, lamp])).ok


def test_leaving_the_floor_is_caught_with_a_rotated_footprint():
    # turned a quarter, the 1 m width runs along x: x 3.0..4.0, flush with the wall
    inside = obj('a', 'dresser', 3.5, 1.5, 1.0, 0.5, yaw=math.pi / 2)
    assert geometry.off_floor(Scene(ROOM, [inside])) == []
    out = obj('a', 'dresser', 3.8, 1.5, 1.0, 0.6)                       # x 3.5..4.1
    assert geometry.off_floor(Scene(ROOM, [out])) == ['a']


def test_door_zone_must_stay_clear():
    blocker = obj('a', 'dresser', 1.0, 0.5, 1.0, 0.4)
    assert geometry.blocked_doors(Scene(ROOM, [blocker])) == [0]
    aside = obj('a', 'dresser', 3.0, 0.3, 1.0, 0.4)
    assert geometry.blocked_doors(Scene(ROOM, [aside])) == []


def test_second_tier_needs_seventy_percent_on_its_parent():
    stand = obj('s', 'stand', 2.0, 1.5, 0.5, 0.4, h=0.5)
    on = obj('l', 'table lamp', 2.0, 1.5, 0.3, 0.3, z=0.5, support='s')
    hanging = obj('l', 'table lamp', 2.2, 1.5, 0.3, 0.3, z=0.5, support='s')   # x 2.05..2.35
    floating = obj('l', 'table lamp', 2.0, 1.5, 0.3, 0.3, z=0.9, support='s')
    assert geometry.under_supported(Scene(ROOM, [stand, on])) == []
    assert geometry.support_fraction(hanging, stand) < 0.7
    assert geometry.under_supported(Scene(ROOM, [stand, hanging])) == ['l']
    assert geometry.under_supported(Scene(ROOM, [stand, floating])) == ['l']


def test_a_wall_of_furniture_disconnects_the_doors():
    # wardrobes across the room from y=0.9 to y=1.5, from wall to wall but a 0.3 m gap
    left = obj('a', 'wardrobe', 1.35, 1.2, 0.6, 2.7, yaw=0.0)
    right = obj('b', 'wardrobe', 3.5, 1.2, 0.6, 1.0)
    scene = Scene(ROOM, [left, right])
    assert geometry.collisions(scene) == []
    assert not geometry.doors_connected(scene)          # 0.3 m gap < 0.4 m robot
    wider = Scene(ROOM, [left, obj('b', 'wardrobe', 3.7, 1.2, 0.6, 0.6)])
    assert geometry.doors_connected(wider)               # 0.7 m gap
    assert not geometry.check_scene(scene).ok
    assert 'not connected' in geometry.check_scene(scene).summary()
