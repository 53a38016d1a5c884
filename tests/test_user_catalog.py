"""A catalog of the user's own meshes (``user_catalog``, ``catalog.Catalog``): models made
here with trimesh in every axis convention, format and unit, measured against hand
calculation; broken inputs as report lines; synthesis retrieving the user's models; exports
drawing their meshes; the command line."""
from __future__ import annotations

import json
import math
from pathlib import Path
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import trimesh

from scene_synth_ros import catalog
from scene_synth_ros.catalog import Catalog, UserModel
from scene_synth_ros.categories import CATEGORIES
from scene_synth_ros.errors import MAX_SENTENCE, CatalogError
from scene_synth_ros.meshes import build_parts, variant_for
from scene_synth_ros.meshes.user import nearest_material
from scene_synth_ros.scene import PlacedObject
from scene_synth_ros.schema import load_scene
from scene_synth_ros.user_catalog import build_catalog, load_catalog, read_catalog, write_catalog

TOL = 1e-5

# A chair in the package's frame: seat 0.5 deep (x) x 0.44 wide (y), 0.95 high, its
# backrest at the back (-x) rising above the seat. Only the backrest is above z = 0.5.
CHAIR = (0.44, 0.5, 0.95)          # width, depth, height


def chair_ours() -> trimesh.Trimesh:
    base = trimesh.creation.box(extents=(0.5, 0.44, 0.48))
    base.apply_translation((0.0, 0.0, 0.24))
    back = trimesh.creation.box(extents=(0.06, 0.44, 0.47))
    back.apply_translation((-0.22, 0.0, 0.48 + 0.235))
    return trimesh.util.concatenate([base, back])


# Package frame -> a file's frame, written out by hand for each convention (columns: where
# our x, y, z go). Ours: front +x, left +y, up +z.
TO_FILE = {
    # glTF: y up, front +z, so its +x is the object's left
    ('+y', '+z'): np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0]], float),
    # z up, front -x: turned by 180 degrees about z
    ('+z', '-x'): np.array([[-1, 0, 0], [0, -1, 0], [0, 0, 1]], float),
    # z up, front +y: our front goes to +y, our left to -x
    ('+z', '+y'): np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]], float),
    # Blender-style OBJ: y up, front -z, our left to -x
    ('+y', '-z'): np.array([[0, -1, 0], [0, 0, 1], [-1, 0, 0]], float),
    # ours
    ('+z', '+x'): np.eye(3),
}


def in_file_frame(mesh: trimesh.Trimesh, up: str, front: str, scale: float = 1.0,
                  shift=(0.0, 0.0, 0.0)) -> trimesh.Trimesh:
    """``mesh`` (package frame) as a file of that convention holds it: turned, in units
    ``1 / scale`` of a metre, and moved off-centre by ``shift`` (file units)."""
    m = mesh.copy()
    t = np.eye(4)
    t[:3, :3] = TO_FILE[(up, front)] / scale
    t[:3, 3] = shift
    m.apply_transform(t)
    return m


