#!/usr/bin/env bash
# The web explorer in headless Chromium (web/tests/README.md): builds web/dist, installs what
# the test needs and runs it. Arguments go to browser.mjs (`--bench`: the frame-time benchmark).
# As root it installs Debian's chromium and Node.js when missing; otherwise it says what to
# install.
set -euo pipefail
cd "$(dirname "$0")"
missing=()
command -v "${CHROMIUM:-chromium}" >/dev/null || missing+=(chromium)
command -v npm >/dev/null || missing+=(nodejs npm)
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "web/tests/run.sh: installing ${missing[*]}" >&2
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
    else
        echo "web/tests/run.sh: the browser test needs ${missing[*]} (Debian/Ubuntu: sudo apt-get install ${missing[*]})" >&2
        exit 1
    fi
fi
# The browser this script found is the one the test drives.
CHROMIUM="$(command -v "${CHROMIUM:-chromium}")"
export CHROMIUM
bash ../run --build-only
npm ci --no-audit --no-fund --silent
node browser.mjs "$@"
