"""Validated JSON reading/writing of room layouts and scenes (scene_synth_ros.schema)."""
import copy
import json
import math
import re

from jsonschema import Draft202012Validator
import pytest

from scene_synth_ros import catalog, schema
from scene_synth_ros.paths import examples_dir, schema_dir
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene
from scene_synth_ros.schema import SceneValidationError

BEDROOM = {
    'room_type': 'bedroom',
    'floor': [[0.0, 0.0], [4.2, 0.0], [4.2, 3.6], [0.0, 3.6]],
    'wall_height': 2.6,
    'doors': [{'position': [0.7, 0.0], 'width': 0.9, 'height': 2.05}],
    'windows': [{'position': [4.2, 1.8], 'width': 1.2, 'height': 1.2, 'sill': 0.9}],
}
HALF_PI = math.pi / 2


def bed(**kw):
    d = {'id': 'double_bed_0', 'category': 'double bed', 'model_id': 'double_bed_03',
         'position': [2.1, 2.5235, 0.0], 'yaw': -HALF_PI, 'size': [1.663, 2.153, 0.875]}
    d.update(kw)
    return d


def stand(**kw):
    d = {'id': 'stand_0', 'category': 'stand', 'model_id': 'stand_03',
         'position': [0.975, 3.392, 0.0], 'yaw': -HALF_PI, 'size': [0.487, 0.416, 0.488]}
    d.update(kw)
    return d


def lamp(**kw):
    d = {'id': 'table_lamp_0', 'category': 'table lamp', 'model_id': 'table_lamp_02',
         'position': [0.975, 3.392, 0.488], 'yaw': -HALF_PI, 'size': [0.3, 0.3, 0.45],
         'support': 'stand_0'}
    d.update(kw)
    return d


def without(d, *keys):
    return {k: v for k, v in d.items() if k not in keys}


def layout(**kw):
    d = copy.deepcopy(BEDROOM)
    d.update(kw)
    return d


def furnished(*objects, **kw):
    return layout(objects=list(objects), **kw)


def assert_one_sentence(err: SceneValidationError, path: str):
    msg = str(err)
    assert err.path == path, (err.path, msg)
    assert path in msg, msg
    assert '\n' not in msg and 'Traceback' not in msg, msg
    assert not re.search(r'[.!?]\s+[A-Z]', msg), f'more than one sentence: {msg}'
    assert 10 < len(msg) < 600, msg


# ----------------------------------------------------------------------------- schema files

def test_a_house_scenes_rooms_have_the_house_layouts_fields_and_their_objects():
    with open(schema_dir() / 'house_layout.schema.json', encoding='utf-8') as f:
        layout = json.load(f)
    with open(schema_dir() / 'house_scene.schema.json', encoding='utf-8') as f:
        scene = json.load(f)
    room = layout['$defs']['house_room']
    furnished = scene['$defs']['furnished_room']
    assert set(furnished['properties']) == set(room['properties']) | {'objects'}
    assert furnished['required'] == room['required']
    assert set(scene['properties']) == set(layout['properties']) | {'meta'}


@pytest.mark.parametrize('name', ['room_layout', 'placed_object', 'scene', 'house_layout',
                                  'house_scene'])
def test_schema_files_are_valid_2020_12(name):
    with open(schema_dir() / f'{name}.schema.json', encoding='utf-8') as f:
        doc = json.load(f)
    Draft202012Validator.check_schema(doc)
    assert doc['$schema'] == 'https://json-schema.org/draft/2020-12/schema'
    assert doc['$id'] == schema.SCHEMA_IDS[name]

    def walk(node, where):
        if isinstance(node, dict):
            for key, sub in node.get('properties', {}).items():
                assert sub.get('description'), f'{name}: {where}.properties.{key} undocumented'
            for i, sub in enumerate(node.get('prefixItems', [])):
                assert sub.get('description'), f'{name}: {where}.prefixItems[{i}] undocumented'
            for key, sub in node.items():
                walk(sub, f'{where}.{key}')
        elif isinstance(node, list):
            for i, sub in enumerate(node):
                walk(sub, f'{where}[{i}]')

    walk(doc, name)


