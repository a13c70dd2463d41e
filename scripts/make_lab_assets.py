#!/usr/bin/env python3
"""Bundled assets of the browser lab's "lit object under an environment" view.

Writes (run from the repository root; deterministic, no network, stdlib + NumPy):

    python3 scripts/make_lab_assets.py

  web/assets/knot.obj  a (2,3) torus knot tube: v, vn (analytic tube normals) and f v//vn
                       triangles, counter-clockwise seen from outside, inside the unit sphere
  web/assets/sky.exr   a 256x128 latitude-longitude probe, RGB 32-bit float: a blue-white sky,
                       a brownish-grey ground and a small warm sun toward (+x, +y, +z)

The probe uses the renderer's mapping (docs/render.md, "Environment lighting"): row 0 looks up
(+y); pixel (x, y) covers theta in [y, y+1)*pi/H from +y and phi in [x, x+1)*2pi/W - pi from -z
toward +x, direction (sin theta sin phi, cos theta, -sin theta cos phi).

The EXR writer follows the OpenEXR file-layout document ("OpenEXR File Layout",
openexr.com/en/latest/OpenEXRFileLayout.html): magic number and version field, a header of
attributes (name, type, size, value) ended by a null byte, the line offset table (one uint64 per
scanline block), then per scanline: int32 y, int32 byte count, and the row's samples channel by
channel in channel-name order. Single part, scanline, compression NONE, little-endian.
"""
import math
import pathlib
import struct

import numpy as np

# --- Torus knot ------------------------------------------------------------------------------
P, Q = 2, 3                # winds P times around the z axis, Q times through the torus hole
CORE, SWING = 2.0, 1.0     # curve: core circle radius and its meridian swing
TUBE = 0.45                # tube radius (same units)
SEGMENTS, SIDES = 150, 12  # SEGMENTS * SIDES * 2 triangles


def knot_curve(t):
    """Points on the (P, Q) torus knot and their unit tangents, for parameters t (N,)."""
    ring = CORE + SWING * np.cos(Q * t)
    point = np.stack([ring * np.cos(P * t), ring * np.sin(P * t), -SWING * np.sin(Q * t)], axis=1)
    d_ring = -Q * SWING * np.sin(Q * t)
    tangent = np.stack([d_ring * np.cos(P * t) - P * ring * np.sin(P * t),
                        d_ring * np.sin(P * t) + P * ring * np.cos(P * t),
                        -Q * SWING * np.cos(Q * t)], axis=1)
    return point, tangent / np.linalg.norm(tangent, axis=1, keepdims=True)


def knot_frame(t, point, tangent):
    """A periodic frame (N, B) across the tube: N points from the torus core circle to the curve."""
    core = np.stack([CORE * np.cos(P * t), CORE * np.sin(P * t), np.zeros_like(t)], axis=1)
    offset = point - core
    normal = offset - np.sum(offset * tangent, axis=1, keepdims=True) * tangent
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    return normal, np.cross(tangent, normal)


def knot_mesh():
    """Vertices, unit normals (both (SEGMENTS*SIDES, 3)) and 0-based triangles of the tube."""
    t = np.arange(SEGMENTS) * (2 * math.pi / SEGMENTS)
    s = np.arange(SIDES) * (2 * math.pi / SIDES)
    point, tangent = knot_curve(t)
    normal, binormal = knot_frame(t, point, tangent)
    around = (np.cos(s)[None, :, None] * normal[:, None, :]
              + np.sin(s)[None, :, None] * binormal[:, None, :])      # (SEGMENTS, SIDES, 3)
    vertices = (point[:, None, :] + TUBE * around) / (CORE + SWING + TUBE)
    index = np.arange(SEGMENTS * SIDES).reshape(SEGMENTS, SIDES)
    a, b = index, np.roll(index, -1, axis=1)             # (i, j), (i, j+1)
    c, d = np.roll(b, -1, axis=0), np.roll(a, -1, axis=0)  # (i+1, j+1), (i+1, j)
    triangles = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                                np.stack([a, c, d], -1).reshape(-1, 3)])
    return vertices.reshape(-1, 3), around.reshape(-1, 3), triangles


def check_outward(vertices, normals, triangles):
    """Every face's geometric normal (counter-clockwise) agrees with its vertex normals."""
    v0, v1, v2 = (vertices[triangles[:, k]] for k in range(3))
    face = np.cross(v1 - v0, v2 - v0)
    assert np.all(np.sum(face * normals[triangles].sum(axis=1), axis=1) > 0), "inward face"


def write_obj(path, vertices, normals, triangles):
    lines = [f"# (2,3) torus knot tube, {len(triangles)} triangles; written by "
             "scripts/make_lab_assets.py"]
    lines += ["v %.5f %.5f %.5f" % tuple(v) for v in vertices]
    lines += ["vn %.5f %.5f %.5f" % tuple(n) for n in normals]
    lines += ["f %d//%d %d//%d %d//%d" % (a, a, b, b, c, c) for a, b, c in triangles + 1]
    path.write_text("\n".join(lines).replace("-0.00000", "0.00000") + "\n")


