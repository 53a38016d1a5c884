#!/usr/bin/env bash
# Training runs, the CUDA tests and the CUDA throughput benchmark on a GPU machine (issue 11,
# part 3: do the networks learn more with longer schedules, more rooms, other settings?;
# issue 16: rooms in lockstep on a GPU).
#
#   OUT=runs/gpu [MODULE=location] [RUNS="bedroom:compact_long office:offsets"]
#       [LOADER_WORKERS=4] [TRAIN_LIMIT=420] [TIMING_ROOMS=0] [BENCH_ROOMS=0] \
#       bash benchmarks/gpu_train.sh [STEPS]
#
# Trains, side by side, the module MODULE (default location) for each ROOM_TYPE:CONFIG of
# RUNS, CONFIG a file of config/ without its .yaml (default: bedroom with compact_long and
# offsets, office with compact_long; `offsets` is compact_long.yaml with location_offsets
# on), each with LOADER_WORKERS DataLoader processes making its batches (they change no
# batch), for at most TRAIN_LIMIT seconds. STEPS, where given, replaces the config's steps
# of the module. Each finished run is exported as a bundle whose other modules are the
# shipped ones (--others-from). Writes to $OUT: each run's log.jsonl (its learning curve),
# its bundle where it finished, else its last checkpoint (resume it on any machine with the
# same command and --run-dir), the CUDA tests' output and, with BENCH_ROOMS, rooms per second
# of that many bedrooms in lockstep of 1, 8 and 32 on the GPU (bench_batch.py). With
# TIMING_ROOMS, then times that many complete bedrooms with the networks on the GPU and on the
# CPU (bench_synth.py). On a CPU machine it runs as well, only slower. Where the machine's
# Python lacks a dependency, wheels in .whl/ are installed first (see the device tool's
# notes). Learning curves: .venv/bin/python benchmarks/learning_curves.py $OUT/*.log.jsonl
set -u
OUT=${OUT:-runs/gpu}
STEPS=${1:-}
MODULE=${MODULE:-location}
TRAIN_LIMIT=${TRAIN_LIMIT:-420}
RUNS=${RUNS:-bedroom:compact_long bedroom:offsets office:compact_long}
LOADER_WORKERS=${LOADER_WORKERS:-4}
TIMING_ROOMS=${TIMING_ROOMS:-0}
BENCH_ROOMS=${BENCH_ROOMS:-0}
mkdir -p "$OUT"
export PYTHONUNBUFFERED=1
if ! python3 -c 'import shapely, trimesh, jsonschema, greenlet' 2>/dev/null; then
  python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
    --target /tmp/site .whl/*.whl || exit 1
  export PYTHONPATH=/tmp/site
fi
export PYTHONPATH=$PWD${PYTHONPATH:+:$PYTHONPATH}
python3 - <<'PY'
import torch
print('torch', torch.__version__, 'cuda', torch.cuda.is_available(),
      torch.cuda.get_device_name(0) if torch.cuda.is_available() else '')
PY

work=$(mktemp -d)
for run in $RUNS; do
  conf=${run##*:}
  [ -f "$work/$conf.yaml" ] && continue
  if [ "$conf" = offsets ]; then
    sed 's/location_offsets: false/location_offsets: true/' config/compact_long.yaml
  else
    cat "config/$conf.yaml"
  fi > "$work/$conf.yaml" || exit 1
  if [ -n "$STEPS" ]; then
    sed -i -E "s/^  $MODULE: \{steps: [0-9]+,/  $MODULE: {steps: $STEPS,/" "$work/$conf.yaml"
  fi
done

(timeout 300 python3 -m pytest -q -p no:cacheprovider tests/test_cuda.py \
  > "$OUT/cuda_tests.log" 2>&1; echo "exit $?" >> "$OUT/cuda_tests.log") &
tests=$!

pids=""
for run in $RUNS; do
  rt=${run%%:*}; conf=${run##*:}
  name=${rt}_${conf}
  timeout "$TRAIN_LIMIT" python3 -m scene_synth_ros.cli train --room-type "$rt" \
    --modules "$MODULE" --others-from scene_synth_ros/weights --config "$work/$conf.yaml" \
    --loader-workers "$LOADER_WORKERS" --threads 0 --run-dir "$work/run_$name" \
    --weights-dir "$work/weights_$name" --quiet > "$work/$name.out" 2>&1 &
  pids="$pids $!"
done
wait "$tests"
if [ "$BENCH_ROOMS" -gt 0 ]; then
  timeout 240 python3 benchmarks/bench_batch.py -n "$BENCH_ROOMS" --workers 1 \
    --lockstep 1 8 32 --device cuda --runtime torch > "$OUT/bench_cuda.log" 2>&1
  echo "exit $?" >> "$OUT/bench_cuda.log"
fi
for p in $pids; do wait "$p"; done
for run in $RUNS; do
  rt=${run%%:*}; run=${rt}_${run##*:}
  cp "$work/run_$run/$rt/log.jsonl" "$OUT/$run.log.jsonl" 2>/dev/null
  cp "$work/weights_$run/$rt.pt" "$OUT/$run.pt" 2>/dev/null \
    || cp "$work/run_$run/$rt/$MODULE.ckpt" "$OUT/$run.$MODULE.ckpt" 2>/dev/null
  echo "== $run"; tail -n 12 "$work/$run.out"
done
echo "== CUDA tests"; tail -n 15 "$OUT/cuda_tests.log"
[ -f "$OUT/bench_cuda.log" ] && { echo "== CUDA throughput"; tail -n 20 "$OUT/bench_cuda.log"; }
if [ "$TIMING_ROOMS" -gt 0 ]; then
  for device in cuda cpu; do
    python3 benchmarks/bench_synth.py -n 0 --timing-rooms "$TIMING_ROOMS" --device "$device"
  done
fi
ls -la "$OUT"
