"""Fuzzed room layouts and payloads through the readers and what serves an accepted room.

    .venv/bin/python benchmarks/fuzz_inputs.py [-n 10000] [--seed 0]

Draws ``n`` layouts from ``tests/fuzz.py`` (the strategies of the property-based tests) and
``n / 4`` arbitrary payloads; each is read, and an accepted room is written back, read
again, turned into markers and exported to SDF and glTF. Prints how many were accepted and
refused, every exception that is not the package's own (there should be none), sentences
that are not one bounded printable line, and the slowest inputs.
"""
import argparse
from collections import Counter
from pathlib import Path
import re
import sys
import tempfile
import time

from benchlib import tests_module
from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st

from scene_synth_ros.errors import MAX_SENTENCE, SceneSynthError
from scene_synth_ros.export import export_gltf, export_sdf
from scene_synth_ros.markers import scene_markers
from scene_synth_ros.schema import dump_scene, parse_room_layout, parse_scene

fuzz = tests_module('fuzz')


def _brief(payload) -> str:
    try:
        return repr(payload)[:100]
    except ValueError:          # an integer too long for Python to write
        return f'<{type(payload).__name__} that Python cannot write out>'


def _reason(sentence: str, path: str) -> str:
    """A refusal's kind: the sentence without its path and numbers, cut short."""
    text = sentence[len(path):] if path and sentence.startswith(path) else sentence
    return re.sub(r"-?[0-9][0-9.e+-]*|'[^']*'", '#', text).strip()[:60]


class Tally:
    def __init__(self):
        self.accepted = self.refused = 0
        self.crashes: list[str] = []
        self.reasons: Counter = Counter()
        self.bad_sentences: list[str] = []
        self.slowest: list[tuple[float, str]] = []

    def run(self, payload, tmp: Path) -> None:
        t0 = time.perf_counter()
        try:
            scene = parse_room_layout(payload)
            text = dump_scene(scene)
            if dump_scene(parse_scene(text)) != text:
                self.crashes.append('round trip changed the scene')
            scene_markers(scene, 'cube')
            export_sdf(scene, tmp / 'room.sdf', tmp / 'meshes')
            export_gltf(scene, tmp / 'room.glb')
            self.accepted += 1
        except SceneSynthError as e:
            self.refused += 1
            s = str(e)
            self.reasons[_reason(s, getattr(e, 'path', ''))] += 1
            if not (s and len(s) <= MAX_SENTENCE and s.isprintable()):
                self.bad_sentences.append(repr(s[:120]))
        except Exception as e:   # what the readers must never let through
            self.crashes.append(f'{type(e).__name__}: {str(e)[:160]}')
        dt = time.perf_counter() - t0
        if len(self.slowest) < 3 or dt > self.slowest[-1][0]:
            self.slowest = sorted(self.slowest + [(dt, _brief(payload))], reverse=True)[:3]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=10000, help='fuzzed layouts')
    ap.add_argument('--seed', type=int, default=0)
    args = ap.parse_args()
    tally = Tally()
    opts = settings(max_examples=args.n, database=None, deadline=None,
                    suppress_health_check=list(HealthCheck))
    with tempfile.TemporaryDirectory() as tmp:
        @seed(args.seed)
        @opts
        @given(fuzz.layouts(wild=False) | fuzz.layouts())
        def fuzz_layouts(layout):
            tally.run(layout, Path(tmp))

        @seed(args.seed)
        @settings(opts, max_examples=max(args.n // 4, 1))
        @given(st.one_of(fuzz.JSON, st.text(max_size=400)))
        def fuzz_payloads(payload):
            tally.run(payload, Path(tmp))

        t0 = time.perf_counter()
        fuzz_layouts()
        fuzz_payloads()
        seconds = time.perf_counter() - t0
    total = tally.accepted + tally.refused + len(tally.crashes)
    print(f'{total} inputs in {seconds:.1f} s: {tally.accepted} accepted and served, '
          f'{tally.refused} refused in one sentence, {len(tally.crashes)} other exceptions, '
          f'{len(tally.bad_sentences)} sentences not one bounded printable line')
    for reason, count in tally.reasons.most_common(12):
        print(f'  refused {count:5d}: {reason}')
    for c in sorted(set(tally.crashes))[:20]:
        print('  crash:', c)
    for s in tally.bad_sentences[:10]:
        print('  sentence:', s)
    for dt, text in tally.slowest:
        print(f'  slowest: {dt:.3f} s  {text}')
    return 1 if tally.crashes or tally.bad_sentences else 0


if __name__ == '__main__':
    sys.exit(main())