def test_references_are_resolved_locally():
    validator = schema._validator('scene')
    assert validator.is_valid({'room': BEDROOM, 'objects': [bed()]})
    assert not validator.is_valid({'room': BEDROOM, 'objects': [dict(bed(), id=None)]})
    # a scene's room is a layout without objects; a layout may have objects
    assert not validator.is_valid({'room': furnished(bed())})
    assert schema._validator('room_layout').is_valid(furnished(bed()))


# ----------------------------------------------------------------------------- valid input

@pytest.mark.parametrize('name', ['bedroom_layout.json', 'lshaped_living_layout.json',
                                  'partial_bedroom.json'])
def test_example_files_parse(name):
    text = (examples_dir() / name).read_text(encoding='utf-8')
    scene = schema.parse_room_layout(text)
    assert scene.room.room_type in ('bedroom', 'living')
    assert scene.meta == {}
    for op in scene.room.openings:
        assert scene.room.wall_of(op) is not None
    assert schema.load_scene(examples_dir() / name).to_dict() == scene.to_dict()


def test_example_contents():
    bedroom = schema.load_scene(examples_dir() / 'bedroom_layout.json')
    x0, y0, x1, y1 = bedroom.room.bounds
    assert (x1 - x0, y1 - y0) == pytest.approx((4.2, 3.6))
    assert len(bedroom.room.doors) == 1 and len(bedroom.room.windows) == 1
    living = schema.load_scene(examples_dir() / 'lshaped_living_layout.json')
    assert living.room.room_type == 'living'            # alias 'living room' resolved
    assert living.room.area == pytest.approx(7 * 6 - 3 * 2.5)
    assert len(living.room.floor) == 6
    assert len(living.room.doors) == 2 and len(living.room.windows) == 2
    partial = schema.load_scene(examples_dir() / 'partial_bedroom.json')
    assert [o.category for o in partial] == ['double bed', 'stand']
    assert [o.id for o in partial] == ['double_bed_0', 'stand_0']   # stand's id assigned
    for o in partial:
        assert catalog.get(o.model_id).size == pytest.approx(o.size)


def test_layout_defaults_and_filled_in_fields():
    d = {'room_type': 'Living_Room', 'floor': [[0, 0], [0, 4], [5, 4], [5, 0]],  # clockwise
         'objects': [{'category': 'sofa', 'position': [2.5, 0.5, 0], 'yaw': HALF_PI,
                      'size': [2.0, 0.9, 0.85]},
                     {'category': 'sofa', 'position': [2.5, 3.5, 0], 'yaw': -HALF_PI,
                      'size': [2.0, 0.9, 0.85], 'id': 'sofa_0'}]}
    scene = schema.parse_room_layout(d)
    assert scene.room.room_type == 'living'
    assert scene.room.wall_height == 2.6
    assert scene.room.doors == () and scene.room.windows == ()
    assert scene.room.area == pytest.approx(20.0)
    assert [o.id for o in scene] == ['sofa_1', 'sofa_0']    # given ids are kept and avoided
    assert scene.objects[0].model_id == catalog.nearest('sofa', 2.0, 0.9).model_id
    assert scene.objects[0].support is None
    assert d['objects'][0].get('id') is None                  # input not modified


def test_supported_object_and_closed_ring_accepted():
    closed = layout(floor=BEDROOM['floor'] + [BEDROOM['floor'][0]])
    scene = schema.parse_room_layout(dict(closed, objects=[bed(), stand(), lamp()]))
    assert len(scene.room.floor) == 4
    assert scene.get('table_lamp_0').support == 'stand_0'
    assert [o.id for o in scene.children_of('stand_0')] == ['table_lamp_0']


def test_input_kinds():
    text = json.dumps(furnished(bed()))
    assert schema.parse_room_layout(text.encode()).to_dict() == \
        schema.parse_room_layout(text).to_dict()
    scene = schema.parse_room_layout(furnished(bed(position=(2.1, 2.5235, 0.0))))
    assert scene.objects[0].position == (2.1, 2.5235, 0.0)
    with pytest.raises(SceneValidationError) as e:
        schema.parse_room_layout(42)
    assert e.value.path == ''


# ----------------------------------------------------------------------------- bad input

def _mut(fn):
    d = layout()
    fn(d)
    return d


