#!/usr/bin/env bash
# Configure and build lsdem in build/ (Release, -Werror, ccache if present), after making sure
# the Debian packages it needs are installed. Used by demo.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DLSDEM_WERROR=ON > build-configure.log 2>&1 || {
    cat build-configure.log >&2
    echo "lsdem: cmake configuration failed (log above)" >&2
    exit 1
}
rm -f build-configure.log
cmake --build build -j"$(nproc)"
