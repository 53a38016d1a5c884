#!/usr/bin/env bash
# Issue 11, part 3, on a GPU machine: does the location module learn more with a longer
# schedule and more rooms, with and without the per-pixel offsets? Also runs the CUDA tests.
#
#   OUT=runs/gpu [RUNS="bedroom:compact_long office:offsets"] [LOADER_WORKERS=4] \
#       [TIMING_ROOMS=0] bash benchmarks/gpu_location.sh [STEPS]
#
# Trains, side by side, the location module of config/compact_long.yaml (5,000 rooms, STEPS
# steps, default the config's 10,000; validated every 1,000) for each ROOM_TYPE:VARIANT of
# RUNS (default: bedroom with offsets off and on, office off; `offsets` is the same
# configuration with location_offsets on), each with LOADER_WORKERS DataLoader processes
# making its batches, and exports each as a bundle whose other modules are the shipped ones
# (--others-from). Writes to $OUT: the bundles, each run's log.jsonl (the learning curve:
# val_loss per 1,000 steps) and the CUDA tests' output. With TIMING_ROOMS, then times that
# many complete bedrooms with the networks on the GPU and on the CPU (bench_synth.py). On a
# CPU machine it runs as well, only slower. Where the machine's Python lacks a dependency,
# wheels in .whl/ are installed first (see the device tool's notes). Learning curves: .venv/bin/python benchmarks/learning_curves.py $OUT/*.log.jsonl
set -u
OUT=${OUT:-runs/gpu}
STEPS=${1:-}
TRAIN_LIMIT=${TRAIN_LIMIT:-420}
RUNS=${RUNS:-bedroom:compact_long bedroom:offsets office:compact_long}
LOADER_WORKERS=${LOADER_WORKERS:-4}
TIMING_ROOMS=${TIMING_ROOMS:-0}
mkdir -p "$OUT"
export PYTHONUNBUFFERED=1
if ! python3 -c 'import shapely, trimesh, jsonschema' 2>/dev/null; then
  python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
    --target /tmp/site .whl/*.whl || exit 1
  export PYTHONPATH=/tmp/site
fi
export PYTHONPATH=$PWD${PYTHONPATH:+:$PYTHONPATH}
python3 - <<'EOF'
import torch
print('torch', torch.__version__, 'cuda', torch.cuda.is_available(),
      torch.cuda.get_device_name(0) if torch.cuda.is_available() else '')
EOF

work=$(mktemp -d)
sed 's/location_offsets: false/location_offsets: true/' config/compact_long.yaml \
  > "$work/offsets.yaml"
if [ -n "$STEPS" ]; then
  for f in config/compact_long.yaml "$work/offsets.yaml"; do
    sed -E "s/^  location: \{steps: [0-9]+,/  location: {steps: $STEPS,/" "$f" \
      > "$work/$(basename "$f").tmp" && mv "$work/$(basename "$f").tmp" "$work/$(basename "$f")"
  done
else
  cp config/compact_long.yaml "$work/compact_long.yaml"
fi

(timeout 300 python3 -m pytest -q -p no:cacheprovider tests/test_cuda.py \
  > "$OUT/cuda_tests.log" 2>&1; echo "exit $?" >> "$OUT/cuda_tests.log") &
tests=$!

pids=""
for run in $RUNS; do
  rt=${run%%:*}; conf=${run##*:}
  name=${rt}_${conf}
  timeout "$TRAIN_LIMIT" python3 -m scene_synth_ros.cli train --room-type "$rt" \
    --modules location --others-from scene_synth_ros/weights --config "$work/$conf.yaml" \
    --loader-workers "$LOADER_WORKERS" --threads 0 --run-dir "$work/run_$name" \
    --weights-dir "$work/weights_$name" --quiet > "$work/$name.out" 2>&1 &
  pids="$pids $!"
done
for p in $pids; do wait "$p"; done
wait "$tests"
for run in $RUNS; do
  rt=${run%%:*}; run=${rt}_${run##*:}
  cp "$work/run_$run/$rt/log.jsonl" "$OUT/$run.log.jsonl" 2>/dev/null
  cp "$work/weights_$run/$rt.pt" "$OUT/$run.pt" 2>/dev/null
  echo "== $run"; tail -n 12 "$work/$run.out"
done
echo "== CUDA tests"; tail -n 15 "$OUT/cuda_tests.log"
if [ "$TIMING_ROOMS" -gt 0 ]; then
  for device in cuda cpu; do
    python3 benchmarks/bench_synth.py -n 0 --timing-rooms "$TIMING_ROOMS" --device "$device"
  done
fi
ls -la "$OUT"
