#!/usr/bin/env bash
# Fuzz step of CI (called from .ci/run; also runs on its own): installs cargo-fuzz if it is
# missing, builds the fuzz crate (fuzz/, its own workspace) with debug assertions and overflow
# checks, and runs every target for FUZZ_SECONDS seconds (default 10) from its corpus in
# fuzz/corpus/ (empty on a fresh checkout) and its committed seeds in fuzz/seeds/<target>/ (past
# findings, run first: read, never written). Any panic, failed check or input slower than 5 s
# fails the step; the crashing input is left in fuzz/artifacts/<target>/.
#
# The long campaign (docs/testing.md), per target:
#   cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz run -a <target> -- -max_total_time=600 -timeout=5
#
# cargo-fuzz passes nightly-only compiler flags (the sanitizer, coverage instrumentation):
# RUSTC_BOOTSTRAP=1 lets the stable toolchain accept them.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
export CARGO_TERM_COLOR=never RUSTC_BOOTSTRAP=1

SECONDS_PER_TARGET="${FUZZ_SECONDS:-10}"
CARGO_FUZZ_VERSION=0.13.2

if ! cargo fuzz --version 2>/dev/null | grep -qF "$CARGO_FUZZ_VERSION"; then
    cargo install cargo-fuzz --version "$CARGO_FUZZ_VERSION" --locked
fi
cargo fuzz --version
# Warnings denied in the crate and the fuzz targets: cargo-fuzz appends RUSTFLAGS to its own
# flags (dependencies from crates.io have their lints capped).
export RUSTFLAGS="${RUSTFLAGS:+$RUSTFLAGS }-D warnings"

cargo fmt --check
started=$(date +%s)
cargo fuzz build -a
echo "built in $(($(date +%s) - started)) s"

mkdir -p ../target
for target in $(cargo fuzz list); do
    log="../target/fuzz-$target.log"
    # New inputs go to the first corpus directory, so the seeds stay as committed.
    mkdir -p "corpus/$target"
    corpora=("corpus/$target")
    [ -d "seeds/$target" ] && corpora+=("seeds/$target")
    if ! cargo fuzz run -a "$target" "${corpora[@]}" -- -max_total_time="$SECONDS_PER_TARGET" \
        -timeout=5 -print_final_stats=1 >"$log" 2>&1; then
        tail -n 60 "$log"
        echo "FAIL: fuzz target $target (full log: target/fuzz-$target.log)" >&2
        exit 1
    fi
    runs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    echo "  ok: $target: ${runs:-?} inputs in ${SECONDS_PER_TARGET} s"
done
echo "fuzz step: $(($(date +%s) - started)) s after installing cargo-fuzz"
