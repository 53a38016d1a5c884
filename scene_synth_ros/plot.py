"""Pictures of scenes for people: a top-down plan drawn with matplotlib (no screen needed).

The floor is light grey, walls are thick dark lines, a door is a gap in the wall with its leaf
and a quarter-circle swing into the room, a window is a light-blue double line on the wall.
Every object is its rotated footprint filled with its category's colour (second-tier objects
on top, with a darker edge) and a small dark triangle at the middle of its front edge pointing
the way the object faces. Axes are in metres with a 1 m scale bar.

Colours are a fixed function of the category (``colors.category_color``), the same in every
picture and in the RViz markers.

Figures are made with ``matplotlib.figure.Figure`` directly (never pyplot), which renders with
the Agg backend and touches no global matplotlib state.
"""
from __future__ import annotations

import math
import os
from typing import Sequence

from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.patches import Arc, Patch
from matplotlib.patches import Polygon as PolygonPatch
from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar
import numpy as np
import shapely
from shapely import get_parts

from .categories import CATEGORIES, PAPER, Vocabulary
from .colors import (  # noqa: F401  (the colours are plot's API too)
    DOOR_COLOR,
    FLOOR_COLOR,
    UNKNOWN_COLOR,
    WALL_COLOR,
    WINDOW_COLOR,
    WINDOW_GLASS_COLOR,
    category_color,
    category_colors,
)
from .rules.robot import driven_floor, report
from .scene import Room, Scene

WALL_WIDTH_PT = 4.0
DEFAULT_FIGSIZE = (8.0, 6.0)
DEFAULT_DPI = 100


def _darker(rgba, f: float = 0.55):
    r, g, b, a = rgba
    return (r * f, g * f, b * f, a)


# --------------------------------------------------------------------------------------------

def _draw_room(ax, room: Room) -> None:
    ax.add_patch(PolygonPatch(np.asarray(room.floor), closed=True, facecolor=FLOOR_COLOR,
                              edgecolor='none', zorder=0))
    pts = np.asarray(room.floor + room.floor[:2])     # closed, one edge past for the join
    ax.plot(pts[:-1, 0], pts[:-1, 1], color=WALL_COLOR, lw=WALL_WIDTH_PT,
            solid_joinstyle='miter', solid_capstyle='projecting', zorder=2)

    door_gaps, window_gaps, leaves, panes = [], [], [], []
    for op in room.openings:
        wall = room.wall_of(op) or min(room.walls, key=lambda w: w.distance_to(op.position))
        d, n = wall.direction, wall.normal
        c = np.asarray(op.position)
        a, b = c - d * op.width / 2, c + d * op.width / 2
        (door_gaps if op.kind == 'door' else window_gaps).append([a, b])
        if op.kind == 'door':
            leaves.append([a, a + n * op.width])
            theta = math.degrees(math.atan2(d[1], d[0]))
            ax.add_patch(Arc(tuple(a), 2 * op.width, 2 * op.width, theta1=theta,
                             theta2=theta + 90.0, color=DOOR_COLOR, lw=0.9, ls='--',
                             zorder=3))
        else:
            off = n * 0.035
            panes += [[a + off, b + off], [a - off, b - off]]
    for gaps, color in ((door_gaps, FLOOR_COLOR), (window_gaps, WINDOW_GLASS_COLOR)):
        if gaps:
            ax.add_collection(LineCollection(gaps, colors=color, linewidths=WALL_WIDTH_PT + 0.6,
                                             capstyle='butt', zorder=2.5))
    if leaves:
        ax.add_collection(LineCollection(leaves, colors=DOOR_COLOR, linewidths=1.6,
                                         zorder=3))
    if panes:
        ax.add_collection(LineCollection(panes, colors=WINDOW_COLOR, linewidths=1.3,
                                         capstyle='butt', zorder=3))


def _front_triangle(o) -> np.ndarray:
    f = o.front
    s = np.array([-f[1], f[0]])
    c = np.asarray(o.position[:2])
    size = min(max(0.25 * min(o.width, o.depth), 0.03), 0.25)
    apex = c + f * o.depth / 2
    base = apex - f * size
    return np.array([apex, base + s * 0.6 * size, base - s * 0.6 * size])