BAD_LAYOUTS = [
    # (case id, payload, expected path, words the message must contain)
    ('invalid json', '{"room_type": "bedroom", "floor": [[0, 0], [1, 0]', '',
     ['neither JSON', 'nor YAML', 'line 1', 'column 50']),
    # YAML's flow style allows the trailing comma, so this is read, and its floor refused.
    ('trailing comma', '{"room_type": "bedroom",\n "floor": [],\n}', 'floor',
     ['at least 3']),
    ('not an object', '[1, 2, 3]', '', ['must be an object', 'array']),
    ('missing floor', _mut(lambda d: d.pop('floor')), 'floor', ['required']),
    ('missing room type', _mut(lambda d: d.pop('room_type')), 'room_type', ['required']),
    ('missing door width', _mut(lambda d: d['doors'][0].pop('width')), 'doors[0].width',
     ['required']),
    ('floor wrong type', layout(floor='square'), 'floor', ['must be an array', 'string']),
    ('vertex wrong type', layout(floor=[[0, 0], [4, 'a'], [4, 3], [0, 3]]), 'floor[1][1]',
     ['must be a number', 'string']),
    ('boolean wall height', layout(wall_height=True), 'wall_height', ['number', 'boolean']),
    ('vertex with 3 coordinates', layout(floor=[[0, 0], [4, 0, 0], [4, 3], [0, 3]]),
     'floor[1]', ['exactly 2']),
    ('NaN literal', json.dumps(furnished(bed(size=[1.6, float('nan'), 0.9]))),
     'objects[0].size[1]', ['finite', 'NaN']),
    ('Infinity literal', '{"room_type": "bedroom", "floor": [[0, 0], [Infinity, 0], [4, 3]]}',
     'floor[1][0]', ['finite', 'Infinity']),
    ('-Infinity wall height', layout(wall_height=float('-inf')), 'wall_height',
     ['-Infinity']),
    ('NaN in a dict', layout(doors=[{'position': [0.7, 0.0], 'width': float('nan'),
                                     'height': 2.05}]), 'doors[0].width', ['NaN']),
    ('bow tie', layout(floor=[[0, 0], [4, 3], [4, 0], [0, 3]], doors=[], windows=[]),
     'floor', ['self-intersecting', '(2, 1.5)']),
    ('two vertices', layout(floor=[[0, 0], [4, 0]]), 'floor', ['at least 3 vertices', 'got 2']),
    ('huge integer', '{"room_type": "bedroom", "floor": [[0, 0], [1%s, 0], [4, 3]]}' % ('0' * 400),
     'floor[1][0]', ['finite']),
    ('two distinct vertices', layout(floor=[[0, 0], [4, 0], [0, 0]]), 'floor',
     ['3 distinct', 'got 2']),
    ('collinear', layout(floor=[[0, 0], [2, 0], [4, 0]], doors=[], windows=[]), 'floor',
     ['zero area', 'one line']),
    ('repeated vertex', layout(floor=[[0, 0], [4.2, 0], [4.2, 0], [4.2, 3.6], [0, 3.6]]),
     'floor[2]', ['repeats the previous vertex']),
    ('tiny floor', layout(floor=[[0, 0], [1, 0], [1, 1], [0, 1]], doors=[], windows=[]),
     'floor', ['1 m²', 'minimum']),
    ('too long', layout(floor=[[0, 0], [16.5, 0], [16.5, 3], [0, 3]]), 'floor',
     ['16.5 m x 3 m', 'longer than the 16 m', 'bedroom']),
    ('wall too low', layout(wall_height=1.2), 'wall_height', ['at least 1.8 m', '1.2']),
    ('wall too high', layout(wall_height=7), 'wall_height', ['at most 6 m']),
    ('unknown room type', layout(room_type='garage'), 'room_type',
     ["'garage'", 'not a known room type']),
    ('door in the middle of the room',
     layout(doors=[{'position': [2.1, 0.42], 'width': 0.9, 'height': 2.05}]), 'doors[0]',
     ['not on any wall', '0.42 m from the nearest wall']),
    ('door wider than its wall',
     layout(floor=[[0, 0], [3, 0], [3, 1.2], [4, 1.2], [4, 3], [0, 3]],
            doors=[{'position': [3, 0.6], 'width': 1.6, 'height': 2.05}], windows=[]),
     'doors[0]', ['wider (1.6 m)', '1.2 m long']),
    ('door past the corner',
     layout(doors=[{'position': [0.2, 0.0], 'width': 0.9, 'height': 2.05}]), 'doors[0]',
     ['past the end']),
    ('absurd door width',
     layout(doors=[{'position': [2.1, 0.0], 'width': 0.1, 'height': 2.05}]),
     'doors[0].width', ['greater than 0.3 m', 'got 0.1 m']),
    ('door taller than the wall',
     layout(doors=[{'position': [0.7, 0.0], 'width': 0.9, 'height': 2.8}]), 'doors[0]',
     ['above the 2.6 m wall height']),
    ('window above the wall',
     layout(windows=[{'position': [4.2, 1.8], 'width': 1.2, 'height': 1.2, 'sill': 1.6}]),
     'windows[0]', ['2.8 m', 'sill 1.6 m', 'wall height']),
    ('window without sill',
     layout(windows=[{'position': [4.2, 1.8], 'width': 1.2, 'height': 1.2}]),
     'windows[0].sill', ['required']),
    ('overlapping openings',
     layout(windows=[{'position': [1.2, 0.0], 'width': 1.0, 'height': 1.0, 'sill': 1.0}]),
     'windows[0]', ['overlaps doors[0]', '0.45 m']),
    ('extra field', layout(ceiling='flat'), 'ceiling', ['not a known field']),
    ('extra field in a door',
     layout(doors=[{'position': [0.7, 0.0], 'width': 0.9, 'height': 2.05, 'swing': 'in'}]),
     'doors[0].swing', ['not a known field']),
    ('extra field in an object', furnished(bed(colour='red')), 'objects[0].colour',
     ['not a known field']),
    ('object missing yaw', furnished(without(bed(), 'yaw')),
     'objects[0].yaw', ['required']),
    ('unknown category', furnished(without(bed(category='spaceship'), 'model_id')),
     'objects[0].category', ["'spaceship'", 'not a known category']),
    ('category of another room type',
     furnished(without(bed(category='toilet', size=[0.4, 0.7, 0.8]), 'model_id')),
     'objects[0].category', ["'toilet'", 'not a category of a bedroom']),
    ('absurd object size', furnished(bed(size=[5.0, 2.1, 0.9])), 'objects[0].size',
     ['not plausible for a double bed', 'width 5 m']),
    ('negative size', furnished(bed(size=[1.6, -2.0, 0.9])), 'objects[0].size[1]',
     ['greater than 0 m', '-2']),
    ('position with 2 coordinates', furnished(bed(position=[2.1, 2.5])),
     'objects[0].position', ['exactly 3', 'got 2']),
    ('object outside the floor', furnished(bed(position=[2.1, 4.1, 0.0])),
     'objects[0].position', ['outside the floor', '0.5 m']),
    ('object below the floor', furnished(bed(position=[2.1, 2.5, -0.5])),
     'objects[0].position[2]', ['below the floor']),
    ('unknown model id', furnished(bed(model_id='double_bed_99')), 'objects[0].model_id',
     ["'double_bed_99'", 'not a catalog model']),
    ('model of another category', furnished(bed(model_id='stand_03')), 'objects[0].model_id',
     ['stand model']),
    ('duplicate ids', furnished(bed(), stand(id='double_bed_0')), 'objects[1].id',
     ["'double_bed_0'", 'objects[0]']),
    ('bad support id', furnished(bed(), stand(), lamp(support='stand_7')),
     'objects[2].support', ["'stand_7'", 'not the id of any object']),
    ('lamp on a wardrobe',
     furnished(bed(), {'id': 'wardrobe_0', 'category': 'wardrobe',
                       'position': [3.9, 1.2, 0.0], 'yaw': math.pi, 'size': [1.2, 0.6, 2.0]},
               lamp(support='wardrobe_0', position=[3.9, 1.2, 2.0])),
     'objects[2].support', ['wardrobe', 'cannot hold a table lamp', 'stand']),
    ('first tier with a support', furnished(bed(), stand(support='double_bed_0')),
     'objects[1].support', ['must be absent', 'first tier']),
    ('second tier without support', furnished(stand(), lamp(support=None)),
     'objects[1].support', ['required', 'table lamp']),
    ('support is itself', furnished(lamp(id='x', support='x')), 'objects[0].support',
     ['itself']),
    ('empty id', furnished(bed(id='')), 'objects[0].id', ['must not be empty']),
]


