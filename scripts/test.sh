#!/usr/bin/env bash
# Runs every test of the workspace, installing first what the tests check outputs with:
# Python's ezdxf (reads and audits every DXF), Python's npTDMS (writes the TDMS files the
# importer is tested on) and LinuxCNC's standalone `rs274` interpreter
# (runs every laser program), from Debian's linuxcnc-uspace.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! python3 -c "import ezdxf" 2>/dev/null; then
  echo "installing ezdxf (pip)"
  python3 -m pip install --quiet --disable-pip-version-check ezdxf
fi
# npTDMS (pip name nptdms): another TDMS writer and reader, which the TDMS import is tested
# against (tests/import_tdms.rs, tests/import_recording.rs).
if ! python3 -c "import nptdms" 2>/dev/null; then
  echo "installing npTDMS (pip)"
  python3 -m pip install --quiet --disable-pip-version-check nptdms
fi
# pytest and numpy for the Python package's tests, then the package itself, built from this
# checkout by maturin (PEP 517; an abi3 wheel, docs/python.md). Rebuilt every run, so the tests
# see the current source. The wheel's release build runs in the background, beside the
# workspace's build below (each has its own target folder; on two cores the one fills the
# other's single-threaded stretches), and is waited for before the Python tests. It runs at a
# lower priority: the workspace's build and tests are on the way to the end, the wheel only at
# the end.
python3 -m pip install --quiet --disable-pip-version-check pytest numpy
mkdir -p target
wheel_log="target/python-wheel-build.log"
echo "building and installing the dlw Python package in the background (pip install ./crates/python, log: $wheel_log)"
nice -n 10 python3 -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps ./crates/python \
  >"$wheel_log" 2>&1 &
wheel_pid=$!
trap 'kill "$wheel_pid" 2>/dev/null || true' EXIT

if ! command -v rs274 >/dev/null 2>&1; then
  echo "installing linuxcnc-uspace (apt) for rs274"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends linuxcnc-uspace >/dev/null
fi

# Property tests (proptest) draw their cases from this seed, so a run is repeatable and CI does
# not pass or fail by the draw; set PROPTEST_RNG_SEED to another number to explore new cases (a
# failing case is saved in the test's .proptest-regressions file and replayed first after that).
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-20261125}"

# The runtime crates must build without std (no_std, libm only).
cargo build --quiet -p dlw-geometry -p dlw-estimator --no-default-features
# Every test target but the criterion benches, which are built (dev profile, next line) but not
# run: run as tests they take one iteration each of full-size work (2 min of CI for no check);
# `cargo bench` measures them (docs/performance.md).
cargo test --workspace --lib --bins --tests --examples "$@"
cargo build --quiet --workspace --benches --profile dev
cargo test --workspace --doc

# The Python package against the command line it mirrors.
cargo build --quiet --bin dlw
if ! wait "$wheel_pid"; then
  cat "$wheel_log" >&2
  echo "building the dlw Python package failed (log above)" >&2
  exit 1
fi
python3 -c "import dlw; print('import dlw:', dlw.__version__)"
DLW_BIN="$PWD/target/debug/dlw" python3 -m pytest -q crates/python/tests

# Opt-in: a short libFuzzer run of each cargo-fuzz target (docs/fuzzing.md). Needs a nightly
# toolchain and cargo-fuzz, which this script does not install (rustup downloads them from
# outside crates.io); tests/fuzz_inputs.rs runs the same entry points on stable every time.
if [ "${DLW_FUZZ_CI:-0}" != "0" ]; then
  if cargo +nightly fuzz --version >/dev/null 2>&1; then
    fuzz/make-seeds.sh >/dev/null
    for t in dxf_import design_file recording; do
      (cd fuzz && cargo +nightly fuzz run "$t" "corpus/$t" -- \
        -max_total_time="${DLW_FUZZ_CI_SECONDS:-30}" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=256)
    done
  else
    echo "DLW_FUZZ_CI set but no nightly toolchain with cargo-fuzz: skipping the libFuzzer runs" >&2
  fi
fi