def draw_scene(scene: Scene, ax=None, legend: bool = True, title: str | None = None,
               scale_bar: bool = True, vocabulary: Vocabulary = PAPER):
    """Draw ``scene`` on ``ax`` (a new figure of ``DEFAULT_FIGSIZE`` if None) and return the
    axes. ``title=None`` writes the room type and object count; ``''`` writes none. The
    scene's categories are those of ``vocabulary``."""
    if ax is None:
        fig = Figure(figsize=DEFAULT_FIGSIZE, dpi=DEFAULT_DPI)
        ax = fig.add_axes((0.08, 0.08, 0.6, 0.84) if legend else (0.1, 0.08, 0.85, 0.84))
    room = scene.room
    _draw_room(ax, room)

    objs = sorted(scene.objects, key=lambda o: (o.support is not None, o.top))
    for tier, zorder, lw in ((False, 4, 0.6), (True, 6, 1.1)):
        group = [o for o in objs if (o.support is not None) == tier]
        if not group:
            continue
        faces = [category_color(o.category, vocabulary) for o in group]
        edges = [_darker(c, 0.25 if tier else 0.6) for c in faces]
        ax.add_collection(PolyCollection([o.corners() for o in group], facecolors=faces,
                                         edgecolors=edges, linewidths=lw, zorder=zorder))
        ax.add_collection(PolyCollection([_front_triangle(o) for o in group],
                                         facecolors=(0.1, 0.1, 0.1, 0.75),
                                         edgecolors='none', zorder=zorder + 0.5))

    x0, y0, x1, y1 = room.bounds
    pad = 0.35
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - (0.75 if scale_bar else pad), y1 + pad)   # room for the scale bar
    ax.set_aspect('equal', adjustable='box')
    ax.set_xlabel('x [m]', fontsize=8)
    ax.set_ylabel('y [m]', fontsize=8)
    ax.tick_params(labelsize=7)
    if title is None:
        title = f'{room.room_type}: {len(scene)} objects'
    if title:
        ax.set_title(title, fontsize=10)
    if scale_bar:
        ax.add_artist(AnchoredSizeBar(ax.transData, 1.0, '1 m', 'lower right', pad=0.3,
                                      borderpad=0.3, sep=2, frameon=False, size_vertical=0.03,
                                      fontproperties={'size': 7}))
    if legend:
        handles = _legend_handles(_present_categories([scene]), vocabulary)
        if handles:
            ax.legend(handles=handles, loc='upper left', bbox_to_anchor=(1.02, 1.0),
                      fontsize=7, frameon=False, borderaxespad=0.0)
    return ax


def _present_categories(scenes: Sequence[Scene]) -> list[str]:
    """Categories present in ``scenes``, in ``CATEGORIES`` order (unknown names last)."""
    seen = {o.category for s in scenes for o in s.objects}
    order = {name: k for k, name in enumerate(CATEGORIES)}
    return sorted(seen, key=lambda c: (order.get(c, len(order)), c))


def _legend_handles(categories: Sequence[str], vocabulary: Vocabulary = PAPER
                    ) -> list[Patch]:
    colors = {c: category_color(c, vocabulary) for c in categories}
    return [Patch(facecolor=colors[c], edgecolor=_darker(colors[c], 0.6), label=c)
            for c in categories]


def save_png(scene: Scene, path: str | os.PathLike, dpi: int = DEFAULT_DPI,
             figsize: tuple[float, float] = DEFAULT_FIGSIZE, legend: bool = True,
             title: str | None = None, vocabulary: Vocabulary = PAPER) -> str:
    """Write a picture of ``scene`` to ``path`` (PNG of exactly ``figsize * dpi`` pixels) and
    return the path."""
    fig = Figure(figsize=figsize, dpi=dpi)
    ax = fig.add_axes((0.08, 0.08, 0.6, 0.84) if legend else (0.1, 0.08, 0.85, 0.84))
    draw_scene(scene, ax=ax, legend=legend, title=title, vocabulary=vocabulary)
    fig.savefig(path, dpi=dpi, format='png')
    return os.fspath(path)


