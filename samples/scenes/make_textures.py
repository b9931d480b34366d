#!/usr/bin/env python3
"""Writes the side files of the scene command streams into samples/scenes/data/.

Standard library only; the output is committed, so replaying the scenes does not need Python.
Every file is raw little-endian data as the stream's Lock / LockRect / LockBox expects it
(vertex buffers: tightly packed f32 vertices; index buffers: u16; textures: rows of texels
tightly packed, A8R8G8B8 texels stored as the 32-bit value 0xAARRGGBB, i.e. bytes B, G, R, A).

    python3 samples/scenes/make_textures.py          # (re)writes samples/scenes/data/*
"""
import math
import struct

import scene_data
from scene_data import DATA, write, f32, u16, argb


class Lcg(scene_data.Lcg):
    def pick(self, items):
        return items[self.next() % len(items)]


def clamp8(v):
    return max(0, min(255, int(round(v))))


def hue(h, s=0.55, v=0.85):
    """HSV to RGB in [0, 1]."""
    h = (h % 1.0) * 6.0
    i = int(h)
    f = h - i
    p, q, t = v * (1 - s), v * (1 - s * f), v * (1 - s * (1 - f))
    return [(v, t, p), (q, v, p), (p, v, t), (p, q, v), (t, p, v), (v, p, q)][i % 6]


# ---------------------------------------------------------------- scene 2: shared-edge meshes
def to_clip(xs, ys, size=256.0):
    """Viewport pixel coordinates (pixel centres at integers) to clip x, y for a size x size
    viewport: Xs = (x + 1) * W/2, Ys = (1 - y) * H/2."""
    return xs / (size / 2) - 1.0, 1.0 - ys / (size / 2)


def scene02():
    # (a) a 9x9 grid of vertices from -16 to 272 pixels (36 apart), interior vertices moved by
    # sub-pixel amounts (0, halves, quarters, 1/256, ...), cells split along alternating
    # diagonals. Grid lines at jitter 0 run exactly through pixel centres.
    rng = Lcg(2)
    jitters = [0.0, 0.0, 0.5, -0.5, 0.25, -0.75, 1.0 / 256, -1.0 / 256, 0.125, 3.0, -5.5, 7.25]
    n = 8
    pts = {}
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = -16.0 + 36 * i, -16.0 + 36 * j
            if 0 < i < n and 0 < j < n:
                x += rng.pick(jitters)
                y += rng.pick(jitters)
            pts[(i, j)] = (x, y)
    tris = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = pts[(i, j)], pts[(i + 1, j)], pts[(i + 1, j + 1)], pts[(i, j + 1)]
            if (i + j) % 2 == 0:  # clockwise on screen (y down): a b c, a c d
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    grid = b""
    for k, tri in enumerate(tris):
        r, g, b = hue(k * 0.137, 0.5, 0.75)
        for (x, y) in tri:
            grid += f32(*to_clip(x, y), 0.5, r, g, b, 1.0)
    # (b) a fan of 32 triangles around the pixel centre (128, 128) out to a square of half-size
    # 160: every spoke ends on integer pixel coordinates, so spokes of slope 0, 1, 1/2, 1/4 ...
    # run exactly through pixel centres.
    ring = []
    for t in range(-160, 160, 40):
        ring.append((128 + t, 128 - 160))          # top edge, left to right
    for t in range(-160, 160, 40):
        ring.append((128 + 160, 128 + t))          # right edge, top to bottom
    for t in range(160, -160, -40):
        ring.append((128 + t, 128 + 160))          # bottom edge, right to left
    for t in range(160, -160, -40):
        ring.append((128 - 160, 128 + t))          # left edge, bottom to top
    fan = b""
    for k in range(len(ring)):
        p, q = ring[k], ring[(k + 1) % len(ring)]
        r, g, b = hue(k * 0.211 + 0.05, 0.5, 0.75)
        for (x, y) in ((128.0, 128.0), p, q):      # clockwise on screen
            fan += f32(*to_clip(float(x), float(y)), 0.5, r, g, b, 1.0)
    return {"02_grid.vb": grid, "02_fan.vb": fan}


