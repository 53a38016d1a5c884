"""The input-limits gate and the bounded error sentences: each input of the hardening
campaign that killed or wedged the node (issue 12) is now refused in one sentence, or
accepted in a form that everything downstream can use."""
import json
import math

import pytest

from scene_synth_ros import limits
from scene_synth_ros.errors import MAX_SENTENCE, SceneSynthError, quoted, sentence
from scene_synth_ros.export import export_gltf
from scene_synth_ros.markers import scene_markers
from scene_synth_ros.scene import ccw
from scene_synth_ros.schema import (
    SceneValidationError,
    _schemas,
    dump_scene,
    parse_room_layout,
    parse_scene,
)

SQUARE = [[0, 0], [4, 0], [4, 4], [0, 4]]


def _nested(depth, leaf=0):
    for _ in range(depth):
        leaf = [leaf]
    return leaf


def _meta(depth):
    m = {}
    for _ in range(depth):
        m = {'a': m}
    return m


REFUSED = {
    'a key that is a lone surrogate': (
        '{"\\ud800": 1, "room_type": "bedroom", "floor": %s}' % json.dumps(SQUARE),
        "'\\ud800'", 'not a known field'),
    'an integer of 4,301 digits in text': (
        '{"room_type": "bedroom", "floor": %s, "wall_height": 1%s}'
        % (json.dumps(SQUARE), '0' * 4301), '', 'at most 1000 are read'),
    'an integer of 4,301 digits in a dict': (
        {'room_type': 'bedroom', 'floor': SQUARE, 'wall_height': 10 ** 4301},
        'wall_height', 'about 4302 digits'),
    'JSON nested 975 deep': (
        '{"room_type": "bedroom", "floor": ' + '[' * 975 + ']' * 975 + '}',
        None, 'nested'),      # json's own depth guard or ours, whichever comes first
    'a dict nested 975 deep': (
        {'room_type': 'bedroom', 'floor': _nested(975)}, 'floor' + '[0]' * 31,
        'nested more than 32 levels'),
    'a finite but huge coordinate': (
        {'room_type': 'bedroom', 'floor': [[1e308, 0], [4, 0], [4, 4], [0, 4]]},
        'floor[0][0]', 'at most 100000 m'),
    'a room 1e9 m from the origin': (
        {'room_type': 'bedroom', 'floor': [[1e9 + x, 1e9 + y] for x, y in SQUARE]},
        None, 'at most 100000 m'),
    'a 7 MB payload': (
        json.dumps({'room_type': 'x' * 7_000_000, 'floor': SQUARE}), '',
        'at most 1048576 are read'),
    'a long room type': ({'room_type': 'x' * 3000, 'floor': SQUARE}, 'room_type',
                         'at most 128 characters'),
    'a 10,000-vertex outline': (
        {'room_type': 'bedroom', 'floor': [[2 + 2 * math.cos(k / 1591.5),
                                            2 + 2 * math.sin(k / 1591.5)]
                                           for k in range(10_000)]},
        '', 'more than 20000 values'),
    'a 300-vertex outline': (
        {'room_type': 'bedroom', 'floor': [[2 + 2 * math.cos(k / 47.75),
                                            2 + 2 * math.sin(k / 47.75)] for k in range(300)]},
        'floor', 'at most 256 vertices'),
    'a ring closed twice, nearly': (
        {'room_type': 'bedroom', 'floor': SQUARE + [[0.0005, 0], [0, 0]]}, 'floor[4]',
        'repeats the first vertex'),
}


@pytest.mark.parametrize('payload,path,words', REFUSED.values(), ids=list(REFUSED))
def test_inputs_that_killed_the_node_are_refused_in_one_sentence(payload, path, words):
    with pytest.raises(SceneValidationError) as e:
        parse_room_layout(payload)
    text = str(e.value)
    if path is not None:
        assert e.value.path == path, (e.value.path, text)
    assert words in text
    assert len(text) <= MAX_SENTENCE and text.isprintable()
    text.encode('utf-8')


