#!/usr/bin/env python3
"""Remove the debugging `name` custom section from a .wasm file, in place.

    python3 scripts/strip-wasm-names.py www/pkg/redundant_ik_bg.wasm

The section only holds function names for stack traces (a fifth of the
release module). Cargo's `strip = "symbols"` would drop it too, but also drops
the `target_features` section that wasm-bindgen reads, so the build strips the
names here instead. Standard library only; every other section is kept as is.
"""

import sys

MAGIC = b"\0asm"


def leb128(data: bytes, i: int) -> tuple[int, int]:
    """Unsigned LEB128 at data[i:]; returns (value, next index)."""
    value = shift = 0
    while True:
        if i >= len(data):
            raise ValueError("truncated LEB128 number")
        byte = data[i]
        i += 1
        value |= (byte & 0x7F) << shift
        shift += 7
        if byte < 0x80:
            return value, i


def strip_names(data: bytes) -> tuple[bytes, int]:
    """The module without its `name` sections, and how many bytes went."""
    if data[:4] != MAGIC or len(data) < 8:
        raise ValueError("not a WebAssembly module")
    out = bytearray(data[:8])
    i = 8
    while i < len(data):
        start = i
        section_id = data[i]
        size, body = leb128(data, i + 1)
        end = body + size
        if end > len(data):
            raise ValueError("truncated section")
        drop = False
        if section_id == 0:
            name_len, name_start = leb128(data, body)
            drop = data[name_start : name_start + name_len] == b"name"
        if not drop:
            out += data[start:end]
        i = end
    return bytes(out), len(data) - len(out)


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    path = sys.argv[1]
    with open(path, "rb") as f:
        data = f.read()
    try:
        stripped, removed = strip_names(data)
    except ValueError as e:
        print(f"strip-wasm-names: {path}: {e}", file=sys.stderr)
        return 1
    if removed:
        with open(path, "wb") as f:
            f.write(stripped)
    print(f"strip-wasm-names: {path}: {len(data)} -> {len(stripped)} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
