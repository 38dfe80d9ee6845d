#!/usr/bin/env bash
# Serves web/dist (made by web/build.sh) at http://localhost:${1:-8080}/ with web/serve.py: the
# wasm and the JavaScript compressed as the browser accepts (zstd, br or gzip copies that
# web/build.sh wrote), .wasm as application/wasm. Open, for example,
#   http://localhost:8080/?level=kinetics/simple_pendulum.ron
set -euo pipefail
cd "$(dirname "$0")"
if [ ! -f dist/index.html ]; then
  echo "web/serve.sh: no web/dist yet; build it first with web/build.sh" >&2
  exit 2
fi
exec python3 serve.py --port "${1:-8080}" --dir dist
