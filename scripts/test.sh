#!/usr/bin/env bash
# Runs every test of furrow, installing what is missing first (scripts/setup.sh):
#   formatting and lints; native unit, corpus, property and doc tests; the wasm build's tests in
#   Node and in headless Chromium; the built npm package in Node and in Chromium; the viewer in
#   Chromium (Playwright). Prints the time of each step.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh rust browser npm

started=$(date +%s)
timings=()
step() {
  local name=$1
  shift
  printf '\n\033[1m== %s\033[0m\n' "$name"
  local t0
  t0=$(date +%s)
  "$@"
  timings+=("$(printf '%4ss  %s' $(( $(date +%s) - t0 )) "$name")")
}

wasm_test() {
  CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
    WASM_BINDGEN_TEST_TIMEOUT=120 \
    cargo test --target wasm32-unknown-unknown --features small-alloc --test wasm "$@"
}

step "format" cargo fmt --check
lints() {
  cargo clippy --all-targets --quiet -- -D warnings
  # The bindings only exist for wasm32.
  cargo clippy --target wasm32-unknown-unknown --features small-alloc --lib --test wasm --quiet -- -D warnings
}
step "lints" lints
# Every source file under 1,000 lines, a Rust file's before its tests.
file_lengths() {
  local long
  long=$(find src examples tests benches www js pkg-tests scripts \
      \( -name '*.rs' -o -name '*.js' -o -name '*.mjs' -o -name '*.ts' -o -name '*.py' -o -name '*.sh' \) \
      -not -path 'tests/fields/*' -print0 |
    xargs -0 awk 'FNR == 1 { if (name != "" && n > 1000) print name ": " n " lines"; name = FILENAME; n = 0; done = 0 }
      done { next }
      /^mod tests \{/ && prev ~ /^#\[cfg\(test\)\]/ { done = 1; n--; next }
      { n++; prev = $0 }
      END { if (n > 1000) print name ": " n " lines" }')
  if [ -n "$long" ]; then
    echo "files over 1,000 lines (before their tests):"
    echo "$long"
    return 1
  fi
}
step "file lengths" file_lengths
step "native tests" cargo test
# Every worst-case input plans or is refused within 60 s and 4 GB (a hang check, in release).
step "termination (release)" cargo test --release --test termination -- --ignored every_case_plans_or_is_refused_in_time
step "wasm tests in Node" wasm_test
step "wasm tests in Chromium" env WASM_BINDGEN_USE_BROWSER=1 bash -c "$(declare -f wasm_test); wasm_test"
step "package build" scripts/build.sh
step "package and viewer tests (Node, Chromium)" node --test --test-concurrency=1 pkg-tests/

printf '\n\033[1m== all tests passed in %ss\033[0m\n' $(( $(date +%s) - started ))
printf '%s\n' "${timings[@]}"
