"""Whole-or-nothing file writes and the file names the package gives ids."""
from __future__ import annotations

import os
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from scene_synth_ros import catalog
from scene_synth_ros.export import export_sdf
from scene_synth_ros.files import read_json, safe_name, write_atomic, writing_together
from scene_synth_ros.scene import PlacedObject, Room, Scene


def test_safe_name_keeps_plain_ids_and_uses_only_safe_characters():
    for text in ('wardrobe_00', 'double_bed_3', 'A9_z'):
        assert safe_name(text) == text
    for text in ('a@1.5', 'lamp 1', 'é/..', ''):
        assert set(safe_name(text)) <= set('abcdefghijklmnopqrstuvwxyz'
                                           'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-')


def test_safe_name_keeps_ids_that_differ_only_in_replaced_characters_apart():
    # The old SDF names mapped every one of these to 'a_1_5'.
    texts = ['a_1_5', 'a@1.5', 'a.1.5', 'a 1 5', 'a-1-5', 'a@1_5', 'a-40-1-2e-5', 'a_40_1_2e_5']
    names = [safe_name(t) for t in texts]
    assert len(set(names)) == len(texts), dict(zip(texts, names, strict=True))


def test_sdf_models_of_ids_that_sanitise_alike_stay_apart(tmp_path):
    room = Room('bedroom', ((0, 0), (4, 0), (4, 3), (0, 3)))
    v = catalog.variants('stand')[0]
    objs = [PlacedObject(oid, 'stand', v.model_id, (x, 1.0, 0.0), 0.0, v.size)
            for oid, x in (('stand 1', 1.0), ('stand_1', 2.5))]
    path = export_sdf(Scene(room, objs), tmp_path / 'world.sdf')
    names = [m.get('name') for m in ET.parse(path).getroot().iter('model')]
    assert safe_name('stand 1') in names and 'stand_1' in names


def test_write_atomic_writes_text_and_bytes(tmp_path):
    write_atomic(tmp_path / 'a.json', 'ä\n')
    write_atomic(tmp_path / 'b.bin', b'\x00\xff')
    assert (tmp_path / 'a.json').read_bytes() == 'ä\n'.encode('utf-8')
    assert (tmp_path / 'b.bin').read_bytes() == b'\x00\xff'
    write_atomic(tmp_path / 'a.json', 'new')
    assert (tmp_path / 'a.json').read_text() == 'new'
    assert sorted(p.name for p in tmp_path.iterdir()) == ['a.json', 'b.bin']


def test_a_failed_write_leaves_the_old_files_and_no_temporaries(tmp_path):
    (tmp_path / 'm.obj').write_text('old obj')
    with pytest.raises(RuntimeError):
        with writing_together(tmp_path, ['m.mtl', 'm.obj']) as tmp:
            (tmp / 'm.mtl').write_text('new mtl')
            (tmp / 'm.obj').write_text('new obj')
            raise RuntimeError('the exporter failed')
    assert sorted(p.name for p in tmp_path.iterdir()) == ['m.obj']
    assert (tmp_path / 'm.obj').read_text() == 'old obj'


def test_files_written_together_arrive_in_the_order_given(tmp_path, monkeypatch):
    moved = []
    replace = os.replace
    monkeypatch.setattr(os, 'replace', lambda a, b: (moved.append(os.path.basename(b)),
                                                     replace(a, b)))
    with writing_together(tmp_path, ['m.mtl', 'm.obj']) as tmp:
        (tmp / 'm.obj').write_text('obj')
        (tmp / 'm.mtl').write_text('mtl')
    assert moved == ['m.mtl', 'm.obj']
    assert sorted(p.name for p in tmp_path.iterdir()) == ['m.mtl', 'm.obj']


def test_read_json_names_the_file_in_one_sentence(tmp_path, monkeypatch):
    class Bad(ValueError):
        pass
    monkeypatch.chdir(tmp_path)         # short paths, whatever the temporary folder's is
    tmp_path = Path('.')
    (tmp_path / 'ok.json').write_text('{"a": [1, 2]}')
    assert read_json(tmp_path / 'ok.json', 'the table', Bad) == {'a': [1, 2]}
    with pytest.raises(Bad, match=r"^the table '.*gone.json' does not exist \(build one\)$"):
        read_json(tmp_path / 'gone.json', 'the table', Bad, ' (build one)')
    (tmp_path / 'bad.json').write_text('{"a": 1,\n oops}')
    with pytest.raises(Bad, match='is not valid JSON: .* at line 2$'):
        read_json(tmp_path / 'bad.json', 'the table', Bad)
    (tmp_path / 'latin.json').write_bytes(b'{"a": "\xe9"}')
    with pytest.raises(Bad, match='^cannot read the table'):
        read_json(tmp_path / 'latin.json', 'the table', Bad)
    with pytest.raises(Bad, match='^cannot read the table'):
        read_json(tmp_path, 'the table', Bad)             # a folder