@pytest.mark.parametrize('payload,path,words', [c[1:] for c in BAD_LAYOUTS],
                         ids=[c[0] for c in BAD_LAYOUTS])
def test_bad_layouts_are_rejected(payload, path, words):
    with pytest.raises(SceneValidationError) as e:
        schema.parse_room_layout(payload)
    assert isinstance(e.value, ValueError)
    if path:
        assert_one_sentence(e.value, path)
    else:
        assert e.value.path == ''
        assert '\n' not in str(e.value)
    for w in words:
        assert w in str(e.value), str(e.value)
    if not isinstance(payload, str):   # validate_layout_dict agrees with the parser
        with pytest.raises(SceneValidationError) as e2:
            schema.validate_layout_dict(payload)
        assert e2.value.path == e.value.path


def test_bad_layout_table_is_big_enough():
    assert len(BAD_LAYOUTS) >= 20


BAD_SCENES = [
    ('missing room', {'objects': []}, 'room', ['required']),
    ('objects inside the room', {'room': furnished(bed())}, 'room.objects',
     ['not a known field']),
    ('object without id', {'room': BEDROOM, 'objects': [dict(bed(), id=None)]},
     'objects[0].id', ['must be a string', 'null']),
    ('object without model id', {'room': BEDROOM, 'objects': [without(bed(), 'model_id')]},
     'objects[0].model_id', ['required']),
    ('meta not an object', {'room': BEDROOM, 'objects': [], 'meta': [1]}, 'meta',
     ['must be an object']),
    ('NaN in meta', {'room': BEDROOM, 'objects': [], 'meta': {'score': float('nan')}},
     'meta.score', ['NaN']),
    ('vertex of the room', {'room': layout(floor=[[0, 0], [4, 0], [4, 0], [0, 3]])},
     'room.floor[2]', ['repeats']),
    ('door of the room', {'room': layout(doors=[{'position': [2.0, 1.0], 'width': 0.9,
                                                 'height': 2.0}])},
     'room.doors[0]', ['not on any wall']),
    ('room type of the room', {'room': layout(room_type='garage')}, 'room.room_type',
     ['garage']),
    ('extra top-level field', {'room': BEDROOM, 'objects': [], 'seed': 3}, 'seed',
     ['not a known field']),
]


