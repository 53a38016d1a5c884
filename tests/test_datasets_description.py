"""The data-set description (datasets/description.py): derived from scenes by hand, read
back, enough to build the package's RoomTypeSpec, and every edit mistake a sentence."""
import pytest
import yaml

from scene_synth_ros.categories import CategoryInfo, RoomCategorySpec, RoomTypeSpec
from scene_synth_ros.datasets import ImportConfig, description
from scene_synth_ros.errors import DatasetError

FLOOR = [[0, 0], [4, 0], [4, 3], [0, 3]]


def o(oid, cat, x, y, z, yaw, size, support=None):
    d = {'id': oid, 'category': cat, 'model_id': 'm', 'position': [x, y, z], 'yaw': yaw,
         'size': size}
    if support:
        d['support'] = support
    return d


def scenes():
    a = {'room': {'room_type': 'bedroom', 'floor': FLOOR, 'doors': [
        {'position': [2, 0], 'width': 0.9, 'height': 2.1}], 'windows': []}, 'objects': [
        # back on the wall x = 0 (depth 2.0, centre 1.0): against it
        o('bed_0', 'bed', 1.0, 1.5, 0, 0.0, [1.6, 2.0, 1.0]),
        o('nightstand_0', 'nightstand', 0.2, 0.4, 0, 0.0, [0.4, 0.4, 0.5]),
        o('lamp_0', 'lamp', 0.2, 0.4, 0.5, 0.0, [0.2, 0.2, 0.4], 'nightstand_0'),
        o('ceiling_light_0', 'ceiling light', 2, 1.5, 2.4, 0.0, [0.5, 0.5, 0.2])]}
    b = {'room': {'room_type': 'bedroom', 'floor': FLOOR}, 'objects': [
        # front to the wall x = 4: its back 2 m from any wall
        o('bed_0', 'bed', 3.0, 1.5, 0, 0.0, [1.4, 2.0, 0.8])]}
    return [a, b]


def test_description_of_hand_made_rooms():
    d = description.describe(scenes(), 'test', ImportConfig())
    bedroom = d['room_types']['bedroom']
    assert bedroom['rooms'] == 2 and bedroom['size_cap'] == 6.0
    assert (bedroom['doors_per_room'], bedroom['windows_per_room']) == (0.5, 0.0)
    cats = bedroom['categories']
    assert list(cats)[0] == 'bed'                      # most frequent first
    bed = cats['bed']
    assert (bed['count'], bed['per_room'], bed['rooms_with'], bed['tier']) == (2, 1.0, 2, 'first')
    assert bed['width'] == {'min': 1.4, 'median': 1.5, 'max': 1.6}
    assert bed['height'] == {'min': 0.8, 'median': 0.9, 'max': 1.0}
    assert bed['importance'] == pytest.approx(1.5 * 2.0 * 1.0)
    assert not bed['against_wall']                     # one of two: not most
    assert cats['nightstand']['against_wall']
    lamp = cats['lamp']
    assert lamp['tier'] == 'second' and lamp['supported_by'] == {'nightstand': 1}
    assert cats['ceiling light']['tier'] == 'mounted'
    assert bedroom['importance_order'] == sorted(cats, key=lambda c: -cats[c]['importance'])


def test_written_description_loads_and_builds_a_room_type_spec(tmp_path):
    path = tmp_path / description.FILE_NAME
    description.write(description.describe(scenes(), 'test'), path)
    loaded = description.load(path)
    rt = loaded.room_types['bedroom']
    infos = [CategoryInfo(c.name, c.tier, (c.width[0], c.width[2]), (c.depth[0], c.depth[2]),
                          (c.height[0], c.height[2]), c.supported_by, c.against_wall)
             for c in rt.categories]
    spec = RoomTypeSpec('bedroom', rt.rooms, rt.size_cap, tuple(
        RoomCategorySpec(i, c.count, c.per_room, i.mean_footprint * c.per_room)
        for i, c in zip(infos, rt.categories, strict=True)), rt.doors_per_room,
        rt.windows_per_room)
    assert spec.importance_order() == rt.importance_order
    assert spec['lamp'].info.supported_by == ('nightstand',)


@pytest.mark.parametrize('edit, words', [
    (lambda d: d['room_types']['bedroom']['categories']['lamp'].update(tier='third'),
     'lamp.tier must be one of first, second, mounted'),
    (lambda d: d['room_types']['bedroom']['categories']['lamp'].update(
        supported_by={'shelf': 1}), "names 'shelf', which is not a category of bedroom"),
    (lambda d: d['room_types']['bedroom']['categories']['bed']['width'].update(min=3.0),
     'bed.width must have min <= median <= max'),
    (lambda d: d['room_types']['bedroom']['importance_order'].pop(),
     'importance_order must list each of its categories once'),
    (lambda d: d['room_types']['bedroom']['categories']['bed'].update(count='two'),
     "bed.count must be an integer of at least 1, got 'two'"),
    (lambda d: d['room_types']['bedroom']['categories']['bed'].update(supported_by={'x': 1}),
     'must be empty for the first tier'),
    (lambda d: d.update(version=7), 'version must be 1'),
])
def test_edit_mistakes_are_one_sentence(tmp_path, edit, words):
    d = description.describe(scenes(), 'test')
    edit(d)
    path = tmp_path / 'dataset.yaml'
    path.write_text(yaml.safe_dump(d, sort_keys=False))
    with pytest.raises(DatasetError, match=words) as e:
        description.load(path)
    assert '\n' not in str(e.value)


def test_merging_categories_by_hand_is_accepted(tmp_path):
    d = description.describe(scenes(), 'test')
    rt = d['room_types']['bedroom']
    rt['categories'].pop('ceiling light')
    rt.pop('importance_order')               # derived again when left out
    path = tmp_path / 'dataset.yaml'
    path.write_text(yaml.safe_dump(d, sort_keys=False))
    loaded = description.load(path).room_types['bedroom']
    assert 'ceiling light' not in loaded.names
    assert loaded.importance_order[0] == 'bed'


def test_not_yaml_is_one_sentence(tmp_path):
    path = tmp_path / 'dataset.yaml'
    path.write_text('room_types: [unclosed\n')
    with pytest.raises(DatasetError, match='not valid YAML'):
        description.load(path)
