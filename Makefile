# Two set-up commands, each working on a fresh clone of a fresh machine:
#   make demo   install into .venv, start scene_synth_node, furnish an example room through
#               it, ask it for one more object in a partial room, stop it
#   make test   install into .venv, lint the tree, then run the whole test suite
# and the one that makes the shipped weights again (docs/training.md, "How the shipped
# weights were made"; hours on a CPU):
#   make weights [WEIGHTS_DIR=runs/shipped/weights] [DEVICE=cpu|cuda] [ROOM_TYPES=all]
#                [JOBS=2] [LOADER_WORKERS=0] [WEIGHTS_RUN=runs/shipped]
#                [WEIGHTS_CONFIG=config/shipped.yaml]
#       install, then train every module of each room type of ROOM_TYPES (all, one, or a
#       comma list) as WEIGHTS_CONFIG states, JOBS processes side by side with one torch
#       thread each, on DEVICE, and write the bundles to WEIGHTS_DIR (WEIGHTS_DIR=
#       scene_synth_ros/weights replaces the shipped ones). The same seed gives the same
#       weights. Resumable: run it again with the same WEIGHTS_RUN. Progress, time-stamped,
#       on the screen and in WEIGHTS_RUN/weights.log. LOADER_WORKERS: processes making each
#       job's batches ahead (on a GPU; they change no weight).
# make help prints this.
SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-stamp
# pip's warnings about the machine's local package mirrors are noise, not failures.
PIP_QUIET := grep -v -E "is ignored: it is neither a file nor a directory" || true

.PHONY: help install ros2-tools demo test test-fast lint bench gallery evaluate procthor weights clean

help:
	@sed -n '/^#/!q; s/^# \{0,1\}//p' Makefile

install: $(STAMP)

