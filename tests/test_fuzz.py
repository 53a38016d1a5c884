"""Property-based tests of everything that reads outside input: every input either becomes a
room that round-trips and survives markers, exports and synthesis, or is refused with the
package's own error in one bounded, printable sentence; never another exception.

Derandomised (the same examples every run); ``benchmarks/fuzz_inputs.py`` runs more of them
and times each."""
import json
from pathlib import Path
import tempfile

from fuzz import JSON, layouts
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
import pytest

from scene_synth_ros.errors import MAX_SENTENCE, SceneSynthError
from scene_synth_ros.export import export_gltf, export_sdf
from scene_synth_ros.markers import scene_markers
from scene_synth_ros.schema import dump_scene, parse_room_layout, parse_scene
from scene_synth_ros.synth import SynthConfig, Synthesizer, check_room_fits

FUZZ = settings(derandomize=True, database=None, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.filter_too_much])


def assert_one_sentence(error: SceneSynthError) -> None:
    text = str(error)
    assert text and len(text) <= MAX_SENTENCE, text[:200]
    assert text.isprintable(), repr(text[:200])          # one line, no control characters
    text.encode('utf-8')                                 # no lone surrogates
    assert type(error).__module__.startswith('scene_synth_ros'), type(error)


def survives(scene) -> None:
    """What the node and the command line do with an accepted room."""
    text = dump_scene(scene)
    again = parse_scene(text)
    assert dump_scene(again) == text
    assert again.room.floor == scene.room.floor
    assert scene_markers(scene, 'cube')
    with tempfile.TemporaryDirectory() as tmp:
        export_sdf(scene, Path(tmp) / 'room.sdf', Path(tmp) / 'meshes')
        export_gltf(scene, Path(tmp) / 'room.glb')


def read_layout(payload):
    try:
        return parse_room_layout(payload)
    except SceneSynthError as e:
        assert_one_sentence(e)
        return None


@settings(FUZZ, max_examples=800)
@given(layouts(wild=False) | layouts())
def test_layouts_are_served_or_refused_in_one_sentence(layout):
    scene = read_layout(layout)
    if scene is None:
        return
    survives(scene)
    # The same document as text reads the same.
    again = read_layout(json.dumps(layout))
    assert again is not None and dump_scene(again) == dump_scene(scene)


@settings(FUZZ, max_examples=400)
@given(st.one_of(JSON, st.text(max_size=200), st.binary(max_size=200)))
def test_any_payload_is_a_room_or_one_sentence(payload):
    for reader in (parse_room_layout, parse_scene):
        try:
            reader(payload)
        except SceneSynthError as e:
            assert_one_sentence(e)


@settings(FUZZ, max_examples=300)
@given(JSON)
def test_any_json_text_is_a_room_or_one_sentence(value):
    try:
        text = json.dumps(value)
    except ValueError:          # Python cannot write an integer of 4,300 digits or more
        return
    for reader in (parse_room_layout, parse_scene):
        try:
            reader(text)
        except SceneSynthError as e:
            assert_one_sentence(e)


@pytest.fixture(scope='module')
def tiny_synth(tiny_weights):
    return Synthesizer(tiny_weights, SynthConfig(max_objects=6))


@settings(FUZZ, max_examples=12)
@given(layouts(wild=False).filter(lambda d: d['room_type'] in ('bedroom', 'bathroom')))
def test_accepted_rooms_can_be_furnished(tiny_synth, layout):
    scene = read_layout(layout)
    if scene is None:
        return
    try:
        check_room_fits(scene.room)
        result = tiny_synth.complete(scene, seed=0)
    except SceneSynthError as e:
        assert_one_sentence(e)
        return
    survives(result.scene)