def test_a_scene_with_deep_meta_is_refused_and_what_is_accepted_can_be_written():
    deep = {'room': {'room_type': 'bedroom', 'floor': SQUARE}, 'meta': _meta(500)}
    with pytest.raises(SceneValidationError, match='nested more than 32'):
        parse_scene(json.dumps(deep))
    ok = {'room': {'room_type': 'bedroom', 'floor': SQUARE}, 'meta': _meta(30)}
    scene = parse_scene(ok)
    assert parse_scene(dump_scene(scene)).meta == scene.meta


@pytest.mark.parametrize('closing', [[0.0005, 0], [0, 0.0009], [0, 0]])
def test_a_nearly_closing_vertex_is_dropped_so_the_room_has_no_sliver_wall(closing):
    scene = parse_room_layout({'room_type': 'bedroom', 'floor': SQUARE + [closing]})
    assert len(scene.room.floor) == 4
    assert min(w.length for w in scene.room.walls) > 3.9
    assert scene_markers(scene, 'cube')                # GEOS triangulated the floor
    assert parse_scene(dump_scene(scene)).room.floor == scene.room.floor


def test_winding_is_found_far_from_the_origin():
    for off in (0.0, 1e4, 1e5, 1e9):
        square = [(off + x, off + y) for x, y in [(0, 0), (4, 0), (4, 4), (0, 4)]]
        for given in (square, square[::-1]):
            pts = ccw(given)
            area2 = sum((x0 - off) * (y1 - off) - (x1 - off) * (y0 - off)
                        for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1], strict=True))
            assert area2 == 32.0, (off, given)


def test_accepted_rooms_far_from_the_origin_are_served(tmp_path):
    far = [[9.9e4 + x, -9.9e4 + y] for x, y in SQUARE]
    scene = parse_room_layout({'room_type': 'bedroom', 'floor': far,
                               'doors': [{'position': [9.9e4 + 2, -9.9e4], 'width': 0.9,
                                          'height': 2.0}]})
    assert scene_markers(scene, 'cube')
    export_gltf(scene, tmp_path / 'far.glb')
    assert parse_scene(dump_scene(scene)).room.floor == scene.room.floor


def test_sentences_are_one_bounded_printable_line():
    assert sentence('two\nlines\t and  spaces') == 'two lines and spaces'
    assert sentence('a\ud800b\x00c') == 'a\ufffdb\ufffdc'
    long = sentence('x' * 10_000_000)
    assert len(long) == MAX_SENTENCE and long.endswith('…')
    assert quoted('y' * 5000) == repr('y' * 40) + '…'
    assert quoted('short') == "'short'"
    # Every error of the package goes through it, whatever the caller passed.
    e = SceneSynthError('bad \ud800 input\n' + 'z' * 1000)
    assert str(e).isprintable() and len(str(e)) == MAX_SENTENCE


def test_check_tree_reads_any_depth_without_recursing():
    with pytest.raises(limits.LimitExceeded) as e:
        limits.check_tree({'meta': _meta(100_000)})
    assert e.value.path == 'meta' + '.a' * 31
    limits.check_tree({'meta': _meta(30)})      # 32 levels with the document's own
    with pytest.raises(limits.LimitExceeded, match='more than'):
        limits.check_tree([0] * (limits.MAX_NODES + 1))


def test_the_schemas_carry_the_counts_of_limits():
    layout = _schemas()['room_layout']
    defs = layout['$defs']
    assert defs['floor']['maxItems'] == limits.MAX_FLOOR_VERTICES
    assert defs['doors']['maxItems'] == defs['windows']['maxItems'] == limits.MAX_OPENINGS
    assert layout['properties']['objects']['maxItems'] == limits.MAX_OBJECTS
    assert _schemas()['scene']['properties']['objects']['maxItems'] == limits.MAX_OBJECTS
    for item in defs['point2']['prefixItems']:
        assert item['maximum'] == -item['minimum'] == limits.MAX_COORDINATE
