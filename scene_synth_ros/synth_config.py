"""The synthesis settings in one table: ``SynthConfig``, what ``Synthesizer`` furnishes with.

Each field carries a ``Setting`` in its metadata: its type, its range (numbers) or its
choices (names), one line on what it does, and where it is exposed: as a parameter of
``scene_synth_node`` (``node``) and as a flag of ``scene-synth generate``, ``complete`` and
``suggest`` (``flag``). The node's parameters (``server.ServerConfig``, ``server.PARAMETERS``
and from them the node's descriptors and ``config/scene_synth_node.yaml``) and the command
line's flags are derived from this table, and ``check_value`` enforces the same range for
all of them, so that a value one front end refuses, every front end refuses.

The robot is one field here (``robot.Robot``, which checks its own ranges); the node and the
command line set it through three flat settings (``ROBOT_SETTINGS``).

Nothing heavy is imported here (no torch): ``scene-synth --help`` and the node's parameter
table read it.
"""
from __future__ import annotations

from dataclasses import MISSING, Field, dataclass, field, fields
import math
import os
from typing import Any

from .catalog import Catalog
from .errors import ConfigError, number, quoted
from .networks.config import RUNTIMES
from .rules.robot import CLEARANCE_RANGE, RADIUS_RANGE, REACH_RANGE, Robot

SETTING = 'setting'                     # the metadata key of a field's ``Setting``
DEVICES = ('auto', 'cpu', 'cuda')       # torch devices (auto: cuda when there is one)


@dataclass(frozen=True)
class Setting:
    """What one configuration field is (see the module docstring)."""

    kind: type                                  # bool, int, float, str, tuple (names), Robot
    description: str                            # what it does, one line
    bounds: tuple[float, float] | None = None   # inclusive range of a number
    choices: tuple[str, ...] | None = None      # the strings it may be
    node: bool = False            # a parameter of scene_synth_node under the field's name
    flag: str | None = None       # its command-line flag
    read_only: bool = False       # node: set when the node starts, never changed after
    optional: bool = False        # None is allowed (meaning: the default behaviour)
    # Other types code may hand over in its place (never from a user's text).
    accepts: tuple[type, ...] = ()

    def __post_init__(self):
        if self.bounds is not None:      # a float's range of floats: the node reads its type
            object.__setattr__(self, 'bounds', tuple(self.kind(b) for b in self.bounds))

    @property
    def limits(self) -> tuple | None:
        """The range or the choices, whichever it has (None: any value of its type)."""
        return self.bounds if self.bounds is not None else self.choices

    def limits_text(self) -> str:
        """The range (``0.05 to 5``) or the choices (``one of auto, cpu, cuda``) in words;
        '' for neither."""
        if self.bounds is not None:
            lo, hi = (str(b) if isinstance(b, int) else number(b) for b in self.bounds)
            return f'{lo} to {hi}'
        return f'one of {", ".join(self.choices)}' if self.choices is not None else ''


def setting(default: Any, description: str, *, kind: type | None = None, **more) -> Field:
    """A dataclass field with its ``Setting`` (``kind``: that of ``default`` unless given)."""
    return field(default=default, metadata={SETTING: Setting(
        kind or type(default), description, **more)})


def check_value(label: str, value: Any, s: Setting) -> Any:
    """``value`` for a setting ``s`` (whole numbers as the setting's type), or ConfigError in
    one sentence naming ``label`` (the field, parameter or flag the value came in)."""
    if value is None and s.optional:
        return value
    if s.accepts and isinstance(value, s.accepts):
        return value
    if s.kind is bool:
        if not isinstance(value, bool):
            raise ConfigError(f'{label} must be true or false, got {quoted(value)}')
        return value
    if s.kind in (int, float):
        return _check_number(label, value, s)
    if s.kind is str:
        if not isinstance(value, str):
            raise ConfigError(f'{label} must be a string, got {quoted(value)}')
        if s.choices is not None and value not in s.choices:
            raise ConfigError(f'{label} must be one of {", ".join(s.choices)}, '
                              f'got {quoted(value)}')
        return value
    if s.kind is tuple:
        if not isinstance(value, tuple) or not all(isinstance(v, str) for v in value):
            raise ConfigError(f'{label} must be a tuple of names, got {quoted(value)}')
        return value
    if not isinstance(value, s.kind):
        raise ConfigError(f'{label} must be a {s.kind.__name__}, got {quoted(value)}')
    return value


