#!/usr/bin/env bash
# Refreshes tests/fields from the workplace's shared benchmark fields (../shared/fields), so that a
# clone tests anywhere. Run it when shared/ changes; tests/corpus.rs fails while the copy is stale.
set -euo pipefail
cd "$(dirname "$0")/.."
src=${1:-../shared/fields}
[ -d "$src" ] || { echo "no $src to sync from" >&2; exit 1; }
mkdir -p tests/fields
# Everything but our own licence notes is replaced by the shared copy.
find tests/fields -type f ! -name 'LICENSE*' -delete
cp -r "$src"/. tests/fields/
echo "tests/fields refreshed from $src"