def save(mesh: trimesh.Trimesh, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix == '.glb':
        s = trimesh.Scene()
        s.add_geometry(mesh, geom_name=path.stem)
        path.write_bytes(trimesh.exchange.gltf.export_glb(s))
    else:
        mesh.export(path)
    return path


def manifest(folder: Path, models: list[dict], defaults: dict | None = None) -> Path:
    data = {'models': models, **({'defaults': defaults} if defaults else {})}
    path = folder / 'manifest.yaml'
    path.write_text(json.dumps(data))            # JSON is YAML
    return path


def placed(model: UserModel, vertices: np.ndarray) -> np.ndarray:
    t = model.matrix
    return vertices @ t[:3, :3].T + t[:3, 3]


# ---- measuring: conventions, units, offsets ---------------------------------------------------
CASES = [  # file, up, front, what the manifest says, file units per metre, shift (file units)
    ('chair.glb', '+y', '+z', {}, 1.0, (0.3, 1.0, -2.0)),
    ('chair_back.obj', '+z', '-x', {'front': '-x'}, 1.0, (0.0, 0.0, 0.0)),
    ('chair_cm.stl', '+z', '+y', {'front': '+y', 'units': 'cm'}, 100.0, (12.0, -40.0, 7.0)),
    ('chair_blender.obj', '+y', '-z', {'up': '+y', 'front': '-z', 'scale': 0.5}, 2.0,
     (0.0, 0.0, 0.0)),
    ('chair.stl', '+z', '+x', {}, 1.0, (1.5, 0.25, 0.0)),
]


@pytest.mark.parametrize('name,up,front,says,per_metre,shift', CASES)
def test_a_model_lands_in_the_package_frame(tmp_path, name, up, front, says, per_metre, shift):
    chair = chair_ours()
    save(in_file_frame(chair, up, front, 1 / per_metre, shift), tmp_path / name)
    manifest(tmp_path, [{'file': name, 'category': 'straight chair', **says}])
    report = build_catalog(tmp_path)
    assert report.lines == []
    (m,) = report.models
    assert m.model_id == Path(name).stem and m.category == 'straight chair'
    assert m.size == pytest.approx(CHAIR, abs=TOL)
    # The offset undoes the shift: the file's shift, turned into our frame and in metres.
    turned_shift = np.linalg.inv(TO_FILE[(up, front)]) @ np.asarray(shift) / per_metre
    assert m.matrix[:3, 3] == pytest.approx(-turned_shift, abs=TOL)
    # Placed, the file's vertices are the chair's own, in our frame.
    file_vertices = np.asarray(trimesh.load(tmp_path / name, force='mesh').vertices, float)
    v = placed(m, file_vertices)
    assert v.min(axis=0) == pytest.approx((-0.25, -0.22, 0.0), abs=TOL)
    assert v.max(axis=0) == pytest.approx((0.25, 0.22, 0.95), abs=TOL)
    # The yaw convention: the backrest (all that is above the seat) is at the back, -x.
    back = v[v[:, 2] > 0.5]
    assert len(back) and back[:, 0].max() < -0.18


@pytest.mark.parametrize('name,up,front,says,per_metre,shift', CASES)
def test_the_rviz_mesh_is_the_model_in_the_package_frame(tmp_path, name, up, front, says,
                                                         per_metre, shift):
    # The STL that markers show: RViz gives a mesh resource a pose and a scale only, so
    # the file itself must be turned, centred, in metres and at the measured size.
    save(in_file_frame(chair_ours(), up, front, 1 / per_metre, shift), tmp_path / name)
    manifest(tmp_path, [{'file': name, 'category': 'straight chair', **says}])
    report = build_catalog(tmp_path)
    path = write_catalog(tmp_path / 'out' / 'catalog.json', report.models, report.lines)
    stem = Path(name).stem
    assert json.loads(path.read_text())['models'][0]['marker'] == f'markers/{stem}.stl'
    (m,) = read_catalog(path).user.values()
    assert m.marker == str((tmp_path / 'out' / 'markers' / f'{stem}.stl').resolve())
    data = Path(m.marker).read_bytes()
    mesh = trimesh.load(m.marker, force='mesh', process=False)
    assert len(data) == 84 + 50 * len(mesh.faces)                # binary STL
    w, d, h = m.size
    assert mesh.bounds[0] == pytest.approx((-d / 2, -w / 2, 0.0), abs=TOL)
    assert mesh.bounds[1] == pytest.approx((d / 2, w / 2, h), abs=TOL)
    back = mesh.vertices[mesh.vertices[:, 2] > 0.5]              # the backrest, behind
    assert len(back) and back[:, 0].max() < -0.18


def test_a_catalog_without_rviz_meshes_still_reads(tmp_path):
    # Catalogs written before the markers existed have no "marker": they read as before.
    save(chair_ours(), tmp_path / 'c.stl')
    manifest(tmp_path, [{'file': 'c.stl', 'category': 'straight chair'}])
    report = build_catalog(tmp_path)
    # A mesh that cannot be read when the catalog is written: the catalog, without its STL.
    (tmp_path / 'c.stl').rename(tmp_path / 'moved.stl')
    path = write_catalog(tmp_path / 'catalog.json', report.models, report.lines)
    data = json.loads(path.read_text())
    assert 'marker' not in data['models'][0] and not (tmp_path / 'markers').exists()
    assert read_catalog(path).get('c').marker == ''
    data['models'][0]['marker'] = 3
    path.write_text(json.dumps(data))
    with pytest.raises(CatalogError, match=r'models\[0\] is broken \(marker must be a path'):
        read_catalog(path)


def test_defaults_of_the_manifest_apply_to_every_model(tmp_path):
    chair = chair_ours()
    for k in range(2):
        save(in_file_frame(chair, '+y', '-z', 0.01), tmp_path / f'c{k}.obj')
    manifest(tmp_path, [{'file': 'c0.obj', 'category': 'straight chair'},
                        {'file': 'c1.obj', 'category': 'chair', 'id': 'kept', 'front': '-z'}],
             defaults={'up': '+y', 'front': '-z', 'units': 'cm'})
    report = build_catalog(tmp_path)
    assert [m.model_id for m in report.models] == ['c0', 'kept']
    for m in report.models:
        assert m.size == pytest.approx(CHAIR, abs=TOL)


def test_a_stretched_user_model_fills_the_objects_box(tmp_path):
    save(in_file_frame(chair_ours(), '+y', '+z', shift=(5, 5, 5)), tmp_path / 'c.glb')
    manifest(tmp_path, [{'file': 'c.glb', 'category': 'straight chair'}])
    cat = build_catalog(tmp_path).catalog()
    obj = PlacedObject('chair_1', 'straight chair', 'c', (1.0, 2.0, 0.0), 0.3,
                       (0.5, 0.6, 1.0))
    v = variant_for(obj, cat)
    assert isinstance(v, UserModel) and v.size == (0.5, 0.6, 1.0) and v.model_id != 'c'
    allv = np.vstack([p.vertices for p in build_parts(v)])
    assert allv.min(axis=0) == pytest.approx((-0.3, -0.25, 0.0), abs=TOL)
    assert allv.max(axis=0) == pytest.approx((0.3, 0.25, 1.0), abs=TOL)
    back = allv[allv[:, 2] > 0.5 / 0.95]
    assert back[:, 0].max() < -0.2                  # still at the back
    # At its own size, the model itself; without the catalog, a procedural chair.
    own = PlacedObject('chair_2', 'straight chair', 'c', (0, 0, 0), 0.0, cat.get('c').size)
    assert variant_for(own, cat) is cat.get('c')
    assert not isinstance(variant_for(obj), UserModel)


def test_colours_become_the_nearest_palette_material(tmp_path):
    assert nearest_material((150, 105, 65, 255)) == 'wood'
    mesh = chair_ours()
    mesh.visual.vertex_colors = (48, 50, 56, 255)
    save(mesh, tmp_path / 'dark.glb')
    manifest(tmp_path, [{'file': 'dark.glb', 'category': 'straight chair', 'up': '+z',
                         'front': '+x'}])
    (m,) = build_catalog(tmp_path).models
    assert {p.material for p in build_parts(m)} == {'fabric_dark'}


# ---- broken inputs: report lines, never a crash ----------------------------------------------
def test_broken_models_are_report_lines(tmp_path):
    chair = chair_ours()
    save(chair, tmp_path / 'good.stl')
    (tmp_path / 'empty.obj').write_text('# nothing here\n')
    (tmp_path / 'garbage.glb').write_bytes(b'glTF\x02\x00\x00\x00' + bytes(range(256)) * 4)
    (tmp_path / 'nan.obj').write_text('v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n')
    flat = trimesh.Trimesh([[0, 0, 0], [0.5, 0, 0], [0.5, 0.5, 0], [0, 0.5, 0]],
                           [[0, 1, 2], [0, 2, 3]])
    save(flat, tmp_path / 'flat.stl')
    save(in_file_frame(chair, '+z', '+x', 0.01), tmp_path / 'in_cm.stl')      # no units
    save(in_file_frame(chair, '+y', '+z'), tmp_path / 'yup.stl')              # no up axis
    manifest(tmp_path, [
        {'file': 'good.stl', 'category': 'straight chair'},
        {'file': 'empty.obj', 'category': 'straight chair'},
        {'file': 'garbage.glb', 'category': 'straight chair'},
        {'file': 'missing.obj', 'category': 'sofa'},
        {'file': 'nan.obj', 'category': 'straight chair'},
        {'file': 'flat.stl', 'category': 'straight chair'},
        {'file': 'in_cm.stl', 'category': 'straight chair'},
        {'file': 'yup.stl', 'category': 'straight chair'},
        {'file': 'good.stl', 'category': 'rocking chair'},
        {'file': 'good.stl', 'category': 'straight chair', 'up': '+q'},
        {'file': 'good.stl', 'category': 'straight chair', 'up': 'z', 'front': '-z'},
        {'file': 'good.stl', 'category': 'straight chair', 'units': 'furlong'},
        {'file': 'good.stl', 'category': 'straight chair', 'scale': -1},
        {'file': 'good.stl', 'category': 'straight chair', 'colour': 'red'},
        {'file': 'good.stl', 'category': 'straight chair'},                 # same id again
        {'file': 'good.stl', 'category': 'sofa', 'id': 'sofa_00'},          # procedural id
        {'file': 'good.stl', 'category': 'straight chair', 'id': 'a@b'},
        {'category': 'straight chair'},
        'just a string',
    ])
    report = build_catalog(tmp_path)
    assert [m.model_id for m in report.models] == ['good']
    expected = [
        "models[8] 'good.stl': category 'rocking chair' is not a category of ours",
        "models[9] 'good.stl': up '+q' is not an axis",
        "models[10] 'good.stl': its front and up are the same axis",
        "models[11] 'good.stl': units 'furlong' are not one of",
        "models[12] 'good.stl': scale -1 is not a positive number",
        "models[13] 'good.stl': unknown key 'colour'",
        "models[16] 'good.stl': id 'a@b' must be",
        'models[17]: no "file"',
        'models[18]: not a mapping',
        "'empty.obj': it holds no triangles",
        "'garbage.glb': trimesh cannot read it",
        "'missing.obj': no such file",
        "'nan.obj': it has non-finite vertex coordinates",
        "'flat.stl': its box is flat",
        "'in_cm.stl': a 44 x 50 x 95 m straight chair is implausible",
        "'yup.stl': a 0.95 x 0.44 x 0.5 m straight chair is implausible",
        "'good.stl': its id 'good' is already 'good.stl''s",
        "'good.stl': its id 'sofa_00' is a procedural model's",
    ]
    assert len(report.lines) == len(expected)
    for line in expected:
        assert sum(got.startswith(line) for got in report.lines) == 1, line
    assert any(line.endswith('are its units cm?') for line in report.lines)
    assert any(line.endswith('is its up axis right?') for line in report.lines)
    for line in report.lines:
        assert '\n' not in line and len(line) <= MAX_SENTENCE


def test_a_folder_or_manifest_that_cannot_be_read_is_one_sentence(tmp_path):
    with pytest.raises(CatalogError, match='does not exist'):
        build_catalog(tmp_path / 'nowhere')
    with pytest.raises(CatalogError, match='no manifest'):
        build_catalog(tmp_path)
    (tmp_path / 'manifest.yaml').write_text('models: [unclosed\n')
    with pytest.raises(CatalogError, match='not valid YAML or JSON at line'):
        build_catalog(tmp_path)
    (tmp_path / 'manifest.yaml').write_text('title: my chairs\n')
    with pytest.raises(CatalogError, match='needs a "models" list'):
        build_catalog(tmp_path)
    with pytest.raises(CatalogError, match='does not exist'):
        build_catalog(tmp_path, manifest=tmp_path / 'other.yaml')


def test_a_broken_catalog_file_is_one_sentence(tmp_path):
    path = tmp_path / 'catalog.json'
    with pytest.raises(CatalogError, match='does not exist'):
        read_catalog(path)
    path.write_text('{"format": "something else"}')
    with pytest.raises(CatalogError, match='not a catalog written by'):
        read_catalog(path)
    save(chair_ours(), tmp_path / 'c.stl')
    manifest(tmp_path, [{'file': 'c.stl', 'category': 'straight chair'}])
    report = build_catalog(tmp_path)
    write_catalog(path, report.models, report.lines)
    data = json.loads(path.read_text())
    data['models'][0]['size'] = [0.4, -1, 0.9]
    path.write_text(json.dumps(data))
    with pytest.raises(CatalogError, match=r'models\[0\] is broken'):
        read_catalog(path)
    path.write_text('{"format": ')
    with pytest.raises(CatalogError, match='not valid JSON'):
        load_catalog(path)


def test_a_mesh_gone_since_the_build_is_one_sentence_at_export(tmp_path):
    save(chair_ours(), tmp_path / 'c.stl')
    manifest(tmp_path, [{'file': 'c.stl', 'category': 'straight chair'}])
    (m,) = build_catalog(tmp_path).models
    (tmp_path / 'c.stl').unlink()
    with pytest.raises(CatalogError, match='cannot be read any more'):
        build_parts(m)


# ---- other layouts: 3D-FUTURE, a folder per category ----------------------------------------
def test_a_3d_future_folder(tmp_path):
    chair = chair_ours()
    info = [{'model_id': 'aaaa-1', 'category': 'Dining Chair', 'super-category': 'Chair'},
            {'model_id': 'bbbb-2', 'category': 'Dining Chair', 'super-category': 'Chair'},
            {'model_id': 'cccc-3', 'category': 'Pendant Lamp', 'super-category': 'Lighting'},
            {'model_id': 'dddd-4', 'category': 'Robot Vacuum', 'super-category': 'Others'},
            {'model_id': 'ffff-6', 'category': '', 'super-category': 'Others'}]
    (tmp_path / 'model_info.json').write_text(json.dumps(info))
    for model_id in ('aaaa-1', 'cccc-3', 'dddd-4', 'ffff-6'):
        save(in_file_frame(chair, '+y', '+z', shift=(0.1, 0.0, 0.2)),
             tmp_path / model_id / 'raw_model.obj')
    save(chair, tmp_path / 'eeee-5' / 'raw_model.obj')
    report = build_catalog(tmp_path)
    (m,) = report.models
    assert (m.model_id, m.category) == ('aaaa-1', 'straight chair')
    assert m.size == pytest.approx(CHAIR, abs=TOL)
    assert m.matrix[:3, 3] == pytest.approx((-0.2, -0.1, 0.0), abs=TOL)
    assert sorted(report.lines) == sorted([
        "3D-FUTURE category 'Pendant Lamp' (1 models) maps to none of ours",
        "3D-FUTURE category 'Robot Vacuum' (1 models) is not in the category map; add it "
        "there to keep them",
        '1 models of model_info.json have no raw_model.obj in this folder',
        '1 models of model_info.json have no category',
        "'eeee-5': a model folder that model_info.json does not list"])
    # An edited category map keeps the lamp's category... as one of ours.
    edited = tmp_path / 'map.yaml'
    edited.write_text('Dining Chair: chair\nPendant Lamp: null\nRobot Vacuum: null\n')
    (m,) = build_catalog(tmp_path, category_map=edited).models
    assert m.category == 'chair'
    edited.write_text('Dining Chair: throne\n')
    with pytest.raises(CatalogError, match="'throne', which is not a category of ours"):
        build_catalog(tmp_path, category_map=edited)


REAL_FUTURE = (Path(__file__).resolve().parent.parent.parent / 'shared' / 'data' / 'real' /
               '3dfront' / '3dfuture_model_category_mapping.csv')


@pytest.mark.skipif(not REAL_FUTURE.is_file(), reason=f'no {REAL_FUTURE}')
def test_the_category_map_knows_every_real_3d_future_category():
    from scene_synth_ros.datasets.models import ModelCategories
    from scene_synth_ros.user_catalog.sources import future_mapping
    mapping = future_mapping()
    theirs = {e.category.lower() for e in ModelCategories(REAL_FUTURE).table.values()
              if e.category}
    assert theirs <= set(mapping), sorted(theirs - set(mapping))
    assert mapping['dining chair'] == 'straight chair' and mapping['pendant lamp'] is None


def test_a_folder_per_category(tmp_path):
    chair = chair_ours()
    save(chair, tmp_path / 'straight_chair' / 'a.stl')
    save(in_file_frame(chair, '+y', '+z'), tmp_path / 'straight chair' / 'b.glb')
    save(chair, tmp_path / 'thrones' / 'c.stl')
    report = build_catalog(tmp_path)
    assert sorted(m.model_id for m in report.models) == ['a', 'b']
    assert report.lines == ["'thrones'/: not a category of ours, so its 1 mesh files are "
                            'skipped']


# ---- a small real-looking set -----------------------------------------------------------------
def _box(lo, hi) -> trimesh.Trimesh:
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    b = trimesh.creation.box(extents=hi - lo)
    b.apply_translation((lo + hi) / 2)
    return b


def double_bed() -> trimesh.Trimesh:
    """2.1 deep, 1.7 wide, headboard 1.1 high at the back (-x)."""
    frame = _box((-1.05, -0.85, 0.0), (1.05, 0.85, 0.35))
    mattress = _box((-1.0, -0.8, 0.35), (1.05, 0.8, 0.55))
    head = _box((-1.05, -0.85, 0.0), (-0.97, 0.85, 1.1))
    return trimesh.util.concatenate([frame, mattress, head])


def desk_parts() -> list[trimesh.Trimesh]:
    """1.4 wide, 0.7 deep, 0.75 high: a top and four legs, five meshes."""
    parts = [_box((-0.35, -0.7, 0.72), (0.35, 0.7, 0.75))]
    for x in (-0.32, 0.29):
        for y in (-0.67, 0.64):
            parts.append(_box((x, y, 0.0), (x + 0.03, y + 0.03, 0.72)))
    return parts


REAL = {  # id: (category, size (w, d, h))
    'oak_bed': ('double bed', (1.7, 2.1, 1.1)),
    'night_left': ('stand', (0.5, 0.4, 0.55)),
    'big_wardrobe': ('wardrobe', (1.2, 0.6, 2.0)),
    'work_desk': ('desk', (1.4, 0.7, 0.75)),
}


@pytest.fixture(scope='module')
def real_set(tmp_path_factory) -> tuple[Path, Path]:
    """(folder, catalog file) of ``make_real_set``."""
    return make_real_set(tmp_path_factory.mktemp('furniture'))


def make_real_set(root: Path) -> tuple[Path, Path]:
    """(folder, catalog file) of a bed (GLB, y up), a nightstand (OBJ in cm, front -x), a
    wardrobe (STL, z up, off-centre) and a desk (GLB of five meshes, z up, front +y), with
    the catalog written to ``root/catalog.json``."""
    save(in_file_frame(double_bed(), '+y', '+z', shift=(0.0, 0.0, 3.0)),
         root / 'beds' / 'oak_bed.glb')
    stand = trimesh.util.concatenate([_box((-0.2, -0.25, 0.0), (0.2, 0.25, 0.55)),
                                      _box((0.2, -0.1, 0.3), (0.2, 0.1, 0.32))])
    save(in_file_frame(stand, '+z', '-x', 0.01), root / 'night_left.obj')
    save(in_file_frame(_box((-0.3, -0.6, 0.0), (0.3, 0.6, 2.0)), '+z', '+x',
                       shift=(4.0, -1.0, 0.5)), root / 'big_wardrobe.stl')
    desk = trimesh.Scene()
    for k, part in enumerate(desk_parts()):
        desk.add_geometry(in_file_frame(part, '+z', '+y'), geom_name=f'part{k}')
    (root / 'work_desk.glb').write_bytes(trimesh.exchange.gltf.export_glb(desk))
    manifest(root, [
        {'file': 'beds/oak_bed.glb', 'category': 'double bed'},
        {'file': 'night_left.obj', 'category': 'stand', 'front': '-x', 'units': 'cm'},
        {'file': 'big_wardrobe.stl', 'category': 'wardrobe'},
        {'file': 'work_desk.glb', 'category': 'desk', 'up': '+z', 'front': '+y'},
    ])
    report = build_catalog(root)
    assert report.lines == []
    return root, write_catalog(root / 'catalog.json', report.models, report.lines)


def test_the_real_looking_set_measures_and_reads_back(real_set):
    _, path = real_set
    cat = read_catalog(path)
    assert cat.user_categories == [c for c in CATEGORIES
                                   if c in {'double bed', 'stand', 'wardrobe', 'desk'}]
    for model_id, (category, size) in REAL.items():
        m = cat.get(model_id)
        assert m.category == category and m.size == pytest.approx(size, abs=TOL)
    assert len(build_parts(cat.get('work_desk'))) == 5           # the file's five meshes
    assert load_catalog(path) is load_catalog(str(path))          # read once


def test_retrieval_uses_the_users_models_and_falls_back(real_set):
    cat = read_catalog(real_set[1])
    assert [v.model_id for v in cat.variants('double bed')] == ['oak_bed']
    assert cat.nearest('double bed', 1.4, 2.0).model_id == 'oak_bed'
    assert cat.ranked('stand', 0.3, 0.3)[0].model_id == 'night_left'
    # A category without a user model: the procedural catalog, as the module's functions.
    assert cat.variants('sofa') == catalog.variants('sofa')
    assert cat.ranked('sofa', 2.0, 0.9) == catalog.ranked('sofa', 2.0, 0.9)
    assert cat.nearest('sofa', 2.0, 0.9) == catalog.nearest('sofa', 2.0, 0.9)
    assert cat.get('sofa_03') == catalog.get('sofa_03')          # objects placed before
    assert cat.fallback(['double bed', 'sofa', 'stand']) == ['sofa']
    with pytest.raises(KeyError):
        cat.get('no_such_model')
    assert load_catalog(None) is catalog.PROCEDURAL and load_catalog(cat) is cat


def test_a_catalog_made_in_python(real_set):
    models = list(read_catalog(real_set[1]).user.values())
    cat = Catalog(models[:2])
    assert cat.user_categories == ['stand', 'double bed'] and cat.source is None   # table order
    assert len(cat.all_variants()) == len(catalog.all_variants()) - 2 * 8 + 2
    with pytest.raises(ValueError, match='two user models'):
        Catalog(models + models[:1])


@pytest.fixture(scope='module')
def user_room(real_set):
    """A bedroom furnished by the shipped weights from the real-looking set."""
    from scene_synth_ros.corpus.generate import empty_room
    from scene_synth_ros.synth import SynthConfig, Synthesizer
    synth = Synthesizer(config=SynthConfig(catalog=str(real_set[1])))
    for seed in range(6):
        scene = synth.generate(empty_room('bedroom', seed), seed).scene
        if any(o.model_id in REAL for o in scene.objects):
            return scene
    pytest.fail('no synthesized bedroom holds a user model')


def test_synthesis_retrieves_the_users_models(user_room, real_set):
    cat = read_catalog(real_set[1])
    covered = set(cat.user_categories)
    assert any(o.category in covered for o in user_room.objects)
    for o in user_room.objects:
        if o.category in covered:
            assert o.model_id in REAL and cat.get(o.model_id).size == o.size
        else:
            assert catalog.get(o.model_id).category == o.category      # procedural
    # The scene is valid with the catalog, and refers to models the default one lacks.
    from scene_synth_ros.schema import SceneValidationError, dump_scene, parse_scene
    text = dump_scene(user_room, cat)
    assert parse_scene(text, cat).objects[0].model_id == user_room.objects[0].model_id
    with pytest.raises(SceneValidationError, match='is not a catalog model id'):
        dump_scene(user_room)


def _user_objects(scene):
    return [o for o in scene.objects if o.model_id in REAL]


def test_gltf_export_holds_the_users_meshes_at_the_objects_size(user_room, real_set,
                                                                   tmp_path):
    from scene_synth_ros.export import write
    cat = read_catalog(real_set[1])
    path = write(user_room, 'gltf', tmp_path / 'room.glb', catalog=cat)
    loaded = trimesh.load(path)
    for o in _user_objects(user_room):
        names = [g for g in loaded.geometry if g.startswith(f'{o.model_id}/')]
        assert names, o.model_id
        v = np.vstack([loaded.geometry[g].vertices for g in names])
        # the object's own frame, z up: depth along x, width along y
        assert np.ptp(v, axis=0) == pytest.approx((o.depth, o.width, o.height), abs=1e-4)
        faces = sum(len(loaded.geometry[g].faces) for g in names)
        assert faces == sum(len(p.faces) for p in build_parts(cat.get(o.model_id)))


def test_sdf_export_refers_to_the_users_meshes(user_room, real_set, tmp_path):
    from scene_synth_ros.export import write
    cat = read_catalog(real_set[1])
    path = write(user_room, 'sdf', tmp_path / 'room.sdf', catalog=cat)
    world = ET.parse(path).getroot()
    for o in _user_objects(user_room):
        model = next(m for m in world.iter('model') if m.get('name') == o.id)
        uri = model.find('.//visual/geometry/mesh/uri').text
        assert o.model_id in uri
        mesh = trimesh.load(tmp_path / uri, force='mesh')
        assert np.ptp(mesh.vertices, axis=0) == pytest.approx((o.depth, o.width, o.height),
                                                              abs=1e-4)
        pose = [float(v) for v in model.find('pose').text.split()]
        assert pose[:2] == pytest.approx(o.position[:2], abs=1e-5)
        assert math.isclose(pose[5], o.yaw, abs_tol=1e-5)


@pytest.mark.parametrize('fmt', ['mjcf', 'urdf', 'usd'])
def test_other_exports_write_the_users_meshes(user_room, real_set, tmp_path, fmt):
    from scene_synth_ros.export import FORMATS, write
    from scene_synth_ros.files import safe_name
    cat = read_catalog(real_set[1])
    path = write(user_room, fmt, tmp_path / f'room{FORMATS[fmt].suffix}', tmp_path / 'meshes',
                 catalog=cat)
    written = {p.relative_to(tmp_path / 'meshes').parts[0] for p in
               (tmp_path / 'meshes').rglob('*') if p.is_file()}
    for o in _user_objects(user_room):
        assert any(name.split('.')[0] == safe_name(o.model_id) for name in written), fmt
    if fmt == 'mjcf':
        import mujoco
        mujoco.MjModel.from_xml_path(str(path))         # the simulator loads it


# ---- the command line -------------------------------------------------------------------------
def test_catalog_build_generate_and_export_commands(cli, real_set, tmp_path):
    root, _ = real_set
    out = tmp_path / 'mine.json'
    r = cli('catalog', 'build', root, '--out', out)
    assert 'kept 4 models of 4 categories' in r.stdout and f'wrote {out}' in r.stdout
    assert [m['model_id'] for m in json.loads(out.read_text())['models']] == list(REAL)
    assert sorted(p.name for p in (tmp_path / 'markers').iterdir()) == \
        sorted(f'{k}.stl' for k in REAL)                         # the meshes RViz shows
    r = cli('catalog', 'list', '--catalog', out)
    assert 'oak_bed' in r.stdout and 'sofa_00' in r.stdout and 'double_bed_00' not in r.stdout
    scene = tmp_path / 'room.json'
    r = cli('generate', '--room-type', 'bedroom', '--seed', '1', '--catalog', out,
            '--out', scene)
    assert f'catalog {out}: your models for ' in r.stdout
    assert 'procedural models for' in r.stdout
    r = cli('export', scene, '--catalog', out, '--gltf', tmp_path / 'room.glb')
    assert (tmp_path / 'room.glb').is_file()
    r = cli('complete', scene, '--catalog', out, '--out', tmp_path / 'again.json')
    used = {o['model_id'] for o in json.loads(scene.read_text())['objects']}
    if used & set(REAL):        # a scene of the user's models needs their catalog to load
        r = cli('export', scene, '--gltf', tmp_path / 'x.glb', ok=False)
        assert r.returncode == 2 and 'is not a catalog model id' in r.stderr
    # A batch: scenes that load with the catalog, and exports that draw the user's meshes.
    batch = tmp_path / 'batch'
    cli('generate', '--room-type', 'bedroom', '--catalog', out, '-n', '3', '--workers', '1',
        '--export', 'gltf', '--out', batch)
    models = load_catalog(out)
    scenes = [load_scene(p, models) for p in sorted((batch / 'scenes').glob('*.json'))]
    assert len(scenes) == 3
    own = {o.model_id for s in scenes for o in s.objects} & set(REAL)
    assert own                                   # the user's beds, stands, wardrobes, desks
    assert all(o.category == models.get(o.model_id).category for s in scenes for o in s.objects)
    assert len(list((batch / 'gltf').glob('*.glb'))) == 3


def test_catalog_build_bad_input_is_one_sentence(cli, tmp_path):
    r = cli('catalog', 'build', ok=False)
    assert r.returncode == 2 and 'needs the folder' in r.stderr
    r = cli('catalog', 'build', tmp_path / 'nowhere', ok=False)
    assert r.returncode == 2 and 'does not exist' in r.stderr
    (tmp_path / 'manifest.yaml').write_text('models: [{file: gone.obj, category: sofa}]\n')
    r = cli('catalog', 'build', tmp_path, ok=False)
    assert r.returncode == 1 and "'gone.obj': no such file" in r.stdout
    r = cli('generate', '--catalog', tmp_path / 'none.json', ok=False)
    assert r.returncode == 2 and 'does not exist' in r.stderr
    assert 'Traceback' not in r.stderr
