#!/usr/bin/env bash
# Runs Atmoscope's whole test suite: unit tests, CLI and preset tests, and GPU tests on Mesa's
# software Vulkan driver (lavapipe) when the machine has no GPU.
#
# On a machine without the Vulkan loader and lavapipe, or without a C/C++ compiler (the FLIP
# metric's crate builds C++), it installs them (Debian packages mesa-vulkan-drivers, libvulkan1,
# g++) when run as root; otherwise it says what to install.
# With CI=true, or where lavapipe is installed, a missing GPU adapter fails the GPU tests
# instead of skipping them; elsewhere the run ends with a count of the skipped ones.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"

packages=(mesa-vulkan-drivers libvulkan1 g++)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "tests/run.sh: installing ${missing[*]}" >&2
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    else
        echo "tests/run.sh: the build and the GPU tests need ${missing[*]} (Debian/Ubuntu: sudo apt-get install ${missing[*]})" >&2
    fi
fi

# wgpu would otherwise fall back to GL on llvmpipe without a word; lavapipe needs its threads.
export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"

# Two tiers. Without arguments this is the fast tier CI runs: units, GPU/CPU twins, the
# scheduler, the GUI and the command line. `--research` adds the research tier: the tests
# marked `#[ignore = "research tier: …"]` (accuracy over the view suite, AOD ranges, the fits,
# Leenman's replay, long stress runs) and the web explorer in headless Chromium, to run
# whenever the physics changes (docs/testing.md).
research=""
if [ "${1:-}" = "--research" ]; then
    shift
    research=1
fi

# The explorer also builds for the browser (web/README.md): the fast tier checks that it
# compiles for wasm32; the research tier runs it in headless Chromium (web/tests/run.sh).
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown >&2 ||
        echo "tests/run.sh: the web check needs Rust's wasm32 target: rustup target add wasm32-unknown-unknown" >&2
fi
if rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown || [ "${CI:-}" = true ]; then
    cargo check --locked --target wasm32-unknown-unknown -p atmoscope
fi

# A GPU test without an adapter (allowed only outside CI and without lavapipe) says SKIPPED
# and passes, and the runner hides a passing test's output: each skip is written to this file
# and counted at the end, so that a skip never reads as a pass.
skips="$(mktemp)"
export ATMOSCOPE_GPU_SKIPS="$skips"
report_skips() {
    if [ -s "$skips" ]; then
        echo "tests/run.sh: $(wc -l <"$skips") GPU test(s) SKIPPED for want of a GPU adapter (they passed without running):" >&2
        sed 's/^/  /' "$skips" >&2
    else
        echo "tests/run.sh: no GPU test skipped" >&2
    fi
    rm -f "$skips"
}
trap report_skips EXIT

# cargo-nextest runs each test in a process of its own and keeps both cores busy to the end
# (.config/nextest.toml); cargo test runs the binaries one after another, each waiting on its
# slowest test. Under either a test name filters and --no-fail-fast goes on past a failure
# (nextest's default here); other flags are the runner's own.
if cargo nextest --version >/dev/null 2>&1; then
    cargo nextest run --workspace --locked ${research:+--run-ignored all} "$@"
    # nextest runs no doc tests.
    cargo test --workspace --locked --doc
else
    # --include-ignored is the test harness's own flag: after the user's `--`, if any.
    if [ -n "$research" ]; then
        if printf '%s\n' "$@" | grep -qx -- '--'; then
            set -- "$@" --include-ignored
        else
            set -- "$@" -- --include-ignored
        fi
    fi
    cargo test --workspace --locked "$@"
fi
if [ -n "$research" ]; then
    bash web/tests/run.sh
fi
