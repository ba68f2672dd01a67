#!/bin/sh
# Installs the Debian packages `make fuzz` needs on top of those of `make test`
# (tools/build/install-deps.sh): clang, and the compiler-rt of its version, which holds
# libFuzzer (libclang_rt.fuzzer) and the sanitizer runtimes clang links. On Debian 12:
# clang (clang 14) and libclang-rt-14-dev. `make test` never needs them: its replays of
# the fuzz inputs are built with gcc.
# As root it runs apt-get; otherwise it prints the exact command and fails
# (tools/build/install-deps.sh does either).
set -eu

major=14    # Debian 12's clang
if command -v clang >/dev/null 2>&1; then
    major=$(clang -dumpversion | cut -d. -f1)
fi
exec sh "$(dirname "$0")/install-deps.sh" --for "make fuzz (clang and its libFuzzer runtime)" \
    clang "libclang-rt-$major-dev"
