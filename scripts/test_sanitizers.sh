#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and
# runs the whole suite under them. Any report from the project's code fails a
# test (halt_on_error; UBSan does not recover). Leaks inside Mesa's llvmpipe
# at eglTerminate are suppressed (scripts/lsan.supp); the project's own are not.
# Usage: scripts/test_sanitizers.sh [ctest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVGI_SANITIZE=address,undefined \
  > build-asan.log 2>&1 || { cat build-asan.log; exit 1; }
cmake --build build-asan
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$(pwd)/scripts/lsan.supp:print_suppressions=0
junit=build-asan/ctest_junit.xml
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --output-junit "$(pwd)/$junit" "$@" && exit 0
# LeakSanitizer's own tracer sometimes crashes at a process's exit under load ("Tracer caught signal 11 …
# LeakSanitizer has encountered a fatal error", seen on llvmpipe's many threads): no report on the code.
# Tests whose only fault is that run once more (scripts/lsan_tracer_crashes.py); any other failure fails.
retry=$(python3 scripts/lsan_tracer_crashes.py "$junit") || exit 1
[ -n "$retry" ] || exit 1
echo "test_sanitizers.sh: LeakSanitizer's tracer crashed at exit in: $(echo $retry | tr '\n' ' ')— running them again"
ctest --test-dir build-asan --output-on-failure -R "^($(echo "$retry" | paste -sd'|'))\$"
