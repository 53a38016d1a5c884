"""Tests of the scene pictures (scene_synth_ros.plot)."""
from __future__ import annotations

import math
import subprocess
import sys
import time

import matplotlib
import matplotlib.image as mpimg
import numpy as np
import pytest

from scene_synth_ros import catalog
from scene_synth_ros.categories import CATEGORIES
from scene_synth_ros.plot import (
    FLOOR_COLOR,
    category_color,
    category_colors,
    draw_scene,
    save_grid,
    save_png,
)
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene


def make_scene() -> Scene:
    room = Room('bedroom', ((0.0, 0.0), (4.5, 0.0), (4.5, 4.0), (0.0, 4.0)),
                doors=(Opening('door', (3.8, 0.0), 0.9, 2.1),),
                windows=(Opening('window', (2.0, 4.0), 1.2, 1.3, 0.9),))

    def o(oid, cat, x, y, yaw, w, d, h, z=0.0, support=None):
        return PlacedObject(oid, cat, catalog.variants(cat)[0].model_id, (x, y, z), yaw,
                            (w, d, h), support)

    return Scene(room, [
        o('bed', 'double bed', 2.0, 2.95, -math.pi / 2, 1.6, 2.0, 1.0),
        o('stand', 'stand', 0.8, 3.75, -math.pi / 2, 0.5, 0.45, 0.55),
        o('lamp', 'table lamp', 0.8, 3.75, 0.0, 0.3, 0.3, 0.5, 0.55, 'stand'),
        o('wardrobe', 'wardrobe', 4.2, 2.5, math.pi, 1.6, 0.6, 2.1),
        o('desk', 'desk', 1.0, 0.35, math.pi / 2, 1.4, 0.65, 0.75),
        o('chair', 'office chair', 1.0, 1.1, -math.pi / 2, 0.6, 0.6, 1.0),
    ])


def pixel_rgb(ax, img, x, y):
    """RGB of the saved image at the data point (x, y) of ``ax``."""
    px, py = ax.transData.transform((x, y))
    return img[int(img.shape[0] - py), int(px), :3]


def test_colors_are_fixed_and_distinct():
    colors = category_colors()
    assert list(colors) == list(CATEGORIES)
    rgb = {c[:3] for c in colors.values()}
    assert len(rgb) == len(CATEGORIES)                      # every category its own colour
    tab20 = matplotlib.colormaps['tab20'].colors
    assert category_color('wardrobe')[:3] == tuple(tab20[0])  # first category, first colour
    assert category_color('not a category')[:3] == (0.6, 0.6, 0.6)
    floor = matplotlib.colors.to_rgb(FLOOR_COLOR)
    assert all(max(abs(a - b) for a, b in zip(c, floor, strict=True)) > 0.05 for c in rgb)
    # Same mapping in a fresh interpreter.
    out = subprocess.run([sys.executable, '-c',
                          'from scene_synth_ros.plot import category_color as c;'
                          'print(repr(c("sofa")), repr(c("toilet")))'],
                         capture_output=True, text=True, check=True).stdout.strip()
    assert out == f'{category_color("sofa")!r} {category_color("toilet")!r}'


def test_save_png_writes_expected_image(tmp_path):
    path = tmp_path / 'scene.png'
    t0 = time.perf_counter()
    assert save_png(make_scene(), path, dpi=80, figsize=(8, 6)) == str(path)
    assert time.perf_counter() - t0 < 2.0
    img = mpimg.imread(path)
    assert img.shape == (480, 640, 4)
    # Several distinct object colours appear, each on many pixels.
    rgb = img[..., :3]
    found = 0
    for cat in ('double bed', 'stand', 'table lamp', 'wardrobe', 'desk', 'office chair'):
        c = np.asarray(category_color(cat)[:3])
        if (np.abs(rgb - c).max(-1) < 0.02).sum() > 30:
            found += 1
    assert found == 6
    assert len(np.unique((rgb * 255).astype(np.uint8).reshape(-1, 3), axis=0)) > 20


def test_object_colour_is_stable_across_pictures(tmp_path):
    scene = make_scene()
    other = Scene(scene.room, [o for o in scene.objects if o.id in ('wardrobe', 'chair')])
    colours = []
    for k, s in enumerate((scene, other)):
        ax = draw_scene(s)
        fig = ax.figure
        path = tmp_path / f'{k}.png'
        fig.savefig(path, dpi=fig.dpi)
        img = mpimg.imread(path)
        colours.append((pixel_rgb(ax, img, 4.2, 2.5), pixel_rgb(ax, img, 1.0, 1.0)))
        # Floor is light grey away from objects.
        assert np.allclose(pixel_rgb(ax, img, 3.0, 1.0), matplotlib.colors.to_rgb(FLOOR_COLOR),
                           atol=0.01)
    (w0, c0), (w1, c1) = colours
    assert np.allclose(w0, w1, atol=0.01) and np.allclose(c0, c1, atol=0.01)
    assert np.allclose(w0, category_color('wardrobe')[:3], atol=0.01)
    assert np.allclose(c0, category_color('office chair')[:3], atol=0.01)


def test_draw_scene_on_given_axes_with_legend_and_title():
    from matplotlib.figure import Figure
    fig = Figure(figsize=(5, 4))
    ax = fig.add_subplot()
    assert draw_scene(make_scene(), ax=ax, title='my room') is ax
    assert ax.get_title() == 'my room'
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ['wardrobe', 'stand', 'double bed', 'desk', 'office chair', 'table lamp']
    assert ax.get_aspect() == 1.0
    ax2 = draw_scene(make_scene(), legend=False, title='')
    assert ax2.get_legend() is None and ax2.get_title() == ''


def test_save_grid(tmp_path):
    scene = make_scene()
    empty = Scene(scene.room, [])
    path = tmp_path / 'grid.png'
    save_grid([scene, empty, scene, scene], path, ncols=3, titles=['a', 'b', 'c', 'd'],
              dpi=50, cell=3.0)
    img = mpimg.imread(path)
    assert img.shape[:2] == (2 * 3 * 50, (3 * 3 + 2) * 50)
    with pytest.raises(ValueError):
        save_grid([scene], tmp_path / 'x.png', titles=['a', 'b'])
    with pytest.raises(ValueError):
        save_grid([], tmp_path / 'y.png')