@pytest.mark.parametrize('payload,path,words', [c[1:] for c in BAD_SCENES],
                         ids=[c[0] for c in BAD_SCENES])
def test_bad_scenes_are_rejected(payload, path, words):
    with pytest.raises(SceneValidationError) as e:
        schema.parse_scene(json.dumps(payload))
    assert_one_sentence(e.value, path)
    for w in words:
        assert w in str(e.value), str(e.value)
    with pytest.raises(SceneValidationError):
        schema.validate_scene_dict(payload)


def test_error_is_picklable():
    import pickle
    err = pickle.loads(pickle.dumps(SceneValidationError('objects[0].id is bad', 'objects[0].id')))
    assert (str(err), err.path) == ('objects[0].id is bad', 'objects[0].id')


# ----------------------------------------------------------------------------- writing

def _l_shaped_scene() -> Scene:
    room = Room('living', ((0.0, 0.0), (7.0, 0.0), (7.0, 3.5), (4.0, 3.5), (4.0, 6.0),
                           (0.0, 6.0)), 2.7,
                (Opening('door', (1.0, 0.0), 0.9, 2.1), Opening('door', (4.0, 4.75), 1.4, 2.1)),
                (Opening('window', (7.0, 1.75), 1.6, 1.4, 0.8),
                 Opening('window', (2.0, 6.0), 1.8, 1.4, 0.8)))
    objects = [
        PlacedObject('sofa_0', 'sofa', 'sofa_03', (0.45, 3.0, 0.0), 0.0, (2.1, 0.9, 0.85)),
        PlacedObject('coffee_table_0', 'coffee table', 'coffee_table_01',
                     (1.6 + 1e-9, 3.0, 0.0), 0.1 + 0.2, (1.1, 0.6, 0.4)),
        PlacedObject('plant_0', 'plant', 'plant_00', (1.6, 3.1, 0.4), -2.5,
                     (0.2, 0.2, 0.4), 'coffee_table_0'),
    ]
    return Scene(room, objects, {'seed': 1234, 'generator': 'test', 'timing_s': 0.123456789,
                                 'nested': {'list': [1, 2.5, 'x', None, True]}})


