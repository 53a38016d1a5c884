"""An import inside a function is for a heavy optional dependency only, or for a module of
the package that imports one at its top (so that, say, the node starts without torch), with
its reason on the line; everything else is imported at the top of its module (issue 34). The
command line (``cli/``) imports the package inside its handlers so that ``--help`` stays
fast."""
import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / 'scene_synth_ros'

# Heavy, or present only with an extra or in a ROS install.
OPTIONAL = {'torch', 'matplotlib', 'trimesh', 'pxr', 'mujoco', 'pybullet', 'onnx',
            'onnxruntime', 'ray', 'ament_index_python'}

def _function_imports():
    """(file relative to the package, module as written, line text) of every import inside
    a function, outside ``cli/``."""
    for path in sorted(PACKAGE.rglob('*.py')):
        rel = path.relative_to(PACKAGE)
        if rel.parts[0] == 'cli':
            continue
        text = path.read_text(encoding='utf-8')
        lines = text.splitlines()
        for node in ast.walk(ast.parse(text)):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for n in ast.walk(node):
                if isinstance(n, ast.Import):
                    names = [a.name for a in n.names]
                elif isinstance(n, ast.ImportFrom):
                    names = ['.' * n.level + (n.module or '')]
                else:
                    continue
                for name in names:
                    yield rel.as_posix(), name, lines[n.lineno - 1]


def _heavy(rel: str, name: str) -> bool:
    """Whether ``name`` (as imported in the package file ``rel``) is a heavy optional
    dependency, or a module of the package that imports one at its top."""
    if not name.startswith('.'):
        return name.split('.')[0] in OPTIONAL
    level = len(name) - len(name.lstrip('.'))
    base = (PACKAGE / rel).parent
    for _ in range(level - 1):
        base = base.parent
    target = base.joinpath(*name.lstrip('.').split('.'))
    path = target / '__init__.py' if target.is_dir() else target.with_suffix('.py')
    if not path.is_file():
        return False
    for n in ast.parse(path.read_text(encoding='utf-8')).body:
        if isinstance(n, ast.Import) and any(a.name.split('.')[0] in OPTIONAL
                                             for a in n.names):
            return True
        if isinstance(n, ast.ImportFrom) and n.level == 0 and \
                (n.module or '').split('.')[0] in OPTIONAL:
            return True
    return False


def test_imports_inside_functions_are_heavy_optional_ones_with_a_reason():
    wrong = [f'{f}: {line.strip()}' for f, name, line in _function_imports()
             if not _heavy(f, name) or '#' not in line]
    assert not wrong, 'import these at the top of the module, or say why not on the line:\n' \
        + '\n'.join(wrong)
