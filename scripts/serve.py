#!/usr/bin/env python3
"""Serve the demo (www/) on 127.0.0.1 with .wasm as application/wasm.

    python3 scripts/serve.py [--port 8000] [--dir www] [--cors] [--prefix /courses/robotics/arm/]

Standard library only. It sends no CORS header unless --cors is given
(`Access-Control-Allow-Origin: *`, which pages on other sites need to load
the <redundant-ik-demo> element; the e2e test serves both ways). --port 0
picks a free port; the URL is printed as the first line (`Serving
http://127.0.0.1:PORT/`, with the prefix), so scripts can read it.
--prefix serves the directory under that sub-path only (anything outside
it is a 404), as a host that puts the page in a folder of its site would
(scripts/test-dist.sh).
"""

import argparse
import functools
import http.server
import os
import sys


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {
        **http.server.SimpleHTTPRequestHandler.extensions_map,
        ".wasm": "application/wasm",
        ".js": "text/javascript",
        ".mjs": "text/javascript",
        ".css": "text/css",
        ".html": "text/html; charset=utf-8",
        ".json": "application/json",
        ".svg": "image/svg+xml",
    }

    def send_head(self):
        prefix = self.server.prefix
        if self.path.split("?")[0] == prefix[:-1]:
            self.send_response(301)
            self.send_header("Location", prefix)
            self.end_headers()
            return None
        if not self.path.startswith(prefix):
            self.send_error(404, f"outside {prefix}")
            return None
        return super().send_head()

    def translate_path(self, path):
        return super().translate_path("/" + path[len(self.server.prefix):])

    def end_headers(self):
        # A development server: always fetch the freshly built module.
        self.send_header("Cache-Control", "no-store")
        if self.server.cors:
            self.send_header("Access-Control-Allow-Origin", "*")
        super().end_headers()

    def log_message(self, fmt, *args):
        if not self.server.quiet:
            super().log_message(fmt, *args)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--port", type=int, default=8000, help="port (0: any free port)")
    parser.add_argument("--dir", default="www", help="directory to serve (default: www)")
    parser.add_argument("--quiet", action="store_true", help="do not log requests")
    parser.add_argument("--cors", action="store_true", help="send Access-Control-Allow-Origin: * (for pages on other sites)")
    parser.add_argument("--prefix", default="/", help="the sub-path to serve the directory under (default: /)")
    args = parser.parse_args()
    prefix = "/" + args.prefix.strip("/") + "/" if args.prefix.strip("/") else "/"

    root = os.path.abspath(args.dir)
    if not os.path.isdir(root):
        print(f"serve.py: no such directory: {root}", file=sys.stderr)
        return 2
    if not os.path.exists(os.path.join(root, "pkg", "redundant_ik_bg.wasm")):
        print(f"serve.py: warning: {root}/pkg is not built yet (run `make web`)", file=sys.stderr)

    handler = functools.partial(Handler, directory=root)
    try:
        server = http.server.ThreadingHTTPServer(("127.0.0.1", args.port), handler)
    except OSError as e:
        print(f"serve.py: cannot listen on 127.0.0.1:{args.port}: {e.strerror}", file=sys.stderr)
        return 1
    server.quiet = args.quiet
    server.cors = args.cors
    server.prefix = prefix
    port = server.server_address[1]
    print(f"Serving http://127.0.0.1:{port}{prefix} (directory {root}); Ctrl-C stops.", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
