#!/usr/bin/env bash
# The shipped weights' one command on a GPU machine, the CUDA tests and the CUDA throughput
# benchmarks (issue 35: shipped weights that one command makes; issue 16: rooms in lockstep
# on a GPU).
#
#   OUT=runs/gpu [ROOM_TYPES=all] [JOBS=3] [LOADER_WORKERS=4] [CONFIG=config/shipped.yaml]
#       [TRAIN_LIMIT=420] [TIMING_ROOMS=0] [BENCH_ROOMS=0] bash benchmarks/gpu_train.sh
#
# Runs `make weights DEVICE=cuda` (the Makefile's header) for at most TRAIN_LIMIT seconds:
# every module of each room type of ROOM_TYPES as CONFIG states, JOBS processes side by side
# on the GPU, each with LOADER_WORKERS DataLoader processes making its batches ahead (they
# change no batch). Its run directory is $OUT/run and its bundles go to $OUT/weights: where it
# did not finish, resume it on any machine, the CPU too, with the same command and
# WEIGHTS_RUN=$OUT/run (`make weights WEIGHTS_RUN=... WEIGHTS_DIR=...`). Beside it, the CUDA
# tests; then, with BENCH_ROOMS, rooms per second of that many bedrooms in lockstep of 1, 8
# and 32 on the GPU (bench_batch.py); with TIMING_ROOMS, that many complete bedrooms timed
# with the networks on the GPU and on the CPU (bench_synth.py). On a CPU machine it runs as
# well, only slower (DEVICE=cpu). Where the machine's Python lacks a dependency, wheels in
# .whl/ are installed first (see the device tool's notes); the venv of `make install` is
# not made there (-o install). Progress: $OUT/run/weights.log; learning curves:
# .venv/bin/python benchmarks/learning_curves.py $OUT/run/*/log.jsonl
set -u
OUT=${OUT:-runs/gpu}
ROOM_TYPES=${ROOM_TYPES:-all}
JOBS=${JOBS:-3}
LOADER_WORKERS=${LOADER_WORKERS:-4}
CONFIG=${CONFIG:-config/shipped.yaml}
DEVICE=${DEVICE:-cuda}
TRAIN_LIMIT=${TRAIN_LIMIT:-420}
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

(timeout 300 python3 -m pytest -q -p no:cacheprovider tests/test_cuda.py \
  > "$OUT/cuda_tests.log" 2>&1; echo "exit $?" >> "$OUT/cuda_tests.log") &
tests=$!

# timeout signals the whole process group: make, the trainer and its workers stop together,
# their checkpoints whole (each is written aside, then moved into place).
if command -v make > /dev/null; then
  timeout "$TRAIN_LIMIT" make --no-print-directory -o install weights DEVICE="$DEVICE" \
    ROOM_TYPES="$ROOM_TYPES" JOBS="$JOBS" LOADER_WORKERS="$LOADER_WORKERS" \
    WEIGHTS_CONFIG="$CONFIG" WEIGHTS_RUN="$OUT/run" WEIGHTS_DIR="$OUT/weights" \
    SCENE_SYNTH="python3 -m scene_synth_ros.cli" > "$OUT/make_weights.out" 2>&1
  echo "make weights: exit $? (124: stopped after TRAIN_LIMIT=$TRAIN_LIMIT s, resumable)"
  tail -n 25 "$OUT/run/weights.log"
else
  echo 'make weights: skipped, this machine has no make'
fi

wait "$tests"
if [ "$BENCH_ROOMS" -gt 0 ]; then
  timeout 240 python3 benchmarks/bench_batch.py -n "$BENCH_ROOMS" --workers 1 \
    --lockstep 1 8 32 --device cuda --runtime torch > "$OUT/bench_cuda.log" 2>&1
  echo "exit $?" >> "$OUT/bench_cuda.log"
fi
echo "== CUDA tests"; tail -n 15 "$OUT/cuda_tests.log"
[ -f "$OUT/bench_cuda.log" ] && { echo "== CUDA throughput"; tail -n 20 "$OUT/bench_cuda.log"; }
if [ "$TIMING_ROOMS" -gt 0 ]; then
  for device in cuda cpu; do
    python3 benchmarks/bench_synth.py -n 0 --timing-rooms "$TIMING_ROOMS" --device "$device"
  done
fi
ls -la "$OUT" "$OUT/weights" 2>/dev/null
