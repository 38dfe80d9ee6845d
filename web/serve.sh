#!/usr/bin/env bash
# Serves web/dist (made by web/build.sh) at http://localhost:${1:-8080}/ with Python's web
# server, which sends .wasm as application/wasm. Open, for example,
#   http://localhost:8080/?level=kinetics/simple_pendulum.ron
set -euo pipefail
cd "$(dirname "$0")"
if [ ! -f dist/index.html ]; then
  echo "web/serve.sh: no web/dist yet; build it first with web/build.sh" >&2
  exit 2
fi
port="${1:-8080}"
echo "rigidlab: http://localhost:$port/   (Ctrl-C stops)"
exec python3 -m http.server --bind 127.0.0.1 --directory dist "$port"
