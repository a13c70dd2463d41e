"""Shared by the tests of `import specula`: the CLI of the same build, run for reference numbers."""
import json
import os
import subprocess

import pytest


def cli(*args):
    """The CLI's JSON output of `specula ARGS --format json` (or its own --json)."""
    done = subprocess.run([os.environ["SPECULA_CLI"], *args], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def cli_error(*args):
    """The CLI's one-line error for a bad invocation (exit 2), without its 'specula: error: ' prefix."""
    done = subprocess.run([os.environ["SPECULA_CLI"], *args], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2, done.stdout
    return done.stderr.strip().removeprefix("specula: error: ")


def column(table, name):
    return [row[name] for row in table["rows"]]


@pytest.fixture
def specula():
    """The package, with the models a test loads forgotten after it (the catalogue is the CLI's)."""
    import specula as package
    yield package
    package.clear_models()


def cli_text(*args):
    """The CLI's standard output for `specula ARGS`."""
    done = subprocess.run([os.environ["SPECULA_CLI"], *args], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stdout


def read_exr(path):
    """The float channels of a scanline OpenEXR file written with ZIP compression (what `specula
    render --exr-pixel float` writes), as an (H, W, channels) float32 array, channels in the
    file's (alphabetical) order: enough of the format to read our own files without a library."""
    import struct
    import zlib
    import numpy as np
    data = open(path, "rb").read()
    assert data[:4] == b"\x76\x2f\x31\x01", "not an OpenEXR file"
    at, header = 8, {}
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        header[data[at:name_end].decode()] = data[type_end + 5:type_end + 5 + size]
        at = type_end + 5 + size
    at += 1
    assert header["compression"] == b"\x03", "ZIP compression (16 lines a chunk) expected"
    channels, c = [], header["channels"]
    while c[0] != 0:
        end = c.index(b"\0")
        assert struct.unpack_from("<i", c, end + 1)[0] == 2, "float channels expected"
        channels.append(c[:end].decode())
        c = c[end + 17:]
    x0, y0, x1, y1 = struct.unpack("<4i", header["dataWindow"])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    chunks = (height + 15) // 16
    offsets = struct.unpack_from(f"<{chunks}Q", data, at)
    image = np.zeros((height, width, len(channels)), dtype=np.float32)
    for offset in offsets:
        y, size = struct.unpack_from("<ii", data, offset)
        lines = min(16, y1 + 1 - y)
        raw = data[offset + 8:offset + 8 + size]
        expected = lines * width * len(channels) * 4
        if size < expected:
            t = np.frombuffer(zlib.decompress(raw), dtype=np.uint8).astype(np.int64)
            t = (np.cumsum(t - 128) + 128) & 0xFF  # undo the predictor: t[i] = t[i-1] + d[i] - 128
            half = (len(t) + 1) // 2
            raw_bytes = np.empty(len(t), dtype=np.uint8)
            raw_bytes[0::2], raw_bytes[1::2] = t[:half], t[half:]
            raw = raw_bytes.tobytes()
        block = np.frombuffer(raw, dtype="<f4").reshape(lines, len(channels), width)
        image[y - y0:y - y0 + lines] = block.transpose(0, 2, 1)
    return image, channels