def _check_number(label: str, value: Any, s: Setting) -> int | float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ConfigError(f'{label} must be a number, got {quoted(value)}')
    try:
        as_float = float(value)
    except OverflowError:                   # an integer past what a float holds
        as_float = math.copysign(math.inf, value)
    if s.kind is int and not as_float.is_integer():
        raise ConfigError(f'{label} must be an integer, got {quoted(value)}')
    if s.bounds is not None and not (math.isfinite(as_float)
                                     and s.bounds[0] <= value <= s.bounds[1]):
        raise ConfigError(f'{label} must be between {s.bounds[0]} and {s.bounds[1]}, '
                          f'got {quoted(value)}')
    return s.kind(value)


def settings_of(cls) -> dict[str, tuple[Setting, Any]]:
    """Each field of the dataclass ``cls`` that has a ``Setting``: name -> (setting,
    default), in field order."""
    return {f.name: (f.metadata[SETTING], f.default) for f in fields(cls)
            if SETTING in f.metadata}


@dataclass
class SynthConfig:
    """How ``Synthesizer`` furnishes a room; refuses an out-of-range value in one sentence
    (``ConfigError``). Passed to the synthesizer, or with each call of it."""

    location_temperature: float = setting(
        0.8, 'temperature of the location distribution (paper: 0.8)',
        bounds=(0.05, 5.0), node=True, flag='--temperature')
    max_objects: int = setting(30, 'most objects in one room', bounds=(1, 100), node=True,
                               flag='--max-objects')
    location_samples: int = setting(
        12, 'locations drawn for one category draw before it counts as not fitting',
        bounds=(1, 100))
    # Rooms furnished in lockstep (``lockstep``) batch their decoding anyway; decoding
    # ahead here decodes placements that are never tried.
    location_batch: int = setting(
        1, 'locations drawn and decoded together (1: each only once the ones before it '
        'failed)', bounds=(1, 100))
    # The networks answer a centroid with a blob as wide as their training target, and a
    # draw anywhere in it misses a wall by up to a pixel.
    location_mode: bool = setting(
        True, "move each of a category's first draws (centre_draws) to the centre of the "
        'blob of the location distribution it fell in')
    # Every draw of one blob decoded to its centre is the same point: a spot refused once
    # would be refused every time, where a draw a pixel aside may fit.
    centre_draws: int = setting(
        4, "how many of a category's draws location_mode moves to their blob's centre; the "
        'later ones fall anywhere in their pixel', bounds=(0, 100))
    # A departure from the paper, as the partner zones are: the location module's heat map
    # can miss the only free side of a partner.
    zone_samples: int = setting(
        8, "locations drawn uniformly over a group piece's partner zone once the location "
        "module's draws there all failed", bounds=(0, 100))
    models_per_location: int = setting(
        3, 'catalog models tried at one location, nearest footprint first', bounds=(1, 100))
    category_attempts: int = setting(
        4, 'category draws for one insertion before it ends with nothing fitting',
        bounds=(1, 100))
    # Not for a module that draws from its learned spread (``dimensions_noise``): its draw is
    # the size, and co-occurrence would hand near ties to the corpus's frequent models.
    fit_slack: float = setting(
        0.15, 'log-footprint slack within which the models that co-occur with those in the '
        'room come first, for dimensions modules that answer their mean', bounds=(0.0, 1.0))
    snap_threshold: float = setting(
        0.5, "snap a yaw to the room's axes when the snap classifier's probability is above "
        'this (1: never)', bounds=(0.0, 1.0))
    # The location module sees the room at about 9 cm a pixel: furniture meant to stand
    # against a wall lands a few centimetres off it or through it.
    wall_reach: float = setting(
        0.25, 'move first-tier furniture that stands within this distance (m) of a wall '
        'onto the wall (0: never)', bounds=(0.0, 1.0))
    robot: Robot = setting(
        Robot(), 'the robot every room is furnished for (the node and the command line set '
        'it with robot_radius, robot_reach and robot_clearance)')
    # A departure from the paper: the networks leave windows and the fronts of storage and
    # fixtures less clear, wall furniture off its wall, baths out of corners, pieces of a
    # group further from their partners, a kitchen's sink, stove and fridge further apart
    # and a hallway's path narrower than the training rooms do.
    insertion_rules: tuple[str, ...] = setting(
        ('windows_clear', 'storage_clearance', 'wall_contact', 'fixture_clearance',
         'bath_in_corner', 'chair_at_table', 'nightstand_by_bed', 'bidet_by_toilet',
         'coffee_table_has_seating', 'work_triangle', 'fronts_open', 'dining_seats',
         'hallway_path'),
        'the design rules insertion keeps (names of rules.insertion.INSERTION_RULES)')
    # A departure from the paper, as the rules kept at insertion are.
    owed_partners: tuple[str, ...] = setting(
        ('coffee_table_has_seating', 'double_bed_has_nightstand', 'work_triangle'),
        'rules whose broken cases get one more draw among their partners when the category '
        'module says STOP (names of rules.insertion.OWED_RULES; work_triangle: a kitchen '
        'without its sink, stove or fridge)')
    device: str = setting('cpu', 'torch device for the networks', choices=DEVICES,
                          node=True, flag='--device')
    runtime: str = setting(
        'auto', 'what runs the networks: auto (onnxruntime on the CPU where it is installed, '
        'else torch), torch or onnxruntime; their rooms are equal in distribution',
        choices=RUNTIMES, node=True, flag='--runtime')
    # A path, so that batches can send it to their workers; a loaded catalog serves one
    # process too.
    catalog: str | None = setting(
        None, 'a catalog of your own models (`scene-synth catalog build`): their categories '
        'are furnished with them, the others with the procedural models', kind=str,
        optional=True, accepts=(os.PathLike, Catalog), flag='--catalog')

    def __post_init__(self):
        self.validate()

    def validate(self) -> None:
        """ConfigError, one sentence naming the field, for the first value out of its range
        (a config changed after it was made is checked again here)."""
        for name, (s, _) in settings_of(SynthConfig).items():
            check_value(name, getattr(self, name), s)


