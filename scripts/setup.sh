#!/usr/bin/env bash
# Installs what building and testing furrow needs and is missing; each step is skipped when its
# tool is already there, so running it again costs a second.
#
#   scripts/setup.sh rust      the wasm32 target and wasm-bindgen-cli at the version in Cargo.lock
#   scripts/setup.sh browser   Debian's chromium and chromium-driver (for the browser tests)
#   scripts/setup.sh npm       the npm packages of package-lock.json (playwright-core)
set -euo pipefail
cd "$(dirname "$0")/.."

say() { printf '\033[1m[setup]\033[0m %s\n' "$*"; }

wasm_bindgen_version() {
  # The version of the wasm-bindgen crate in Cargo.lock: the CLI must match it exactly.
  awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock
}

setup_rust() {
  if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    say "adding the wasm32-unknown-unknown target"
    rustup target add wasm32-unknown-unknown
  fi
  local want have
  want=$(wasm_bindgen_version)
  have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
  if [ "$have" != "$want" ]; then
    say "installing wasm-bindgen-cli $want (found '${have:-none}'; takes about 7 minutes on 2 cores)"
    # Without --locked: its own lock file pins a crate version the registry no longer serves.
    cargo install wasm-bindgen-cli --version "$want" --force
  fi
}

setup_browser() {
  if command -v chromium >/dev/null && command -v chromedriver >/dev/null; then
    return
  fi
  say "installing Debian's chromium and chromium-driver"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get install -y --no-install-recommends chromium chromium-driver \
    || { $sudo apt-get update && $sudo apt-get install -y --no-install-recommends chromium chromium-driver; }
}

setup_npm() {
  # npm ci when node_modules is missing or older than the lock file.
  if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
    say "installing npm packages from package-lock.json"
    npm ci --no-audit --no-fund
  fi
}

for what in "${@:-rust}"; do
  case "$what" in
    rust) setup_rust ;;
    browser) setup_browser ;;
    npm) setup_npm ;;
    *) echo "setup.sh: unknown part '$what' (rust, browser, npm)" >&2; exit 2 ;;
  esac
done