def save_house_png(house, path: str | os.PathLike, dpi: int = DEFAULT_DPI,
                   title: str | None = None, vocabulary: Vocabulary = PAPER) -> str:
    """Write a picture of a furnished house (``house.HouseScene``) to ``path``: every room
    with its objects, each room's id and type at its centre, one legend. Returns the path."""
    scenes = [house.scenes[rid] for rid in house.house.rooms]
    x0, y0, x1, y1 = shapely.MultiPolygon([s.room.polygon for s in scenes]).bounds
    width = 7.0
    height = max(3.0, min(12.0, width * (y1 - y0 + 1.1) / max(x1 - x0 + 0.7, 1e-6)))
    fig = Figure(figsize=(width + 2.2, height), dpi=dpi)
    ax = fig.add_axes((0.08, 0.06, 0.68, 0.88))
    for rid, scene in zip(house.house.rooms, scenes, strict=True):
        draw_scene(scene, ax=ax, legend=False, title='', scale_bar=False, vocabulary=vocabulary)
        c = scene.room.polygon.representative_point()
        ax.text(c.x, c.y, f'{rid}\n{scene.room.room_type}', ha='center', va='center',
                fontsize=7, color=(0.15, 0.15, 0.15), zorder=8,
                bbox={'boxstyle': 'round,pad=0.2', 'fc': (1, 1, 1, 0.7), 'ec': 'none'})
    pad = 0.35
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - 0.75, y1 + pad)
    ax.set_title(f'{len(scenes)} rooms, {sum(len(s) for s in scenes)} objects'
                 if title is None else title, fontsize=10)
    ax.add_artist(AnchoredSizeBar(ax.transData, 1.0, '1 m', 'lower right', pad=0.3,
                                  borderpad=0.3, sep=2, frameon=False, size_vertical=0.03,
                                  fontproperties={'size': 7}))
    handles = _legend_handles(_present_categories(scenes), vocabulary)
    if handles:
        ax.legend(handles=handles, loc='upper left', bbox_to_anchor=(1.02, 1.0), fontsize=7,
                  frameon=False, borderaxespad=0.0)
    fig.savefig(path, dpi=dpi, format='png')
    return os.fspath(path)


def save_grid(scenes: Sequence[Scene], path: str | os.PathLike, ncols: int = 3,
              titles: Sequence[str] | None = None, dpi: int = DEFAULT_DPI,
              cell: float = 3.6, legend: bool = True, vocabulary: Vocabulary = PAPER) -> str:
    """A gallery: the scenes on a grid of ``ncols`` columns (``cell`` inches per picture),
    with one legend of every category present at the right. Returns the path."""
    scenes = list(scenes)
    if not scenes:
        raise ValueError('save_grid needs at least one scene')
    if titles is not None and len(titles) != len(scenes):
        raise ValueError(f'{len(titles)} titles given for {len(scenes)} scenes')
    ncols = max(1, min(int(ncols), len(scenes)))
    nrows = math.ceil(len(scenes) / ncols)
    legend_w = 2.0 if legend else 0.0
    fig = Figure(figsize=(ncols * cell + legend_w, nrows * cell), dpi=dpi)
    axes = fig.subplots(nrows, ncols, squeeze=False)
    fig.subplots_adjust(left=0.06 * cell * ncols / (ncols * cell + legend_w),
                        right=(ncols * cell) / (ncols * cell + legend_w) - 0.01,
                        bottom=0.06, top=0.93, wspace=0.3, hspace=0.35)
    for k, ax in enumerate(axes.flat):
        if k >= len(scenes):
            ax.set_axis_off()
            continue
        draw_scene(scenes[k], ax=ax, legend=False,
                   title=None if titles is None else titles[k], vocabulary=vocabulary)
    if legend:
        handles = _legend_handles(_present_categories(scenes), vocabulary)
        if handles:
            fig.legend(handles=handles, loc='upper right', fontsize=7, frameon=False)
    fig.savefig(path, dpi=dpi, format='png')
    return os.fspath(path)


REACHED_COLOR = (0.2, 0.7, 0.3, 0.35)
UNREACHED_COLOR = '#d62728'


def save_reach_png(scene: Scene, robot, path: str | os.PathLike, dpi: int = DEFAULT_DPI,
                   vocabulary: Vocabulary = PAPER) -> str:
    """The robot promise drawn (``robot.report``): the floor the robot's body drives over
    from the doors in green, the objects it cannot reach outlined in red, the verdict as the
    title."""
    found = report(scene, robot)
    fig = Figure(figsize=DEFAULT_FIGSIZE, dpi=dpi)
    ax = fig.add_axes((0.08, 0.08, 0.6, 0.84))
    if found.reachable_floor is None:
        title = 'no doors: the robot comes in nowhere'
    else:
        title = (f'{100 * found.reachable_floor:.0f} % of the free floor reachable for a '
                 f'{2 * robot.radius:g} m robot' + ('' if found.kept else ': promise broken'))
    draw_scene(scene, ax=ax, title=title, vocabulary=vocabulary)
    pieces = [np.asarray(p.exterior.coords) for p in get_parts(driven_floor(scene, robot))
              if p.geom_type == 'Polygon']
    ax.add_collection(PolyCollection(pieces, facecolors=REACHED_COLOR, edgecolors='none',
                                     zorder=3))
    missed = [o.corners() for o in scene.first_tier if o.id in found.unreachable]
    ax.add_collection(PolyCollection(missed, facecolors='none', edgecolors=UNREACHED_COLOR,
                                     linewidths=2.0, zorder=8))
    fig.savefig(path, dpi=dpi, format='png')
    return os.fspath(path)
