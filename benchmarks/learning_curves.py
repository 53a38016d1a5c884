"""Learning curves of training runs: each module's held-out metrics against its step.

    .venv/bin/python benchmarks/learning_curves.py RUN/log.jsonl ... [--module location]
                                                   [--baseline ROOM_TYPE --config YAML]
                                                   [--baseline-weights DIR]

Reads the JSON lines that ``scene-synth train`` writes (``<run-dir>/<room type>/log.jsonl``)
and prints, per log, the validation rows of the module (``val_loss``, and ``val_offset_error``
where the location module regresses offsets). With ``--baseline``, the module of that room
type in the shipped weights (or in ``--baseline-weights``) is evaluated on the same held-out
examples as the runs of ``--config`` (its held-out rooms, its training seed), so that a
longer run is read against the schedule those weights had.
"""
import argparse
import json
from pathlib import Path
import sys

ROOT = Path(__file__).resolve().parent.parent


def curve(path: Path, module: str) -> list[dict]:
    rows = []
    for line in path.read_text(encoding='utf-8').splitlines():
        entry = json.loads(line)
        if entry.get('module') == module and any(k.startswith('val_') for k in entry):
            rows.append(entry)
    return rows


def baseline(room_type: str, module: str, config: str, weights: str | None
             ) -> dict[str, float]:
    import torch
    torch.set_num_threads(1)
    from scene_synth_ros.networks.bundle import load_bundle
    from scene_synth_ros.networks.config import PipelineConfig
    from scene_synth_ros.networks.examples import ExampleSource
    from scene_synth_ros.networks.train import evaluate, load_corpus
    from scene_synth_ros.paths import weights_dir
    cfg = PipelineConfig.from_yaml(config)
    t, m = cfg.train, cfg.model
    val = ExampleSource(room_type, load_corpus(room_type, cfg).val, m.resolution,
                        m.location_resolution, target_radius=t.location_target_radius)
    bundle = load_bundle(Path(weights or weights_dir()) / f'{room_type}.pt')
    return evaluate(module, bundle.networks[module].float(), val, cfg, 'cpu', t.seed,
                    t.val_examples)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('logs', nargs='+', type=Path)
    ap.add_argument('--module', default='location')
    ap.add_argument('--baseline', help='a room type: evaluate its shipped module too')
    ap.add_argument('--baseline-weights', help="the baseline's weights directory (default: "
                    "the package's)")
    ap.add_argument('--config', default=str(ROOT / 'config' / 'compact_long.yaml'),
                    help='the configuration of the runs (held-out rooms and seed)')
    args = ap.parse_args()
    for path in args.logs:
        rows = curve(path, args.module)
        print(f'{path} ({args.module}, {len(rows)} validations)')
        keys = sorted({k for r in rows for k in r if k.startswith('val_')})
        print(f'{"step":>7s} ' + ' '.join(f'{k:>18s}' for k in keys))
        for r in rows:
            print(f'{r["step"]:7d} ' + ' '.join(f'{r.get(k, float("nan")):18.4f}' for k in keys))
    if args.baseline:
        m = baseline(args.baseline, args.module, args.config, args.baseline_weights)
        print(f'{args.baseline_weights or "shipped"} {args.baseline} {args.module} on the '
              'same held-out examples: ' +
              ', '.join(f'val_{k} {v:.4f}' for k, v in m.items()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
