#!/usr/bin/env bash
# Builds the interface package scene_synth_msgs/ into a venv that holds the pip ROS 2 Jazzy
# wheels, from the package index alone (no /opt/ros): rclpy then imports
# scene_synth_msgs.msg / .srv / .action, and `ros2 interface show` finds the types.
#   usage: scripts/build_msgs.sh VENV [BUILD_DIR]
# With a ROS install, build the workspace with colcon instead (README, "With a ROS install").
# Needs cmake and a C compiler. About a minute of pip the first time, 30 s of build.
set -euo pipefail
HERE=$(cd "$(dirname "$0")/.." && pwd)
V=$(cd "${1:?usage: build_msgs.sh VENV [BUILD_DIR]}" && pwd)
B=${2:-"$HERE/build/scene_synth_msgs"}
PY="$V/bin/python"
# The rosidl generators and ament_cmake, at the versions of the rclpy wheel in requirements.txt.
"$PY" -m pip install -q --disable-pip-version-check -r "$HERE/scene_synth_msgs/requirements-build.txt" \
  2>&1 | { grep -v "is ignored: it is neither" || true; }
# The wheels' CMake files name the include folders of the Python that built them
# (/opt/python/cp311-cp311/...); the generated C extensions must compile against this one.
PYINC=$("$PY" -c "import sysconfig; print(sysconfig.get_paths()['include'])")
NPINC=$("$PY" -c "import numpy; print(numpy.get_include())")
{ grep -rlZ --include='*.cmake' /opt/python/cp311-cp311/ "$V/share" 2>/dev/null || true; } \
  | xargs -0 -r sed -i \
    -e "s#/opt/python/cp311-cp311/include/python3.11#$PYINC#g" \
    -e "s#/opt/python/cp311-cp311/lib/python3.11/site-packages/numpy/_core/include#$NPINC#g"
export AMENT_PREFIX_PATH="$V${AMENT_PREFIX_PATH:+:$AMENT_PREFIX_PATH}" CMAKE_PREFIX_PATH="$V"
export PATH="$V/bin:$PATH"
mkdir -p "$B"
step() {  # step NAME COMMAND...: run it, its output in BUILD_DIR/NAME.log, shown on failure
  local name=$1; shift
  "$@" >"$B/$name.log" 2>&1 || { tail -25 "$B/$name.log" >&2
    echo "scene_synth_msgs: $name failed; the whole log is $B/$name.log" >&2; exit 1; }
}
step configure cmake -S "$HERE/scene_synth_msgs" -B "$B" -DCMAKE_INSTALL_PREFIX="$V" \
  -DBUILD_TESTING=OFF -DPython3_EXECUTABLE="$PY" -DCMAKE_BUILD_TYPE=Release
step build cmake --build "$B" -j "$(nproc)"
step install cmake --install "$B"
"$PY" -c "from scene_synth_msgs.action import Furnish; from scene_synth_msgs.srv import InsertObject"
echo "scene_synth_msgs built into $V"
