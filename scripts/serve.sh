#!/usr/bin/env bash
# Builds everything and serves the viewer on http://localhost:8080 (PORT=... to change).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
exec node scripts/serve.mjs --root target/site --port "${PORT:-8080}"
