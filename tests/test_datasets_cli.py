"""``scene-synth import`` (cli/datasets.py): files written, options, and bad input as one
sentence with exit code 2."""
import json

import pytest
from test_datasets_procthor import ASSETS, house

from scene_synth_ros import schema
from scene_synth_ros.datasets import description


@pytest.fixture
def data(tmp_path):
    src = tmp_path / 'src'
    src.mkdir()
    (src / 'houses.jsonl').write_text(json.dumps(house()) + '\n'
                                      + json.dumps(house('Garage')) + '\n')
    (src / 'procthor_asset_boxes.json').write_text(json.dumps(ASSETS))
    return tmp_path


def test_import_writes_scenes_report_and_description(cli, data):
    out = data / 'out'
    run = cli('import', 'procthor', data / 'src', '--out', out)
    assert 'procthor: 1 file(s), 2 room(s) read, 1 kept, 1 dropped' in run.stdout
    assert 'rooms dropped, unmapped room type: 1' in run.stdout
    assert sorted(p.name for p in out.iterdir()) == [
        'dataset.yaml', 'procthor_1_room_1.json', 'report.json', 'report.txt']
    scene = schema.read_payload((out / 'procthor_1_room_1.json').read_text())
    schema.check_against_schema(scene, 'scene')
    report = json.loads((out / 'report.json').read_text())
    assert report['totals']['rooms_kept'] == 1
    assert report['lines'][0]['reason'] == 'missing model'
    assert set(description.load(out / 'dataset.yaml').room_types) == {'bedroom'}


def test_a_room_type_file_of_ones_own_keeps_other_rooms(cli, data):
    types = data / 'types.yaml'
    types.write_text('procthor:\n  Bedroom: bedroom\n  Garage: garage\n')
    run = cli('import', 'procthor', data / 'src', '--out', data / 'out', '--room-types', types,
              '--quiet')
    assert run.stdout.strip() == ('procthor: 1 file(s), 2 room(s) read, 2 kept, 0 dropped; '
                                  '6 object(s) kept, 6 dropped')
    assert (data / 'out' / 'procthor_2_room_1.json').exists()


def test_filters_from_the_command_line(cli, data):
    run = cli('import', 'procthor', data / 'src', '--out', data / 'out',
              '--room-size', 'bedroom=4.5')
    assert 'rooms dropped, room too large: 1' in run.stdout
    run = cli('import', 'procthor', data / 'src', '--out', data / 'out',
              '--object-count', '5', '9')
    assert 'rooms dropped, too few objects: 1' in run.stdout


@pytest.mark.parametrize('args, words', [
    (['procthor', 'nowhere'], 'nowhere: no such file or folder'),
    (['procthor', '{src}', '--category-map', '{src}/houses.jsonl'],
     'ProcTHOR takes its categories from --asset-sizes'),
    (['suncg', '{src}/houses.jsonl'], 'no ModelCategoryMapping.csv'),
    (['procthor', '{src}', '--room-types', '{src}/houses.jsonl'], 'not valid YAML'),
    (['procthor', '{src}', '--scale-range', '2', '1'], 'the scale range must be'),
    (['procthor', '{src}', '--room-size', 'bedroom'], '--room-size takes TYPE=METRES'),
])
def test_bad_input_is_one_sentence_and_exit_2(cli, data, args, words):
    args = [a.format(src=data / 'src') for a in args]
    run = cli('import', *args, '--out', data / 'out', ok=False)
    assert run.returncode == 2
    assert words in run.stderr and len(run.stderr.strip().splitlines()) == 1
