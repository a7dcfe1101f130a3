#!/bin/sh
# Fuzz the contact kernel: tests/kernel/run_fuzz.sh SECONDS   (default 60)
# Builds build/fuzz/fuzz_kernel with clang++ -fsanitize=fuzzer,address,undefined and runs it;
# exits non-zero when libFuzzer finds a crash / failed check (reproducer in build/fuzz/).
set -eu
SECONDS_TO_RUN=${1:-60}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT="$ROOT/build/fuzz"
mkdir -p "$OUT/corpus"
CXX=${CXX_FUZZ:-clang++}
KERNEL_SRC=$(ls "$ROOT"/src/kernel/*.cpp "$ROOT"/src/kernel/force_laws/*.cpp)
$CXX -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I "$ROOT/src/kernel" -I "$ROOT/src/kernel/force_laws" -I/usr/include/eigen3 \
  "$ROOT/tests/kernel/fuzz_kernel.cpp" $KERNEL_SRC -o "$OUT/fuzz_kernel"
cd "$OUT"
exec ./fuzz_kernel -max_total_time="$SECONDS_TO_RUN" -print_final_stats=1 \
  -artifact_prefix="$OUT/" corpus