# ---------------------------------------------------------------- meshes
def sphere(slices, stacks):
    """Unit sphere: position, normal, uv (u around, v from the north pole). Seam duplicated."""
    vb = b""
    for j in range(stacks + 1):
        theta = math.pi * j / stacks
        for i in range(slices + 1):
            phi = 2 * math.pi * i / slices
            x, y, z = math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)
            vb += f32(x, y, z, x, y, z, i / slices, j / stacks)
    ib = []
    w = slices + 1
    for j in range(stacks):
        for i in range(slices):
            a, b, c, d = j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i
            # seen from outside (left-handed, y up; at the -z side x grows with i): a b c, a c d are
            # clockwise on screen
            ib += [a, b, c, a, c, d]
    return vb, u16(ib)


def cylinder(rings, segments, radius=0.3, height=3.0):
    """Cylinder along +y from 0 to height: position, normal, two blend weights (bones 0, 1;
    bone 2 gets 1 - w0 - w1). Bones pivot at y = 1 and y = 2; weights blend over +-0.4."""
    def smooth(e0, e1, x):
        t = min(1.0, max(0.0, (x - e0) / (e1 - e0)))
        return t * t * (3 - 2 * t)

    vb = b""
    for j in range(rings + 1):
        y = height * j / rings
        s1 = smooth(0.6, 1.4, y)   # share of bone 1 and beyond
        s2 = smooth(1.6, 2.4, y)   # share of bone 2
        w0, w1 = 1.0 - s1, s1 - s2
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            nx, nz = math.cos(phi), math.sin(phi)
            vb += f32(radius * nx, y, radius * nz, nx, 0.0, nz, w0, w1)
    ib = []
    w = segments + 1
    for j in range(rings):
        for i in range(segments):
            a, b, c, d = j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i
            ib += [a, c, b, a, d, c]
    return vb, u16(ib)


def grid(n, half):
    """A flat n x n grid of cells in x, z in [-half, half] (FLOAT2 x, z), indexed."""
    vb = b""
    for j in range(n + 1):
        for i in range(n + 1):
            vb += f32(-half + 2 * half * i / n, -half + 2 * half * j / n)
    ib = []
    w = n + 1
    for j in range(n):
        for i in range(n):
            a, b, c, d = j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i
            # seen from above (+y), z away from the viewer: a d c, a c b is clockwise
            ib += [a, d, c, a, c, b]
    return vb, u16(ib)


def slices(count):
    """View-aligned quads at z from +0.9 (far) to -0.9 (near): FLOAT3 positions, drawn back to
    front as a triangle list (two triangles a slice, clockwise on screen)."""
    vb = b""
    for k in range(count):
        z = 0.9 - 1.8 * k / (count - 1)
        s = 0.9
        quad = [(-s, s), (s, s), (s, -s), (-s, s), (s, -s), (-s, -s)]
        for (x, y) in quad:
            vb += f32(x, y, z)
    return vb


