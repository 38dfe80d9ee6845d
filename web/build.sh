#!/usr/bin/env bash
# Builds the web page of the sandbox into web/dist (index.html, rigidlab.js, rigidlab_bg.wasm,
# levels.json):
# a static folder any web server can serve (web/serve.sh serves it locally).
#
# Installs what it needs: the wasm32-unknown-unknown target (rustup) and wasm-bindgen-cli at the
# version of the wasm-bindgen crate in Cargo.lock (the two must match exactly).
set -euo pipefail
cd "$(dirname "$0")/.."

target_dir="${CARGO_TARGET_DIR:-target}"
out=web/dist

if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  echo "web/build.sh: installing the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

want=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
have=$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }' || true)
if [ "$have" != "$want" ]; then
  echo "web/build.sh: installing wasm-bindgen-cli $want (have: ${have:-none}; about 3 min)"
  # Not --locked: the lock file it ships names a webpki-roots this registry no longer serves.
  cargo install wasm-bindgen-cli --version "$want"
fi

# The `web` profile (Cargo.toml): release, optimised for size except the physics, with fat
# link-time optimisation (since 2026-12-07: 16% smaller raw, 5% smaller compressed, and the
# build from nothing no longer than without it, as the dependencies compile to bitcode only:
# docs/web.md). `--no-lto` builds without it: after a change to rigidlab's own code it relinks
# in seconds instead of optimising the whole program again (minutes), for trying things out.
lto=fat
for arg in "$@"; do
  case "$arg" in
    --lto) lto=fat ;;
    --no-lto) lto=false ;;
    *) echo "web/build.sh: unknown option $arg (the options are --no-lto and --lto, the default)" >&2; exit 2 ;;
  esac
done
# The link-time passes run at the opt-level of the crate being linked, the `rigidlab` binary
# (src/main.rs), which the profile sets to 3 with the rest of the rigidlab package: all of Bevy
# was optimised at 3 at the link, inlining it for speed. `-C opt-level=s`, given to the binary
# alone (`cargo rustc` passes it to the last target only), runs the link at "s"; the rigidlab
# library compiles at 3, but the link optimises the whole program once more at "s" (since
# 2026-12-07: docs/web.md, "A lighter page"): with the folding below 5.96 MB brotli against
# 6.18 MB at 3, and the page's own check of the 30x30 joint grid ran 1.34x to 1.49x longer.
# RIGIDLAB_WEB_LINK_OPT=3 builds the faster, larger page.
link_opt="${RIGIDLAB_WEB_LINK_OPT:-s}"
CARGO_PROFILE_WEB_LTO=$lto cargo rustc --profile web --target wasm32-unknown-unknown --bin rigidlab -- -C opt-level="$link_opt"

rm -rf "$out"
mkdir -p "$out"
# The level library, beside the wasm rather than compiled into it (1.8 MB of its raw size;
# src/app/page_library.rs, docs/web.md): every level file under levels/ as a [path, text] pair,
# sorted by path, which web/index.html fetches while the wasm comes.
python3 - levels "$out/levels.json" <<'PY'
import json, os, sys
root, out = sys.argv[1], sys.argv[2]
pairs = []
for dirpath, _, files in os.walk(root):
    for f in files:
        if f.endswith(".ron"):
            path = os.path.join(dirpath, f)
            rel = os.path.relpath(path, os.path.dirname(root) or ".").replace(os.sep, "/")
            with open(path, encoding="utf-8") as fh:
                pairs.append([rel, fh.read()])
with open(out, "w", encoding="utf-8") as fh:
    json.dump(sorted(pairs), fh, ensure_ascii=False, separators=(",", ":"))
PY
# The name section (23 of 67 MB) only names functions in stack traces; the panic message stays.
wasm-bindgen --target web --no-typescript --remove-name-section --remove-producers-section --out-dir "$out" --out-name rigidlab \
  "$target_dir/wasm32-unknown-unknown/web/rigidlab.wasm"
cp web/index.html "$out/"

wasm="$out/rigidlab_bg.wasm"

