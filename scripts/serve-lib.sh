# Sourced by the scripts that test the page in Chromium (scripts/e2e.sh,
# scripts/test-dist.sh): `serve_dir NAME DIR [serve.py options]` starts
# scripts/serve.py for DIR on a free 127.0.0.1 port, stops it when the
# script exits, and sets `url` to the address it printed (with its
# --prefix, if any). NAME prefixes the messages.

serve_dir() {
  local name="$1" dir="$2"
  shift 2
  serve_log="$(mktemp -t "$name-serve.XXXXXX")"
  python3 scripts/serve.py --port 0 --dir "$dir" --quiet "$@" >"$serve_log" 2>&1 &
  serve_pid=$!
  trap 'kill "$serve_pid" 2>/dev/null || true; wait "$serve_pid" 2>/dev/null || true; rm -f "$serve_log"' EXIT INT TERM
  url=""
  for _ in $(seq 1 100); do
    url="$(grep -o 'http://127\.0\.0\.1:[0-9]*/[^ ]*' "$serve_log" | head -n1 || true)"
    [[ -n "$url" ]] && break
    if ! kill -0 "$serve_pid" 2>/dev/null; then
      echo "$name: the static server did not start:" >&2
      cat "$serve_log" >&2
      exit 1
    fi
    sleep 0.05
  done
  if [[ -z "$url" ]]; then
    echo "$name: the static server printed no URL" >&2
    exit 1
  fi
  echo "$name: serving $dir/ at $url"
}