# ---------------------------------------------------------------- textures
def checker_l8(size, square):
    """L8 checkerboard: white square at (0, 0)."""
    out = bytearray()
    for y in range(size):
        for x in range(size):
            out.append(255 if ((x // square) + (y // square)) % 2 == 0 else 0)
    return bytes(out)


def address_pattern():
    """16x16 A8R8G8B8: red grows with x (17 per texel), green with y; a blue 4x4 marker in the
    top-left corner and a white texel at (15, 0) so flips are easy to see."""
    out = b""
    for y in range(16):
        for x in range(16):
            r, g, b = 17 * x, 17 * y, 64
            if x < 4 and y < 4:
                b = 255
            if x == 15 and y == 0:
                r, g, b = 255, 255, 255
            out += argb(255, r, g, b)
    return out


# Face colours of the environment cube (+X, -X, +Y, -Y, +Z, -Z) and the order LockRect names them.
CUBE_FACES = ["POSITIVE_X", "NEGATIVE_X", "POSITIVE_Y", "NEGATIVE_Y", "POSITIVE_Z", "NEGATIVE_Z"]
CUBE_COLOURS = [(230, 60, 50), (60, 200, 220), (70, 200, 60), (200, 70, 200), (60, 80, 230), (235, 200, 40)]


def cube_face(face, edge):
    """A face: its colour, darkened towards the edges along u (x) and brightened along v, with
    a dark grid line every 8 texels (texels 7, 15, 23, 31) so the reflection shows the
    distortion."""
    base = CUBE_COLOURS[face]
    out = b""
    for y in range(edge):
        for x in range(edge):
            if x % 8 == 7 or y % 8 == 7:
                out += argb(255, 20, 20, 20)
                continue
            k = 0.55 + 0.45 * (x + 0.5) / edge
            l = 0.25 * (y + 0.5) / edge
            r, g, b = (clamp8(c * k + 255 * l) for c in base)
            out += argb(255, r, g, b)
    return out


def volume_a4r4g4b4(n):
    """n^3 A4R4G4B4 (16-bit value A R G B from the top nibble): a hollow sphere shell and a
    solid inner blob; colour follows the position (r = x, g = y, b = z)."""
    out = b""
    for z in range(n):
        for y in range(n):
            for x in range(n):
                px, py, pz = ((c + 0.5) / n * 2 - 1 for c in (x, y, z))
                d = math.sqrt(px * px + py * py + pz * pz)
                shell = max(0.0, 1 - abs(d - 0.8) / 0.12)
                blob = max(0.0, 1 - math.sqrt((px - 0.2) ** 2 + (py + 0.15) ** 2 + pz ** 2) / 0.35)
                a = min(1.0, shell + blob)
                r, g, b = (px + 1) / 2, (py + 1) / 2, (pz + 1) / 2
                if blob > shell:
                    r, g, b = 1.0, 0.9, 0.3
                v = (round(a * 15) << 12) | (round(r * 15) << 8) | (round(g * 15) << 4) | round(b * 15)
                out += struct.pack("<H", v)
    return out


def bricks(size):
    """A8R8G8B8 brick wall: rows of 8 texels, bricks 16 wide, offset every other row,
    light mortar lines."""
    out = b""
    for y in range(size):
        for x in range(size):
            row = y // 8
            xx = x + (8 if row % 2 else 0)
            mortar = (y % 8 == 0) or (xx % 16 == 0)
            if mortar:
                out += argb(255, 200, 195, 185)
            else:
                shade = 0.85 + 0.15 * (((xx // 16) * 7 + row * 3) % 5) / 4
                out += argb(255, clamp8(170 * shade), clamp8(70 * shade), clamp8(45 * shade))
    return out


def main():
    files = {}
    files.update(scene02())
    files["sphere.vb"], files["sphere.ib"] = sphere(32, 16)
    files["cylinder.vb"], files["cylinder.ib"] = cylinder(24, 16)
    files["lake.vb"], files["lake.ib"] = grid(48, 8.0)
    files["slices.vb"] = slices(64)
    files["checker_l8_128.bin"] = checker_l8(128, 8)
    files["address_16.bin"] = address_pattern()
    for f in range(6):
        files["cube_%s.bin" % CUBE_FACES[f].lower()] = cube_face(f, 32)
    files["volume_32.bin"] = volume_a4r4g4b4(32)
    files["bricks_64.bin"] = bricks(64)
    total = 0
    for name in sorted(files):
        total += write(name, files[name])
    print("wrote %d files, %d bytes, into %s" % (len(files), total, DATA))


if __name__ == "__main__":
    main()
