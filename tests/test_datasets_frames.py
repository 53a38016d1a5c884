"""The data sets' frames -> REP-103 (datasets/frames.py): each transform convention, the
mirror, and broken transforms, against hand calculation."""
import math

import numpy as np
import pytest

from scene_synth_ros.datasets import frames
from scene_synth_ros.scene import wrap_angle

RH = frames.RH_YUP_TO_ZUP
UNITY = frames.UNITY_TO_ZUP
SWAP = np.array([[1.0, 0, 0], [0, 0, 1], [0, 1, 0]])     # (x, y, z) -> (x, z, y)


def about_y(deg):
    h = math.radians(deg) / 2
    return frames.quaternion_matrix((0.0, math.sin(h), 0.0, math.cos(h)))


def test_the_right_handed_conversion_is_a_rotation_and_the_plain_swap_a_mirror():
    assert np.linalg.det(RH) == pytest.approx(1.0)
    assert np.linalg.det(SWAP) == pytest.approx(-1.0)
    # A model facing +z with +y up has its left hand at +x (up x front, right-handed).
    # In REP-103 an object's left is local +y: (-sin yaw, cos yaw).
    for deg in (0, 37, 90, 200):
        m = about_y(deg)
        p = frames.placement(m, RH)
        left_model = RH @ m @ np.array([1.0, 0, 0])
        assert left_model[:2] == pytest.approx([-math.sin(p.yaw), math.cos(p.yaw)], abs=1e-9)
        # the swap would put the model's left on the object's right
        yaw_swapped = math.atan2(*(SWAP @ m @ np.array([0, 0, 1.0]))[1::-1])
        left_swapped = SWAP @ m @ np.array([1.0, 0, 0])
        assert left_swapped[:2] == pytest.approx(
            [math.sin(yaw_swapped), -math.cos(yaw_swapped)], abs=1e-9)


@pytest.mark.parametrize('deg, yaw', [(0, -90), (90, 0), (180, 90), (-90, 180), (30, -60)])
def test_quaternion_about_y_gives_yaw_theta_minus_90(deg, yaw):
    p = frames.placement(about_y(deg), RH)
    assert wrap_angle(p.yaw - math.radians(yaw)) == pytest.approx(0, abs=1e-9)
    assert p.scale == pytest.approx((1, 1, 1)) and not p.mirrored


def test_quaternion_is_normalised_and_a_zero_one_is_broken():
    assert frames.quaternion_matrix((0, 2, 0, 0)) == pytest.approx(about_y(180))
    with pytest.raises(frames.BrokenTransform):
        frames.quaternion_matrix((0, 0, 0, 0))


def test_column_major_reads_the_translation_from_the_last_four_numbers():
    t = frames.column_major([0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 5, 6, 7, 1])
    assert t[:3, 3] == pytest.approx([5, 6, 7])
    # its rotation is 90 degrees about y: +z to +x
    assert t[:3, :3] @ np.array([0, 0, 1.0]) == pytest.approx([1, 0, 0])
    with pytest.raises(frames.BrokenTransform):
        frames.column_major([1, 0, 0])


@pytest.mark.parametrize('deg, yaw', [(0, 90), (90, 0), (180, -90), (270, -180), (45, 45)])
def test_unity_degrees_about_y_turn_clockwise(deg, yaw):
    p = frames.placement(frames.unity_euler_matrix(0, deg, 0), UNITY)
    assert wrap_angle(p.yaw - math.radians(yaw)) == pytest.approx(0, abs=1e-9)
    # Unity is left-handed: facing +z its right hand is +x, so its left maps to -x ...
    left = UNITY @ frames.unity_euler_matrix(0, deg, 0) @ np.array([-1.0, 0, 0])
    # ... which is the object's local +y in REP-103
    assert left[:2] == pytest.approx([-math.sin(p.yaw), math.cos(p.yaw)], abs=1e-9)


def test_a_mirror_along_the_front_turns_the_front_around_and_across_it_does_not():
    front = frames.placement(np.diag([1.0, 1.0, -1.0]), RH)
    assert front.mirrored and front.yaw == pytest.approx(math.pi / 2)
    side = frames.placement(np.diag([-2.0, 1.0, 1.0]), RH)
    assert side.mirrored and side.yaw == pytest.approx(-math.pi / 2)
    assert side.scale == pytest.approx((2.0, 1.0, 1.0))      # lateral, front, up


@pytest.mark.parametrize('m, words', [
    (np.full((3, 3), np.nan), 'not finite'),
    (np.diag([1.0, 0.0, 1.0]), 'singular'),
    (frames.quaternion_matrix((math.sin(math.pi / 4), 0, 0, math.cos(math.pi / 4))), 'leans'),
])
def test_broken_transforms_say_why(m, words):
    with pytest.raises(frames.BrokenTransform, match=words):
        frames.placement(m, RH)