# The interface package scene_synth_msgs/ is built into the venv with the ROS build tools
# of the package index (scripts/build_msgs.sh); the node's share/ files and executable are
# linked where `ros2 launch` and `ros2 run` look for them (as colcon --symlink-install does),
# so that edits need no reinstall.
MSGS := $(wildcard scene_synth_msgs/*.txt scene_synth_msgs/*.xml scene_synth_msgs/msg/* \
	scene_synth_msgs/srv/* scene_synth_msgs/action/*) scripts/build_msgs.sh
SHARE := $(VENV)/share/scene_synth_ros
$(STAMP): requirements.txt requirements-ros.txt setup.py setup.cfg package.xml $(MSGS) $(wildcard launch/*)
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --disable-pip-version-check -r requirements-ros.txt -r requirements.txt 2>&1 | { $(PIP_QUIET); }
	scripts/build_msgs.sh $(VENV)
	$(PY) -m pip install -q --disable-pip-version-check --no-deps --no-build-isolation --use-pep517 -e . 2>&1 | { $(PIP_QUIET); }
	mkdir -p $(SHARE) $(VENV)/share/ament_index/resource_index/packages $(VENV)/lib/scene_synth_ros
	for f in package.xml config rviz msg_schemas examples meshes; do ln -sfn "$(CURDIR)/$$f" $(SHARE)/$$f; done
	# ros2 launch looks for launch files without following a linked folder
	rm -rf $(SHARE)/launch && mkdir -p $(SHARE)/launch
	for f in launch/*; do ln -sfn "$(CURDIR)/$$f" $(SHARE)/$$f; done
	touch $(VENV)/share/ament_index/resource_index/packages/scene_synth_ros
	ln -sfn ../../bin/scene_synth_node $(VENV)/lib/scene_synth_ros/scene_synth_node
	$(PY) -c "import torch, rclpy, shapely, trimesh, scene_synth_ros, scene_synth_msgs.action; assert torch.__version__.startswith('2.13.0'), torch.__version__"
	touch $(STAMP)

# The real ros2 command line, launch and launch_ros (not on the package index), from
# ../shared/ros2-tools where it is beside the checkout; the tests that use them skip without.
ROS2_TOOLS := ../shared/ros2-tools
TOOLS_STAMP := $(VENV)/.ros2-tools-stamp
ros2-tools: $(TOOLS_STAMP)
$(TOOLS_STAMP): $(STAMP)
	if [ -x $(ROS2_TOOLS)/install.sh ]; then $(ROS2_TOOLS)/install.sh $(VENV) && touch $@; \
	else echo "no $(ROS2_TOOLS): the tests with the real ros2 tools will be skipped"; fi

demo: install
	$(VENV)/bin/scene-synth ros demo --out demo_out

# The whole suite, after the linter.
# The suite on every core (pytest-xdist), a test file to a worker: TEST_WORKERS=1 for one.
TEST_WORKERS ?= auto
test: lint ros2-tools
	$(PY) -m pytest -q -n $(TEST_WORKERS) --dist loadfile --durations=20

# The lane for people working on the code: everything but the tests marked slow.
test-fast: install
	$(PY) -m pytest -q -m "not slow"

# ruff, then the layers and the absence of import cycles (.importlinter).
lint: install
	$(VENV)/bin/ruff check .
	$(VENV)/bin/lint-imports --no-cache

# The quicker benchmarks; benchmarks/README.md lists every one, with what it prints.
bench: install
	$(PY) benchmarks/bench_render.py
	$(PY) benchmarks/bench_corpus.py
	$(PY) benchmarks/bench_synth.py
	$(PY) benchmarks/bench_training.py
	$(PY) benchmarks/bench_node.py

gallery: install
	$(VENV)/bin/scene-synth gallery --out docs/gallery/corpus.png
	$(VENV)/bin/scene-synth gallery --source synthesized --out docs/gallery/synthesized.png
	$(VENV)/bin/scene-synth gallery --source completions --out docs/gallery/completions.png

evaluate: install
	$(VENV)/bin/scene-synth evaluate --room-type all --out docs/evaluation --markdown docs/evaluation.md

# Training on an imported data set, end to end, on the real ProcTHOR rooms beside the
# repository: import, train the compact networks of its three room types (one process per
# room type, one torch thread each), evaluate against the held-out rooms, draw the gallery.
# Resumable: run it again after an interruption. Nothing of it goes into the package.
PROCTHOR := runs/procthor
procthor: install
	$(VENV)/bin/scene-synth import procthor ../shared/data/real/procthor/procthor_1room_train.jsonl.gz --out $(PROCTHOR)/data
	pids=""; for rt in living kitchen bedroom; do \
	  $(VENV)/bin/scene-synth train --data $(PROCTHOR)/data --room-type $$rt \
	    --weights-dir $(PROCTHOR)/weights --run-dir $(PROCTHOR)/run --config config/compact.yaml \
	    --device cpu --threads 1 --quiet > $(PROCTHOR)/train_$$rt.log 2>&1 & pids="$$pids $$!"; \
	done; for p in $$pids; do wait $$p; done
	$(VENV)/bin/scene-synth evaluate --data $(PROCTHOR)/data --weights-dir $(PROCTHOR)/weights \
	  --out docs/procthor --markdown docs/procthor.md
	$(VENV)/bin/scene-synth gallery --source data --data $(PROCTHOR)/data \
	  --weights-dir $(PROCTHOR)/weights --per-type 3 --out docs/gallery/procthor.png

# The shipped weights from this checkout (the header above; docs/training.md).
WEIGHTS_CONFIG ?= config/shipped.yaml
WEIGHTS_RUN ?= runs/shipped
WEIGHTS_DIR ?= $(WEIGHTS_RUN)/weights
DEVICE ?= cpu
ROOM_TYPES ?= all
JOBS ?= 2
LOADER_WORKERS ?= 0
SCENE_SYNTH ?= $(VENV)/bin/scene-synth
weights: install
	mkdir -p $(WEIGHTS_RUN)
	$(SCENE_SYNTH) train --config $(WEIGHTS_CONFIG) --room-type $(ROOM_TYPES) \
	  --device $(DEVICE) --jobs $(JOBS) --loader-workers $(LOADER_WORKERS) \
	  --run-dir $(WEIGHTS_RUN) --weights-dir $(WEIGHTS_DIR) 2>&1 | tee -a $(WEIGHTS_RUN)/weights.log

clean:
	rm -rf $(VENV) demo_out .pytest_cache build *.egg-info