# --- Sky probe -------------------------------------------------------------------------------
WIDTH, HEIGHT = 256, 128
SUPERSAMPLE = 4                          # SUPERSAMPLE^2 samples averaged per pixel
ZENITH = np.array([0.30, 0.45, 0.85])
HORIZON = np.array([0.95, 0.97, 1.00])
GROUND_NEAR = np.array([0.20, 0.17, 0.13])
GROUND_NADIR = np.array([0.13, 0.11, 0.09])
SUN_RADIANCE = 200.0 * np.array([1.00, 0.90, 0.75])
SUN_RADIUS = math.radians(3.0)
SUN_ELEVATION, SUN_AZIMUTH = math.radians(35.0), math.radians(135.0)  # phi from -z toward +x


def direction(theta, phi):
    """The renderer's lat-long direction for polar angle theta (from +y) and azimuth phi."""
    theta, phi = np.broadcast_arrays(theta, phi)
    return np.stack([np.sin(theta) * np.sin(phi), np.cos(theta),
                     -np.sin(theta) * np.cos(phi)], axis=-1)


def radiance(omega):
    """Sky above the horizon, ground below, plus the sun disc; omega (..., 3) unit vectors."""
    up = omega[..., 1:2]
    sky = HORIZON + (ZENITH - HORIZON) * np.sqrt(np.clip(up, 0, 1))
    ground = GROUND_NEAR + (GROUND_NADIR - GROUND_NEAR) * np.clip(-up, 0, 1)
    colour = np.where(up >= 0, sky, ground)
    sun = direction(math.pi / 2 - SUN_ELEVATION, SUN_AZIMUTH)
    in_sun = (omega @ sun) >= math.cos(SUN_RADIUS)
    return colour + in_sun[..., None] * SUN_RADIANCE


def sky_image():
    """(HEIGHT, WIDTH, 3) float32 radiance, each pixel the mean over a SUPERSAMPLE^2 grid."""
    sub = (np.arange(SUPERSAMPLE) + 0.5) / SUPERSAMPLE
    theta = ((np.arange(HEIGHT)[:, None] + sub[None, :]) * math.pi / HEIGHT).reshape(-1)
    phi = ((np.arange(WIDTH)[:, None] + sub[None, :]) * 2 * math.pi / WIDTH - math.pi).reshape(-1)
    fine = radiance(direction(theta[:, None], phi[None, :]))
    image = fine.reshape(HEIGHT, SUPERSAMPLE, WIDTH, SUPERSAMPLE, 3).mean(axis=(1, 3))
    assert np.all(np.isfinite(image)) and np.all(image >= 0)
    return image.astype(np.float32)


def exr_attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr_header(width, height, channels):
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in channels)
    window = struct.pack("<4i", 0, 0, width - 1, height - 1)
    return b"".join([
        exr_attribute("channels", "chlist", chlist + b"\0"),        # pixel type 2: FLOAT
        exr_attribute("compression", "compression", b"\0"),         # NONE
        exr_attribute("dataWindow", "box2i", window),
        exr_attribute("displayWindow", "box2i", window),
        exr_attribute("lineOrder", "lineOrder", b"\0"),             # INCREASING_Y
        exr_attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        exr_attribute("screenWindowCenter", "v2f", struct.pack("<2f", 0.0, 0.0)),
        exr_attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
    ]) + b"\0"


def write_exr(path, rgb):
    """A single-part scanline EXR, compression NONE, channels B, G, R as 32-bit float."""
    height, width, _ = rgb.shape
    head = struct.pack("<ii", 20000630, 2) + exr_header(width, height, "BGR")
    planes = rgb[:, :, ::-1].astype("<f4")                          # B, G, R order
    blocks = [struct.pack("<ii", y, width * 3 * 4) + planes[y].T.tobytes() for y in range(height)]
    offsets, position = [], len(head) + 8 * height
    for block in blocks:
        offsets.append(position)
        position += len(block)
    path.write_bytes(head + struct.pack(f"<{height}Q", *offsets) + b"".join(blocks))


def main():
    root = pathlib.Path(__file__).resolve().parent.parent / "web" / "assets"
    root.mkdir(parents=True, exist_ok=True)
    vertices, normals, triangles = knot_mesh()
    check_outward(vertices, normals, triangles)
    write_obj(root / "knot.obj", vertices, normals, triangles)
    radius = np.linalg.norm(vertices, axis=1).max()
    print(f"wrote {root / 'knot.obj'}: {len(vertices)} vertices, {len(triangles)} triangles, "
          f"bounding radius {radius:.3f}, {(root / 'knot.obj').stat().st_size} bytes")
    sky = sky_image()
    write_exr(root / "sky.exr", sky)
    print(f"wrote {root / 'sky.exr'}: {WIDTH}x{HEIGHT} RGB float, radiance {sky.min():.3f} to "
          f"{sky.max():.1f}, {(root / 'sky.exr').stat().st_size} bytes")


if __name__ == "__main__":
    main()
