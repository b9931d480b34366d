"""What the scene data generators (make_textures.py, make_advanced_data.py,
make_deferred_data.py) share: writing into samples/scenes/data/, packing little-endian values as
the streams' Lock / LockRect / LockBox expect them, and a deterministic random generator.
Standard library only.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data")


def write(name, data):
    os.makedirs(DATA, exist_ok=True)
    with open(os.path.join(DATA, name), "wb") as f:
        f.write(data)
    return len(data)


def f32(*values):
    return struct.pack("<%df" % len(values), *values)


def u16(values):
    return struct.pack("<%dH" % len(values), *values)


def argb(a, r, g, b):
    """An A8R8G8B8 texel: the 32-bit value 0xAARRGGBB (bytes B, G, R, A)."""
    return struct.pack("<I", (a << 24) | (r << 16) | (g << 8) | b)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def smoothstep(e0, e1, x):
    t = min(1.0, max(0.0, (x - e0) / (e1 - e0)))
    return t * t * (3 - 2 * t)


class Lcg:
    """A tiny deterministic generator (the same numbers on every Python version)."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFF

    def next(self):
        self.state = (self.state * 1664525 + 1013904223) & 0xFFFFFFFF
        return self.state >> 8
