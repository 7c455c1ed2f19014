#!/usr/bin/env bash
# Runs every test of the workspace, installing first what the tests check outputs with:
# Python's ezdxf (reads and audits every DXF) and LinuxCNC's standalone `rs274` interpreter
# (runs every laser program), from Debian's linuxcnc-uspace.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! python3 -c "import ezdxf" 2>/dev/null; then
  echo "installing ezdxf (pip)"
  python3 -m pip install --quiet --disable-pip-version-check ezdxf
fi
if ! command -v rs274 >/dev/null 2>&1; then
  echo "installing linuxcnc-uspace (apt) for rs274"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends linuxcnc-uspace >/dev/null
fi

# The runtime crates must build without std (no_std, libm only).
cargo build --quiet -p dlw-geometry -p dlw-estimator --no-default-features
cargo test --workspace --all-targets "$@"
cargo test --workspace --doc