# The robot's three numbers as the node's parameters and the command line's flags set them;
# their ranges are the robot's own (``robot.Robot`` checks them).
ROBOT_SETTINGS: dict[str, tuple[Setting, float]] = {
    'robot_radius': (Setting(
        float, 'radius of the round robot every room is furnished for: it drives between all '
        'doors and reaches every object (m)', bounds=RADIUS_RANGE, node=True,
        flag='--robot-radius'), Robot().radius),
    'robot_reach': (Setting(
        float, "the robot's arm's reach: how close its body must get to an object's front "
        '(m)', bounds=REACH_RANGE, node=True, flag='--robot-reach'), Robot().reach),
    'robot_clearance': (Setting(
        float, 'clearance the robot keeps from furniture and walls while driving (m)',
        bounds=CLEARANCE_RANGE, node=True, flag='--robot-clearance'), Robot().clearance),
}


@dataclass
class MapConfig:
    """The occupancy map of a furnished room (``occupancy.py``), as ``scene-synth map`` and
    the node's ``~/map`` make it."""

    map_resolution: float = setting(0.05, 'metres a cell of the occupancy map',
                                    bounds=(0.01, 1.0), flag='--resolution')
    map_scan_height: float = setting(
        0.3, "height above the floor at which the robot's laser sees obstacles, for the "
        'occupancy map (m)', bounds=(0.0, 3.0), flag='--scan-height')

    def __post_init__(self):
        for name, (s, _) in settings_of(MapConfig).items():
            setattr(self, name, check_value(name, getattr(self, name), s))


def shared(name: str, default: Any = MISSING) -> Field:
    """A field of another configuration (the node's) that is the setting ``name`` of
    synthesis or of its map (a field of ``SynthConfig`` or ``MapConfig``, or one of
    ``ROBOT_SETTINGS``): the same setting, with its default unless ``default`` is given."""
    s, own = (ROBOT_SETTINGS.get(name) or settings_of(MapConfig).get(name)
              or settings_of(SynthConfig)[name])
    return field(default=own if default is MISSING else default, metadata={SETTING: s})


def flag_settings() -> dict[str, tuple[Setting, Any]]:
    """The fields of ``SynthConfig`` with a command-line flag: name -> (setting, default)
    (the robot's flags are those of ``ROBOT_SETTINGS``)."""
    return {n: v for n, v in settings_of(SynthConfig).items() if v[0].flag}