def test_round_trip_l_shaped_room():
    scene = _l_shaped_scene()
    text = schema.dump_scene(scene)
    back = schema.parse_scene(text)
    assert json.loads(schema.dump_scene(back)) == json.loads(text) == scene.to_dict()
    assert back.meta == scene.meta
    assert back.get('plant_0').support == 'coffee_table_0'
    assert back.get('coffee_table_0').position[0] == 1.6 + 1e-9   # floats exact
    assert len(back.room.doors) == 2 and len(back.room.windows) == 2
    assert back.room == scene.room


def test_round_trip_rectangular_room(tmp_path):
    scene = schema.parse_room_layout(furnished(bed(), stand(), lamp()))
    scene.meta = {'seed': 7}
    path = tmp_path / 'scene.json'
    schema.save_scene(scene, path)
    assert not (tmp_path / 'scene.json.tmp').exists()
    back = schema.load_scene(path)
    assert json.loads(path.read_text()) == json.loads(schema.dump_scene(back))
    assert back.to_dict() == scene.to_dict()
    # a second trip changes nothing either
    assert schema.dump_scene(schema.parse_scene(schema.dump_scene(back))) == \
        schema.dump_scene(back)


def test_empty_meta_and_no_objects_round_trip():
    scene = schema.parse_room_layout(BEDROOM)
    text = schema.dump_scene(scene)
    assert json.loads(text) == {'room': BEDROOM, 'objects': []}
    assert schema.parse_scene(text).to_dict() == scene.to_dict()


def test_dump_validates():
    scene = schema.parse_room_layout(furnished(bed()))
    scene.objects[0].size = (1.6, float('nan'), 0.9)
    with pytest.raises(SceneValidationError) as e:
        schema.dump_scene(scene)
    assert_one_sentence(e.value, 'objects[0].size[1]')
    scene = schema.parse_room_layout(furnished(bed()))
    scene.objects.append(PlacedObject('double_bed_0', 'double bed', 'double_bed_01',
                                      (2.0, 1.0, 0.0), 0.0, (1.5, 2.0, 0.9)))
    with pytest.raises(SceneValidationError) as e:
        schema.dump_scene(scene)
    assert_one_sentence(e.value, 'objects[1].id')
    scene = schema.parse_room_layout(BEDROOM)
    scene.meta = {'handle': object()}
    with pytest.raises(SceneValidationError) as e:
        schema.dump_scene(scene)
    assert e.value.path == 'meta' and '\n' not in str(e.value)


def test_dump_accepts_numpy_values():
    import numpy as np
    scene = schema.parse_room_layout(furnished(bed()))
    scene.objects[0].position = tuple(np.array([2.1, 2.5, 0.0]))
    scene.meta = {'seed': np.int64(3)}
    d = json.loads(schema.dump_scene(scene))
    assert d['objects'][0]['position'] == [2.1, 2.5, 0.0] and d['meta'] == {'seed': 3}


@pytest.mark.parametrize('degrees', [0, 17, 30, 45, 90])
@pytest.mark.parametrize('floor, fits', [
    ([[0, 0], [7.5, 0], [7.5, 3.8], [0, 3.8]], True),
    ([[0, 0], [15.8, 0], [15.8, 2.5], [2.8, 2.5], [2.8, 4.5], [0, 4.5]], True),   # an L
    ([[0, 0], [16.3, 0], [16.3, 3.0], [0, 3.0]], False),
    ([[0, 0], [16.2, 0], [16.2, 2.5], [2.8, 2.5], [2.8, 4.5], [0, 4.5]], False),
], ids=['7.5x3.8', 'L-15.8x4.5', '16.3x3', 'L-16.2x4.5'])
def test_a_room_is_accepted_iff_it_fits_in_its_own_axes(floor, fits, degrees):
    """The 16 m bound on a room's longer side is measured along the room's walls, whatever
    way the room is turned (the networks see it in its own axes)."""
    a = math.radians(degrees)
    turned = [[x * math.cos(a) - y * math.sin(a) + 10, x * math.sin(a) + y * math.cos(a) - 3]
              for x, y in floor]
    layout = {'room_type': 'bedroom', 'floor': turned}
    if fits:
        assert len(schema.parse_room_layout(layout).room.floor) == len(floor)
    else:
        with pytest.raises(SceneValidationError, match=r'^floor is 16\.\d+ m x \d(\.\d+)? m '
                                                        r'along its walls, longer than the 16 m '
                                                        r'a bedroom may be along its longer side$'):
            schema.parse_room_layout(layout)