# binaryen's wasm-opt (the npm package `binaryen`, pinned in web/opt/package-lock.json: binaryen
# compiled to wasm, run by Node, so no binary to download) folds functions whose code is the same
# (--duplicate-function-elimination) or the same but for constants (--merge-similar-functions):
# 11.7% less raw, 1.5% less brotli, about 16 CPU-s (docs/web.md). Not -Os or -Oz: they cut the
# raw size less than these two and made the compressed wasm larger. --detect-features reads the
# features the wasm uses from its target_features section (reference types for wasm-bindgen's
# table among them). Without Node (or with RIGIDLAB_WASM_OPT=0) the page is left as it is.
# binaryen is installed again whenever the installed version is not the locked one, and a failed
# install (no registry) leaves the page as wasm-bindgen wrote it, larger but whole.
binaryen_version() { node -p "require('./web/opt/$1').$2" 2>/dev/null || true; }
if [ "${RIGIDLAB_WASM_OPT:-1}" != 0 ] && command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then
  want_binaryen=$(binaryen_version package-lock.json "packages['node_modules/binaryen'].version")
  if [ "$(binaryen_version node_modules/binaryen/package.json version)" != "$want_binaryen" ]; then
    (cd web/opt && npm ci --no-audit --no-fund) || echo "web/build.sh: npm ci in web/opt failed"
  fi
  if [ -n "$want_binaryen" ] && [ "$(binaryen_version node_modules/binaryen/package.json version)" = "$want_binaryen" ]; then
    node web/opt/node_modules/binaryen/bin/wasm-opt --detect-features \
      --duplicate-function-elimination --merge-similar-functions "$wasm" -o "$wasm.opt"
    mv "$wasm.opt" "$wasm"
    # RIGIDLAB_WASM_OPT_OS=1 runs binaryen's -Os after the folding: 1.2 MB less raw, 0.1 MB more
    # brotli, 3 to 4 CPU-min more, and the physics in the page slower (docs/web.md, "A lighter
    # page"); with RIGIDLAB_WEB_LINK_OPT=z it made the 24.9 MB page. Not the default.
    if [ "${RIGIDLAB_WASM_OPT_OS:-0}" = 1 ]; then
      node web/opt/node_modules/binaryen/bin/wasm-opt --detect-features -Os "$wasm" -o "$wasm.opt"
      mv "$wasm.opt" "$wasm"
    fi
  else
    echo "web/build.sh: binaryen $want_binaryen is not installed in web/opt: wasm-opt not run (the page is larger, still whole)"
  fi
else
  echo "web/build.sh: no Node.js and npm (or RIGIDLAB_WASM_OPT=0): wasm-opt not run"
fi
raw=$(stat -c %s "$wasm")
# The page shows how much of the wasm has come (its size, decompressed, is written in).
sed -i "s/__WASM_BYTES__/$raw/" "$out/index.html"

# Compressed copies for web/serve.py (and any static host that serves precompressed files):
# zstd at level 19 (Chromium and Firefox accept it; its window stays within the 8 MB that
# HTTP's zstd coding allows), gzip for every browser, and brotli at quality 11 with a 16 MiB
# window (every current browser over HTTPS; 8% smaller than zstd -19 here, docs/web.md) by the
# `brotli` command or else Node's zlib (the browser test's Node, so CI makes it too).
brotli_node='const z = require("zlib"), fs = require("fs"); const d = fs.readFileSync(process.argv[1]);
fs.writeFileSync(process.argv[1] + ".br", z.brotliCompressSync(d, { params: {
  [z.constants.BROTLI_PARAM_QUALITY]: 11, [z.constants.BROTLI_PARAM_LGWIN]: 24,
  [z.constants.BROTLI_PARAM_SIZE_HINT]: d.length } }));'
for f in "$wasm" "$out/rigidlab.js" "$out/levels.json"; do
  gzip -9 -k -f "$f"
  if command -v zstd >/dev/null 2>&1; then zstd -19 -q -f "$f" -o "$f.zst"; fi
  if command -v brotli >/dev/null 2>&1; then brotli -q 11 -w 24 -f -k "$f"
  elif command -v node >/dev/null 2>&1; then node -e "$brotli_node" "$f"; fi
done
size() { if [ -f "$1" ]; then echo "$(( $(stat -c %s "$1") / 1024 )) KiB"; else echo "none"; fi; }
echo "web/build.sh: $out ready; rigidlab_bg.wasm $((raw / 1024)) KiB, gzip $(size "$wasm.gz"), zstd $(size "$wasm.zst"), brotli $(size "$wasm.br")"
echo "web/build.sh: levels.json $(( $(stat -c %s "$out/levels.json") / 1024 )) KiB, brotli $(size "$out/levels.json.br")"
