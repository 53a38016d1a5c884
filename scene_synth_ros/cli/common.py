"""What the command groups share: the user-error type, room-type arguments, loading a scene
file with a one-sentence error, and the object table and file outputs of a furnished room."""
from __future__ import annotations

import math
from pathlib import Path

from ..categories import PAPER, Vocabulary
from ..errors import SceneSynthError
from ..synth_config import ROBOT_SETTINGS, Setting, check_value

EXIT_BAD_INPUT = 2
WEIGHTS_DIR_HELP = "trained bundles (default: the package's weights/)"


class UserError(SceneSynthError):
    """Bad command-line input: printed as one sentence, exit code 2, no traceback."""


def data_set_option(parser) -> None:
    """``--weights-dir`` on a command that only reads scenes: the weights that furnished
    them, whose data set's room types and categories the scenes use."""
    parser.add_argument('--weights-dir', help='weights trained on an imported data set '
                        '(scene-synth train --data): the room types and categories of scenes '
                        'they furnished')


def weights_vocabulary(args) -> Vocabulary:
    """The room types and categories a command reads room types and scenes with: those of
    the data set ``args.weights_dir``'s bundles were trained on, else the paper's. ``main``
    sets it as ``args.vocabulary``."""
    if getattr(args, 'weights_dir', None) and getattr(args, 'defines_room_types', True):
        from ..networks.served import weights_vocabulary as of_weights
        return of_weights(args.weights_dir)
    return PAPER


def room_types(value: str, vocabulary: Vocabulary = PAPER) -> list[str]:
    """The room types a ``--room-type`` value names: one, or every one for ``all`` (the
    package's room types, or every room type of ``vocabulary``, the weights' in use)."""
    if value == 'all':
        return list(vocabulary.room_types)
    return [vocabulary.resolve(value)]


def load_catalog(path: str | None, vocabulary: Vocabulary = PAPER):
    """The catalog of a ``--catalog`` option: the procedural one without it; its categories
    are those of ``vocabulary``."""
    from ..user_catalog import load_catalog as load  # trimesh and the schemas: not for --help
    return load(path, vocabulary)


def load_scene_file(path: str, catalog=None, vocabulary: Vocabulary = PAPER):
    """The scene (or room layout) in ``path``, its model ids those of ``catalog`` (default:
    the procedural catalog), its room types and categories those of ``vocabulary``; an
    error names the file."""
    from ..schema import load_scene
    return _named(path, load_scene, catalog, vocabulary)


def load_layout_file(path: str, catalog=None, vocabulary: Vocabulary = PAPER):
    """``load_scene_file`` that also reads a house layout or scene, as a
    ``house.HouseScene``."""
    from ..schema import load_layout
    return _named(path, load_layout, catalog, vocabulary)


def _named(path: str, read, *args):
    """``read(path, *args)``, its errors as UserErrors that name the file."""
    from ..schema import SceneValidationError
    try:
        return read(path, *args)
    except FileNotFoundError:
        raise UserError(f'{path}: no such file') from None
    except SceneValidationError as e:
        # The validator says what is wrong inside the document, not which document.
        raise UserError(f'{path}: {e}') from None


def object_table(objects, title: str = '') -> str:
    """Objects one per line: id, category, model, position, yaw, size and support."""
    lines = [title] if title else []
    lines.append(f'  {"id":18s} {"category":16s} {"model":18s} {"x":>6s} {"y":>6s} {"z":>5s} '
                 f'{"yaw°":>6s} {"w x d x h (m)":>17s}  on')
    for o in objects:
        lines.append(f'  {o.id:18s} {o.category:16s} {o.model_id:18s} {o.position[0]:6.2f} '
                     f'{o.position[1]:6.2f} {o.position[2]:5.2f} '
                     f'{math.degrees(o.yaw):6.1f} {o.width:5.2f}x{o.depth:4.2f}x{o.height:4.2f}'
                     f'  {o.support or ""}')
    return '\n'.join(lines)


def write_scene(scene, out: str | None, png: str | None, title: str, catalog=None,
                vocabulary: Vocabulary = PAPER) -> None:
    """Save ``scene`` as JSON to ``out`` and/or as a picture to ``png`` (either may be None),
    creating their directories and saying what was written; its model ids are those of
    ``catalog`` (default: the procedural catalog), its categories those of ``vocabulary``."""
    if out:
        from ..schema import save_scene
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        save_scene(scene, out, catalog, vocabulary)
        print(f'wrote {out}')
    if png:
        from ..plot import save_png
        Path(png).parent.mkdir(parents=True, exist_ok=True)
        save_png(scene, png, title=title, vocabulary=vocabulary)
        print(f'wrote {png}')


def setting_flag(c, s: Setting, default, value=None) -> None:
    """The flag of the synthesis setting ``s`` on parser ``c``: its type, choices, range and
    help from the setting; ``value`` is what it holds when not given (None: the setting's
    ``default`` applies). ``flag_value`` checks its range."""
    text = s.description
    if s.bounds is not None:            # argparse shows the choices
        text += f'; {s.limits_text()}'
    if default is not None:
        text += f' (default {default})'
    c.add_argument(s.flag, dest=flag_dest(s), type=s.kind if s.kind in (int, float) else None,
                   choices=s.choices, default=value, help=text)


def flag_dest(s: Setting) -> str:
    """Where argparse keeps the value of the flag of ``s``."""
    return s.flag.removeprefix('--').replace('-', '_')


def flag_value(s: Setting, args):
    """The value ``args`` hold for the flag of ``s`` (None when it has none), or an error
    naming the flag when it is out of the setting's range."""
    value = getattr(args, flag_dest(s), None)
    return None if value is None else check_value(s.flag, value, s)


def robot_options(c) -> None:
    """The robot every room is furnished for (``robot.Robot``), one flag per number."""
    for s, default in ROBOT_SETTINGS.values():
        setting_flag(c, s, default, value=default)


def robot_from(args):
    """The ``robot.Robot`` of ``robot_options``; an error naming the flag when they make
    none (the robot checks the ranges: they are its own)."""
    from ..rules.robot import Robot
    values = {name.removeprefix('robot_'): getattr(args, flag_dest(s))
              for name, (s, _) in ROBOT_SETTINGS.items()}
    try:
        return Robot(**values)
    except ValueError as e:
        raise UserError(f'--{e}'.replace('--robot ', '--robot-')) from None