# ---- layouts as a person types them: YAML, and Python dicts -------------------------------
SQUARE_JSON = {'room_type': 'office', 'floor': [[0, 0], [4, 0], [4, 4], [0, 4]],
               'doors': [{'position': [2, 0], 'width': 0.9, 'height': 2.0}]}


@pytest.mark.parametrize('text', [
    # what `ros2 topic pub ... "data: '{room_type: office, ...}'"` delivers: YAML flow style
    "{room_type: office, floor: [[0, 0], [4, 0], [4, 4], [0, 4]], "
    "doors: [{position: [2, 0], width: 0.9, height: 2.0}]}",
    # block style, as in a file
    "room_type: office\nfloor:\n  - [0, 0]\n  - [4, 0]\n  - [4, 4]\n  - [0, 4]\n"
    "doors:\n  - {position: [2, 0], width: 0.9, height: 2}\n",
    # what an unquoted mapping arrives as: a Python dict's repr
    str(SQUARE_JSON),
])
def test_a_layout_may_be_yaml_or_a_python_dict(text):
    assert schema.parse_room_layout(text) == schema.parse_room_layout(json.dumps(SQUARE_JSON))


@pytest.mark.parametrize('text,words', [
    ("{'room_type': 'office', 'floor': [(0, 0), (4, 0), (4, 4)]}",
     ['must be an array, got string', "data: '{\"room_type\""]),
    ("{'room_type': None, 'floor': [[0, 0], [4, 0], [4, 4]]}",
     ['not a known room type', 'Python dict', 'single quotes']),
])
def test_a_python_dict_that_fails_says_how_to_quote_json(text, words):
    with pytest.raises(SceneValidationError) as e:
        schema.parse_room_layout(text)
    for w in words:
        assert w in str(e.value)


@pytest.mark.parametrize('text,words', [
    ('a: &x [1, 2]\nb: *x', ['aliases', 'line 2']),                 # expansion bombs
    ('room_type: office\nfloor: !!binary aGVsbG8=', ['floor is binary data']),
    ('{1: 2}', ['key that is not text']),
    ('a: ' + '1' * 5000, ['number too long']),
    ('[' * 900 + ']' * 900, ['nested']),
    ('room_type: office\nfloor: [[0, 0]]\n' + '#' * (70 << 10), ['YAML is read only up to']),
    ('{"room_type": "office", "floor": [[0, 0], [1, 0]', ['neither JSON', 'nor YAML',
                                                          'column 49']),
])
def test_yaml_is_read_within_bounds_and_refused_in_one_sentence(text, words):
    with pytest.raises(SceneValidationError) as e:
        schema.parse_room_layout(text)
    message = str(e.value)
    assert '\n' not in message and len(message) <= 400
    for w in words:
        assert w in message, message


def test_dates_stay_text_and_scenes_stay_json():
    # YAML would read 2026-11-25 as a date, which JSON has not: it stays the text.
    layout = dict(SQUARE_JSON, room_type='2026-11-25')
    with pytest.raises(SceneValidationError, match="'2026-11-25' is not a known room type"):
        schema.parse_room_layout(json.dumps(layout).replace('"2026-11-25"', '2026-11-25'))
    with pytest.raises(SceneValidationError, match='not valid JSON'):    # our own output
        schema.parse_scene('room: {}')


def test_a_request_id_is_kept_in_meta_and_checked():
    scene = schema.parse_room_layout(dict(SQUARE_JSON, request_id='job-7/a'))
    assert scene.meta == {'request_id': 'job-7/a'}
    assert schema.parse_room_layout(SQUARE_JSON).meta == {}
    for bad in ('', 'with space', 'x' * 129, 7):
        with pytest.raises(SceneValidationError, match='request_id'):
            schema.parse_room_layout(dict(SQUARE_JSON, request_id=bad))
