#!/usr/bin/env python3
"""Serves web/dist (made by web/build.sh) as a static host should serve the page.

Python's own `http.server` sends every file as it lies on disk: the 45 MB wasm whole, even to a
browser that asks for it compressed. web/build.sh writes compressed copies beside the wasm,
the JavaScript and the level library (levels.json) (`.gz` always, `.zst` where a `zstd` command exists, `.br` where a `brotli`
command or Node exists); this server sends the smallest of those the browser accepts
(`Accept-Encoding`, q-values honoured, `q=0` refused), with `Content-Encoding` and
`Vary: Accept-Encoding`, and the file itself otherwise.
A production host (nginx's `gzip_static`/`brotli_static`, Caddy's `precompressed`) does the
same from the same files: docs/web.md.

Usage: web/serve.py [--port 8080] [--dir web/dist] [--bind 127.0.0.1]
"""

import argparse
import functools
import http.server
import os
import sys

# The encodings with the suffix of their copy; of those the request accepts, the smallest copy
# on disk is sent (for the wasm built on 2026-12-07, brotli -q 11 came 8% under zstd -19).
ENCODINGS = (("zstd", ".zst"), ("br", ".br"), ("gzip", ".gz"))


def accepted(header):
    """The content codings an Accept-Encoding header accepts (those with q > 0)."""
    out = set()
    for part in header.split(","):
        fields = [f.strip() for f in part.split(";")]
        if not fields[0]:
            continue
        q = 1.0
        for f in fields[1:]:
            if f.startswith("q="):
                try:
                    q = float(f[2:])
                except ValueError:
                    q = 0.0
        if q > 0:
            out.add(fields[0].lower())
    return out


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
    }

    def send_head(self):
        path = self.translate_path(self.path)
        if os.path.isfile(path):
            ok = accepted(self.headers.get("Accept-Encoding", ""))
            copies = [
                (os.path.getsize(path + suffix), coding, path + suffix)
                for coding, suffix in ENCODINGS
                if coding in ok and os.path.isfile(path + suffix)
            ]
            if copies:
                _, coding, encoded = min(copies)
                return self.send_encoded(path, encoded, coding)
        return super().send_head()

    def send_encoded(self, path, encoded, coding):
        f = open(encoded, "rb")
        size = os.fstat(f.fileno()).st_size
        self.send_response(200)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Content-Encoding", coding)
        self.send_header("Content-Length", str(size))
        self.send_header("Vary", "Accept-Encoding")
        self.send_header("Last-Modified", self.date_time_string(os.path.getmtime(path)))
        self.end_headers()
        return f


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description="Serve rigidlab's web page with compressed copies.")
    ap.add_argument("--port", type=int, default=8080)
    ap.add_argument("--dir", default=os.path.join(here, "dist"))
    ap.add_argument("--bind", default="127.0.0.1")
    ap.add_argument("--quiet", action="store_true", help="no line per request")
    args = ap.parse_args()
    if not os.path.isfile(os.path.join(args.dir, "index.html")):
        print(f"web/serve.py: no {args.dir}/index.html yet; build it first with web/build.sh", file=sys.stderr)
        sys.exit(2)
    handler = functools.partial(Handler, directory=args.dir)
    if args.quiet:
        handler.func.log_message = lambda *a: None
    server = http.server.ThreadingHTTPServer((args.bind, args.port), handler)
    print(f"rigidlab: http://localhost:{args.port}/   (Ctrl-C stops)", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
