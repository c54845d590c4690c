#!/usr/bin/env bash
# Builds the commissioning page (examples/web: eigenrad-runtime in WebAssembly and a static
# page) and serves it on http://127.0.0.1:PORT/ (default 8000) with Python's static file
# server; open that address and then a basis file (`eigenrad build ... -o ROOM.basis`).
#
# Usage: scripts/web.sh [PORT]
#        scripts/web.sh --build-only [DIR]   build the page into DIR (default target/web/site)
#                                            and print its files' sizes; serve nothing
#
# Needs the wasm32-unknown-unknown target (`rustup target add wasm32-unknown-unknown`; added
# here when missing) and python3. Nothing is fetched at run time: the page is index.html,
# style.css, app.js and eigenrad_web.wasm.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
build_only=0
site="target/web/site"
port=8000
if [[ ${1:-} == --build-only ]]; then
  build_only=1
  site="${2:-$site}"
elif [[ -n ${1:-} ]]; then
  port="$1"
fi

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  rustup target add wasm32-unknown-unknown >&2
fi
# Its own workspace and target folder: the host workspace's builds are not disturbed.
(cd examples/web &&
  CARGO_TARGET_DIR="$root/target/web" cargo build --release --quiet --target wasm32-unknown-unknown >&2)

mkdir -p "$site"
cp examples/web/www/index.html examples/web/www/style.css examples/web/www/app.js "$site"/
cp target/web/wasm32-unknown-unknown/release/eigenrad_web.wasm "$site"/

if [[ $build_only -eq 1 ]]; then
  (cd "$site" && wc -c index.html style.css app.js eigenrad_web.wasm)
  exit 0
fi
echo "serving $site on http://127.0.0.1:$port/ (Ctrl-C stops)" >&2
exec python3 -m http.server "$port" --bind 127.0.0.1 --directory "$site"
