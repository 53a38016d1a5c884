"""The fixed colours of categories and of a room's floor, walls, doors and windows, the same
in pictures (``plot``) and in RViz markers (``markers``).

``category_color(name)`` walks the categories of ``categories.CATEGORIES`` in their order
over a palette made of matplotlib's tab20, tab20b and tab20c (greys left out so that no
object looks like floor or wall), so a category has the same colour in every picture. A
category of an imported data set that the paper's table lacks (one the ``vocabulary`` passed
in knows) takes the palette entry its name's CRC-32 picks: fixed too, on every machine.
Only its colour maps are read from matplotlib, when a colour is first asked for: the node
starts without the rest of it.
"""
from __future__ import annotations

from functools import lru_cache
import zlib

from .categories import CATEGORIES, PAPER, Vocabulary

FLOOR_COLOR = '#e4e4e4'
WALL_COLOR = '#2b2b2b'
DOOR_COLOR = '#8c5a2b'
WINDOW_COLOR = '#3d8fd1'
WINDOW_GLASS_COLOR = '#d4ecfb'
UNKNOWN_COLOR = (0.6, 0.6, 0.6, 1.0)


@lru_cache(maxsize=1)
def _palette() -> tuple[tuple[float, float, float, float], ...]:
    import matplotlib  # the colour maps only: the node starts without matplotlib
    def colors(name):
        return [tuple(c) for c in matplotlib.colormaps[name].colors]

    t20, t20b, t20c = colors('tab20'), colors('tab20b'), colors('tab20c')
    t20 = [c for k, c in enumerate(t20) if k not in (14, 15)]       # greys
    t20c = t20c[:16]                                                  # greys are 16..19
    # Strong shades first, then lighter ones, so that neighbours in CATEGORIES differ.
    ordered = (t20[0::2] + t20b[0::4] + t20b[2::4] + t20c[0::4] + t20[1::2] + t20b[1::4]
               + t20b[3::4] + t20c[1::4] + t20c[2::4] + t20c[3::4])
    return tuple((r, g, b, 1.0) for r, g, b in ordered)


@lru_cache(maxsize=1)
def category_colors() -> dict[str, tuple[float, float, float, float]]:
    """The fixed RGBA colour of every category of ``categories.CATEGORIES``."""
    import matplotlib  # the colour maps only: the node starts without matplotlib
    # The categories beyond the paper's 52 go on through the palette's last entries, then
    # Dark2 and Set1 without its grey, none as pale as the floor; a data set's categories
    # keep hashing into the palette alone.
    more = [(*c, 1.0) for name, n in (('Dark2', 8), ('Set1', 8))
            for c in matplotlib.colormaps[name].colors[:n]]
    floor = matplotlib.colors.to_rgb(FLOOR_COLOR)
    pal = tuple(c for c in _palette() + tuple(more)
                if max(abs(a - b) for a, b in zip(c[:3], floor, strict=True)) > 0.1)
    return {name: pal[k % len(pal)] for k, name in enumerate(CATEGORIES)}


def category_color(category: str, vocabulary: Vocabulary = PAPER
                   ) -> tuple[float, float, float, float]:
    """RGBA colour of ``category`` (by its name's CRC-32 for a data set's own category, one
    of ``vocabulary``; grey for a name that is no category at all)."""
    known = category_colors().get(category)
    if known is not None:
        return known
    try:
        vocabulary.info(category)
    except KeyError:
        return UNKNOWN_COLOR
    pal = _palette()
    return pal[zlib.crc32(category.encode('utf-8')) % len(pal)]


def rgba(color, alpha: float | None = None) -> tuple[float, float, float, float]:
    """``color`` (a name, ``#rrggbb`` or a tuple) as RGBA floats, with ``alpha`` if given."""
    from matplotlib.colors import to_rgba  # as above
    return tuple(float(c) for c in to_rgba(color, alpha))
