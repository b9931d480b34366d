#!/usr/bin/env python3
"""Writes the side files of the advanced scenes 15-21 (chapter 4 of seed 000) into
samples/scenes/data/, every name prefixed by its scene number, and prints the constants the
streams use (matrices, light positions, the expected log-average luminance of scene 21).

Standard library only, deterministic; the output is committed, so replaying the scenes does
not need Python. The formats are those of make_textures.py: vertex buffers are tightly packed
little-endian f32 vertices, index buffers u16, texture levels rows of texels tightly packed
(A8R8G8B8 as the 32-bit value 0xAARRGGBB, Q8W8V8U8 as bytes U, V, W, Q, L8 one byte,
A16B16G16R16F as four halves R, G, B, A).

    python3 samples/scenes/make_advanced_data.py              # (re)writes data/15_* .. data/21_*
    python3 samples/scenes/make_advanced_data.py --constants  # prints the streams' constants

Matrices are printed as the four rows of M with clip = M * (x, y, z, 1), the registers
`m4x4 oPos, v0, c0` reads (left-handed, y up, D3D9's z in [0, w]).
"""
import math
import struct
import sys

import scene_data
from scene_data import DATA, write, f32, u16, argb, dot


class Lcg(scene_data.Lcg):
    def uniform(self):
        return self.next() / float(1 << 24)


# ---------------------------------------------------------------- small helpers
def clamp8(v):
    return max(0, min(255, int(math.floor(v + 0.5))))


def snorm8(v):
    """Q8W8V8U8 channel: clamp to [-1, 1], round half away from zero, two's complement byte."""
    v = max(-1.0, min(1.0, v)) * 127.0
    i = int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)
    return i & 0xFF


def half(v):
    """float -> IEEE half bits (struct's 'e' rounds to nearest even)."""
    return struct.unpack("<H", struct.pack("<e", v))[0]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def scale(a, s):
    return [x * s for x in a]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a] if n > 0 else [0.0 for _ in a]


def lerp(a, b, t):
    return a + (b - a) * t


# ---------------------------------------------------------------- matrices (column vectors)
def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def transform(m, p):
    v = list(p) + [1.0] if len(p) == 3 else list(p)
    return [sum(m[i][k] * v[k] for k in range(4)) for i in range(4)]


def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def translate(x, y, z):
    m = identity()
    m[0][3], m[1][3], m[2][3] = x, y, z
    return m


def scaling(x, y, z):
    m = identity()
    m[0][0], m[1][1], m[2][2] = x, y, z
    return m


def rot_x(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]]


def rot_y(deg):
    # left-handed: +deg turns +z towards +x... (x' = c x + s z, z' = -s x + c z)
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]]


def rot_z(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return [[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]


def look_at(eye, at, up=(0.0, 1.0, 0.0)):
    """D3DXMatrixLookAtLH as rows: right, up, forward, with the eye moved to the origin."""
    f = normalize(sub(at, eye))
    r = normalize(cross(up, f))
    u = cross(f, r)
    return [r + [-dot(r, eye)], u + [-dot(u, eye)], f + [-dot(f, eye)], [0.0, 0.0, 0.0, 1.0]]


def perspective(fovy_deg, aspect, near, far):
    """D3DXMatrixPerspectiveFovLH: z' = far (z - near) / (far - near), w' = z."""
    ys = 1.0 / math.tan(math.radians(fovy_deg) / 2)
    xs = ys / aspect
    q = far / (far - near)
    return [[xs, 0, 0, 0], [0, ys, 0, 0], [0, 0, q, -q * near], [0, 0, 1, 0]]


def fmt(v):
    """The shortest text that reads back to the same 32-bit float."""
    bits = struct.pack("<f", v)
    for p in range(1, 10):
        s = "%.*g" % (p, v)
        if struct.pack("<f", float(s)) == bits:
            return s
    return repr(v)


def rows(m, count=4):
    return "   ".join(" ".join(fmt(x) for x in m[i]) for i in range(count))


def vec(*values):
    return " ".join(fmt(x) for x in values)


# ---------------------------------------------------------------- meshes
def wind_outward(tris, positions, normals):
    """Orders every triangle clockwise seen from outside (D3D9's front face in a left-handed
    frame): the plain cross product (b - a) x (c - a) must point along the normal."""
    out = []
    for (a, b, c) in tris:
        n = cross(sub(positions[b], positions[a]), sub(positions[c], positions[a]))
        avg = add(add(normals[a], normals[b]), normals[c])
        out += [a, b, c] if dot(n, avg) > 0 else [a, c, b]
    return out


def grid_tris(cols, rows_):
    w = cols + 1
    tris = []
    for j in range(rows_):
        for i in range(cols):
            a, b, c, d = j * w + i, j * w + i + 1, (j + 1) * w + i + 1, (j + 1) * w + i
            tris += [(a, b, c), (a, c, d)]
    return tris


def torus_tangent(major, minor, rr=0.65, r=0.3):
    """Torus around y: position, normal, tangent (dP/du), binormal (dP/dv), uv in [0, 1].
    u runs around the ring, v around the tube. Seams duplicated."""
    pos, nrm, verts = [], [], b""
    for j in range(minor + 1):
        v = 2 * math.pi * j / minor
        for i in range(major + 1):
            u = 2 * math.pi * i / major
            cu, su, cv, sv = math.cos(u), math.sin(u), math.cos(v), math.sin(v)
            p = [(rr + r * cv) * cu, r * sv, (rr + r * cv) * su]
            n = [cv * cu, sv, cv * su]
            t = [-su, 0.0, cu]
            b = [-sv * cu, cv, -sv * su]
            pos.append(p)
            nrm.append(n)
            verts += f32(*p, *n, *t, *b, i / major, j / minor)
    return verts, u16(wind_outward(grid_tris(major, minor), pos, nrm))


def sphere_tangent(slices, stacks):
    """Unit sphere as make_textures.sphere() (same vertex order, so data/sphere.ib indexes it)
    plus tangent dP/du = (-sin phi, 0, cos phi) and binormal dP/dv (towards the south pole)."""
    vb = b""
    for j in range(stacks + 1):
        theta = math.pi * j / stacks
        for i in range(slices + 1):
            phi = 2 * math.pi * i / slices
            st, ct, sp, cp = math.sin(theta), math.cos(theta), math.sin(phi), math.cos(phi)
            x, y, z = st * cp, ct, st * sp
            vb += f32(x, y, z, x, y, z, -sp, 0.0, cp, ct * cp, -st, ct * sp, i / slices, j / stacks)
    return vb


# ---------------------------------------------------------------- scene 15: normal maps
def tile_height(x, y):
    """One square tile per texture repeat: flat top, 45-degree bevel 6 texels wide, grout."""
    d = min(x, y, 1.0 - x, 1.0 - y) * 64.0  # distance to the tile edge in texels
    return min(1.0, max(0.0, (d - 1.5) / 6.0))


def normal_from_height(hfun, size, strength):
    """Tangent-space normals (-dh/du, -dh/dv, 1) by central differences, wrapped."""
    out = []
    for y in range(size):
        for x in range(size):
            u, v = (x + 0.5) / size, (y + 0.5) / size
            e = 1.0 / size
            du = (hfun((u + e) % 1.0, v) - hfun((u - e) % 1.0, v)) / 2.0
            dv = (hfun(u, (v + e) % 1.0) - hfun(u, (v - e) % 1.0)) / 2.0
            out.append((normalize([-du * strength, -dv * strength, 1.0]), hfun(u, v)))
    return out


def tiles_a8r8g8b8(size):
    """A8R8G8B8: rgb = n * 0.5 + 0.5, alpha = albedo (grout darker)."""
    data = b""
    for (n, h) in normal_from_height(tile_height, size, 6.0):
        r, g, b = (clamp8((c * 0.5 + 0.5) * 255) for c in n)
        data += argb(clamp8((0.45 + 0.55 * min(1.0, h * 4)) * 255), r, g, b)
    return data


def rivet_height(u, v):
    """Hemispherical rivets on a 2 x 2 grid per texture repeat, radius 0.17 of a cell."""
    cu, cv = (u * 2) % 1.0 - 0.5, (v * 2) % 1.0 - 0.5
    d = math.sqrt(cu * cu + cv * cv) / 0.34
    return math.sqrt(max(0.0, 1 - d * d)) * 0.6


def rivets_q8w8v8u8(size):
    """Q8W8V8U8 (signed): U, V, W = the normal, Q = 1 (bytes U, V, W, Q)."""
    data = b""
    for (n, _) in normal_from_height(rivet_height, size, 3.0):
        data += bytes([snorm8(n[0]), snorm8(n[1]), snorm8(n[2]), snorm8(1.0)])
    return data


# ---------------------------------------------------------------- scene 16: Perlin noise
def perlin_volume(n, period):
    """Ken Perlin's gradient noise (2002 fade curve, 12 edge gradients) on a lattice of
    period^3 cells, evaluated at the n^3 texel centres and wrapped, so opposite faces of the
    volume continue each other under WRAP addressing; mapped to L8 by its own min/max."""
    rng = Lcg(16)
    perm = list(range(period))
    for i in range(period - 1, 0, -1):
        k = rng.next() % (i + 1)
        perm[i], perm[k] = perm[k], perm[i]
    grads = [(1, 1, 0), (-1, 1, 0), (1, -1, 0), (-1, -1, 0), (1, 0, 1), (-1, 0, 1), (1, 0, -1), (-1, 0, -1),
             (0, 1, 1), (0, -1, 1), (0, 1, -1), (0, -1, -1)]
    table = {}
    for x in range(period):
        for y in range(period):
            for z in range(period):
                table[(x, y, z)] = grads[(perm[(perm[(perm[x] + y) % period] + z) % period] * 7 + x + 3 * y) % 12]

    def fade(t):
        return t * t * t * (t * (t * 6 - 15) + 10)

    values = []
    for z in range(n):
        for y in range(n):
            for x in range(n):
                p = [(c + 0.5) * period / n for c in (x, y, z)]
                i0 = [int(math.floor(c)) for c in p]
                f = [c - i for c, i in zip(p, i0)]
                acc = 0.0
                for corner in range(8):
                    o = [(corner >> k) & 1 for k in range(3)]
                    g = table[tuple((i0[k] + o[k]) % period for k in range(3))]
                    w = 1.0
                    for k in range(3):
                        w *= fade(f[k]) if o[k] else 1 - fade(f[k])
                    acc += w * sum(g[k] * (f[k] - o[k]) for k in range(3))
                values.append(acc)
    lo, hi = min(values), max(values)
    return bytes(clamp8((v - lo) / (hi - lo) * 255) for v in values)


def marble_ramp(size):
    """A8R8G8B8 size x 1: white marble with thin dark grey-green veins, one vein per repeat."""
    data = b""
    for x in range(size):
        t = (x + 0.5) / size
        vein = math.exp(-((t - 0.5) / 0.07) ** 2)
        halo = math.exp(-((t - 0.5) / 0.2) ** 2)
        r = 0.93 - 0.2 * halo - 0.6 * vein
        g = 0.92 - 0.15 * halo - 0.52 * vein
        b = 0.88 - 0.12 * halo - 0.55 * vein
        data += argb(255, clamp8(r * 255), clamp8(g * 255), clamp8(b * 255))
    return data


# ---------------------------------------------------------------- scene 17: environment
CUBE_FACES = ["POSITIVE_X", "NEGATIVE_X", "POSITIVE_Y", "NEGATIVE_Y", "POSITIVE_Z", "NEGATIVE_Z"]


def face_direction(face, sc, tc):
    """The direction a texel of a face stands for (spec/pipeline.md 14.4, inverted)."""
    return [[1.0, -tc, -sc], [-1.0, -tc, sc], [sc, 1.0, tc], [sc, -1.0, -tc], [sc, -tc, 1.0], [-sc, -tc, -1.0]][face]


SUN = normalize([0.5, 0.55, 0.65])


def environment(d):
    """An outdoor scene: sky gradient with a sun, a checkered ground plane at y = -1, and
    eight coloured pillars round the horizon (so that directions are easy to read)."""
    d = normalize(d)
    az = math.degrees(math.atan2(d[0], d[2])) % 360.0
    el = math.degrees(math.asin(max(-1.0, min(1.0, d[1]))))
    for k in range(8):
        centre = k * 45.0 + 22.5
        da = abs((az - centre + 180.0) % 360.0 - 180.0)
        if da < 7.0 and -8.0 < el < 22.0 + 6 * (k % 3):
            col = [[0.9, 0.2, 0.15], [0.95, 0.6, 0.1], [0.95, 0.9, 0.2], [0.3, 0.8, 0.2],
                   [0.15, 0.7, 0.8], [0.2, 0.3, 0.9], [0.6, 0.25, 0.85], [0.95, 0.95, 0.95]][k]
            shade = 0.55 + 0.45 * math.cos(math.radians(da / 7.0 * 80.0))
            return [c * shade for c in col]
    if d[1] < 0:
        t = -1.0 / d[1]
        px, pz = d[0] * t, d[2] * t
        check = (int(math.floor(px)) + int(math.floor(pz))) % 2
        fadeout = min(1.0, t / 25.0)
        c = [0.75, 0.68, 0.55] if check else [0.35, 0.3, 0.25]
        far = [0.55, 0.5, 0.42]
        return [lerp(a, b, fadeout) for a, b in zip(c, far)]
    h = d[1]
    sky = [lerp(0.85, 0.2, h ** 0.5), lerp(0.9, 0.4, h ** 0.5), lerp(1.0, 0.85, h ** 0.5)]
    s = dot(d, SUN)
    if s > 0.995:
        return [1.0, 1.0, 0.9]
    glow = max(0.0, s) ** 40 * 0.5
    return [c + glow for c in sky]


def cube_face(face, edge):
    data = b""
    for y in range(edge):
        for x in range(edge):
            sc, tc = 2 * (x + 0.5) / edge - 1, 2 * (y + 0.5) / edge - 1
            c = environment(face_direction(face, sc, tc))
            data += argb(255, *(clamp8(v * 255) for v in c))
    return data


# ---------------------------------------------------------------- scene 18: shadow-map scene
def box(cx, cy, cz, sx, sy, sz, rot=0.0):
    """A box as 12 triangles, position + normal, clockwise from outside."""
    out = []
    m = rot_y(rot)
    faces = [([1, 0, 0], [0, 0, 1], [0, 1, 0]), ([-1, 0, 0], [0, 0, -1], [0, 1, 0]),
             ([0, 1, 0], [1, 0, 0], [0, 0, 1]), ([0, -1, 0], [1, 0, 0], [0, 0, -1]),
             ([0, 0, 1], [-1, 0, 0], [0, 1, 0]), ([0, 0, -1], [1, 0, 0], [0, 1, 0])]
    for (n, a, b) in faces:
        corners = []
        for (s, t) in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            p = [n[k] * [sx, sy, sz][k] + s * a[k] * [sx, sy, sz][k] + t * b[k] * [sx, sy, sz][k] for k in range(3)]
            p = transform(m, p)[:3]
            corners.append([p[0] + cx, p[1] + cy, p[2] + cz])
        nn = transform(m, n + [0.0])[:3]
        for tri in ((0, 1, 2), (0, 2, 3)):
            pa, pb, pc = (corners[i] for i in tri)
            if dot(cross(sub(pb, pa), sub(pc, pa)), nn) < 0:
                pb, pc = pc, pb
            out += [(pa, nn), (pb, nn), (pc, nn)]
    return out


def tris_pn(tris):
    return b"".join(f32(*p, *n) for (p, n) in tris)


def shadow_scene():
    ground = []
    g = [[-6, 0, -6], [6, 0, -6], [6, 0, 6], [-6, 0, 6]]
    up = [0.0, 1.0, 0.0]
    for tri in ((0, 3, 2), (0, 2, 1)):
        ground += [(g[i], up) for i in tri]
    # clockwise from above check
    pa, pb, pc = ground[0][0], ground[1][0], ground[2][0]
    assert dot(cross(sub(pb, pa), sub(pc, pa)), up) > 0
    objects = box(-1.2, 0.6, 0.3, 0.6, 0.6, 0.6, 25.0)          # a cube
    objects += box(1.3, 1.0, 1.2, 0.18, 1.0, 0.18, 0.0)          # a thin pillar
    objects += box(0.6, 0.2, -1.1, 1.0, 0.2, 0.3, -15.0)        # a low bench
    objects += box(1.3, 2.05, 1.2, 0.9, 0.05, 0.9, 10.0)        # a table top on the pillar
    return tris_pn(ground + objects), len(ground) // 3, len(objects) // 3


# ---------------------------------------------------------------- scene 19: shadow volumes
def shadow_volume_mesh(positions, faces):
    """A closed mesh made ready for extrusion in the vertex shader (000 l.4280): every
    triangle gets its own three vertices carrying the face normal, and every edge (shared by
    two faces) gets a quad of two zero-area triangles joining the two faces' copies of its
    end points. Vertex: position, face normal. Returns (vertex bytes, u16 indices,
    face triangle count, edge triangle count); face triangles come first in the index list."""
    verts, idx = [], []
    edge_owner = {}
    for fi, (a, b, c) in enumerate(faces):
        pa, pb, pc = positions[a], positions[b], positions[c]
        n = normalize(cross(sub(pb, pa), sub(pc, pa)))
        base = len(verts)
        verts += [(pa, n), (pb, n), (pc, n)]
        idx += [base, base + 1, base + 2]
        for k, (s, e) in enumerate(((a, b), (b, c), (c, a))):
            edge_owner[(s, e)] = (base + k, base + (k + 1) % 3)
    faces_tris = len(idx) // 3
    for (s, e), (vs, ve) in sorted(edge_owner.items()):
        if s > e:
            continue
        assert (e, s) in edge_owner, "mesh not closed"
        ws, we = edge_owner[(e, s)]  # the neighbour's copies: we is at s, ws is at e
        # edge s -> e in this face; the side face runs e -> s here and s -> e on the neighbour
        idx += [ve, vs, we, ve, we, ws]
    data = b"".join(f32(*p, *n) for (p, n) in verts)
    return data, u16(idx), faces_tris, len(idx) // 3 - faces_tris


def cube_mesh(cx, cy, cz, s, rot_deg):
    m = matmul(rot_y(rot_deg[1]), rot_x(rot_deg[0]))
    pos = []
    for k in range(8):
        p = [(-1 if not (k & 1) else 1) * s, (-1 if not (k & 2) else 1) * s, (-1 if not (k & 4) else 1) * s]
        p = transform(m, p)[:3]
        pos.append([p[0] + cx, p[1] + cy, p[2] + cz])
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    faces = []
    centre = [cx, cy, cz]
    for (a, b, c, d) in quads:
        for tri in ((a, b, c), (a, c, d)):
            pa, pb, pc = (pos[i] for i in tri)
            out = sub(add(add(pa, pb), pc), scale(centre, 3))
            faces.append(tri if dot(cross(sub(pb, pa), sub(pc, pa)), out) > 0 else (tri[0], tri[2], tri[1]))
    return pos, faces


def torus_mesh(major, minor, rr, r, centre, tilt):
    m = rot_x(tilt)
    pos = []
    for j in range(minor):
        v = 2 * math.pi * j / minor
        for i in range(major):
            u = 2 * math.pi * i / major
            p = [(rr + r * math.cos(v)) * math.cos(u), r * math.sin(v), (rr + r * math.cos(v)) * math.sin(u)]
            p = transform(m, p)[:3]
            pos.append(add(p, centre))
    faces = []
    for j in range(minor):
        for i in range(major):
            a, b = j * major + i, j * major + (i + 1) % major
            c, d = ((j + 1) % minor) * major + (i + 1) % major, ((j + 1) % minor) * major + i
            for tri in ((a, b, c), (a, c, d)):
                pa, pb, pc = (pos[k] for k in tri)
                u = 2 * math.pi * (i + 0.5) / major
                ring = add(transform(m, [rr * math.cos(u), 0.0, rr * math.sin(u)])[:3], centre)
                mid = scale(add(add(pa, pb), pc), 1 / 3)
                out = sub(mid, ring)
                faces.append(tri if dot(cross(sub(pb, pa), sub(pc, pa)), out) > 0 else (tri[0], tri[2], tri[1]))
    return pos, faces


def merge_meshes(meshes):
    pos, faces = [], []
    for (p, f) in meshes:
        base = len(pos)
        pos += p
        faces += [(a + base, b + base, c + base) for (a, b, c) in f]
    return pos, faces


# ---------------------------------------------------------------- scene 21: HDR image
def hdr_pixel(x, y, w, h):
    """A dark church interior with a sunlit stained-glass window (000 l.4530): radiance in
    linear RGB, from about 0.01 in the corners to 60 in the window's panes."""
    u, v = (x + 0.5) / w, (y + 0.5) / h
    # window: a pointed arch between u 0.36..0.64, v 0.12..0.62
    wx, wy = (u - 0.5) / 0.14, v
    in_rect = abs(wx) < 1.0 and 0.3 < wy < 0.62
    arch_c = 0.3
    in_arch = wy <= 0.3 and wy > 0.12 and ((abs(wx) + 1.0) ** 2 * 0.0196 / 0.0784 + ((arch_c - wy) / 0.18) ** 2) < 1.0
    if in_rect or in_arch:
        # lead lines every 0.25 in wx and 0.07 in v
        lead = abs((wx * 2) % 1.0 - 0.5) > 0.44 or abs((v / 0.07) % 1.0 - 0.5) > 0.43
        if lead:
            return [0.02, 0.018, 0.015]
        cell = int(math.floor(wx * 2 + 2)) * 7 + int(math.floor(v / 0.07)) * 3
        panes = [[1.0, 0.15, 0.1], [0.15, 0.3, 1.0], [1.0, 0.8, 0.2], [0.2, 0.9, 0.3], [0.7, 0.2, 0.9], [1.0, 1.0, 0.95]]
        c = panes[cell % len(panes)]
        glow = 40.0 + 25.0 * (1.0 - abs(wx)) * (1 - v)
        return [k * glow for k in c]
    # walls: stone blocks, light falling off from the window
    dist = math.sqrt(((u - 0.5) / 0.5) ** 2 + ((v - 0.37) / 0.6) ** 2)
    light = 0.35 / (0.15 + dist * dist * 3.0)
    mortar = abs((v * 12) % 1.0 - 0.5) > 0.46 or abs(((u * 8) + (0.5 if int(v * 12) % 2 else 0.0)) % 1.0 - 0.5) > 0.47
    row = int(v * 12)
    block = int(u * 8 + (0.5 if row % 2 else 0.0))
    stone = 0.55 if mortar else 0.75 + 0.25 * ((block * 7 + row * 13) % 5) / 4
    col = [0.75, 0.62, 0.48]
    if v > 0.8:  # floor with a coloured patch of sunlight through the window
        stone = 0.7
        col = [0.5, 0.42, 0.35]
        pu, pv = (u - 0.62) / 0.12, (v - 0.9) / 0.06
        if pu * pu + pv * pv < 1.0:
            patch = [[2.5, 0.6, 0.4], [0.6, 0.9, 2.5], [2.4, 2.0, 0.7]][int((pu + 1) * 1.5) % 3]
            return [k * 1.0 for k in patch]
    return [k * light * stone for k in col]


def hdr_image(w, h):
    data = b""
    lums = []
    for y in range(h):
        for x in range(w):
            rgb = hdr_pixel(x, y, w, h)
            hv = [half(c) for c in rgb] + [half(1.0)]
            data += struct.pack("<4H", *hv)
            stored = [struct.unpack("<e", struct.pack("<H", b))[0] for b in hv[:3]]
            lums.append((max(stored) + min(stored)) / 2.0)
    return data, lums


# ---------------------------------------------------------------- constants for the streams
def constants():
    out = []
    # scene 15: three 256x256 viewports, eye (0, 1.2, -2.6) looking at (0, 0, 0), 45 degrees
    vp = matmul(perspective(45.0, 1.0, 0.5, 20.0), look_at([0.0, 1.2, -2.6], [0.0, 0.0, 0.0]))
    torus_world = matmul(rot_x(-35.0), rot_y(20.0))
    sphere_world = rot_y(-30.0)
    out.append("# 15: torus view-projection * world (c0..c3), world rows (c4..c6)")
    out.append(rows(matmul(vp, torus_world)))
    out.append(rows(torus_world, 3))
    out.append("# 15: sphere view-projection * world, world")
    out.append(rows(matmul(vp, sphere_world)))
    out.append(rows(sphere_world, 3))
    # scene 16: eye (0, 0.3, -3), sphere rotated
    vp16 = matmul(perspective(40.0, 1.0, 0.5, 20.0), look_at([0.0, 0.3, -3.0], [0.0, 0.0, 0.0]))
    w16 = matmul(rot_y(-25.0), rot_x(15.0))
    out.append("# 16: view-projection * world, world rows")
    out.append(rows(matmul(vp16, w16)))
    out.append(rows(w16, 3))
    # scene 17: eye (0, 0.4, -3.2)
    vp17 = matmul(perspective(45.0, 1.0, 0.5, 50.0), look_at([0.0, 0.4, -3.2], [0.0, 0.0, 0.0]))
    out.append("# 17: view-projection; sky corner directions (right*tan, up*tan, forward)")
    out.append(rows(vp17))
    view17 = look_at([0.0, 0.4, -3.2], [0.0, 0.0, 0.0])
    t = math.tan(math.radians(22.5))
    out.append(vec(*scale(view17[0][:3], t), 0) + "   " + vec(*scale(view17[1][:3], t), 0) + "   " + vec(*view17[2][:3], 0))
    # scene 18: camera and light
    vp18 = matmul(perspective(45.0, 1.0, 1.0, 30.0), look_at([4.5, 5.0, -7.0], [0.0, 0.5, 0.0]))
    light18 = [-3.0, 7.0, -2.0]
    lvp18 = matmul(perspective(60.0, 1.0, 4.0, 14.0), look_at(light18, [0.2, 0.0, 0.3]))
    out.append("# 18: camera view-projection (c0..c3), light view-projection (c8..c11), light position")
    out.append(rows(vp18))
    out.append(rows(lvp18))
    out.append(vec(*light18, 1))
    # scene 19
    vp19 = matmul(perspective(50.0, 1.0, 0.5, 500.0), look_at([3.5, 4.5, -6.5], [0.0, 0.6, 0.0]))
    out.append("# 19: view-projection, light")
    out.append(rows(vp19))
    # scene 20
    vp20 = matmul(perspective(40.0, 1.0, 0.5, 40.0), look_at([-0.6, 1.1, -3.0], [0.2, 0.4, 2.0]))
    v20 = look_at([-0.6, 1.1, -3.0], [0.2, 0.4, 2.0])
    out.append("# 20: view-projection, view row 2 (view-space z)")
    out.append(rows(vp20))
    out.append(rows([v20[2]], 1))
    out.append("# 20: blur taps c0..c11 of passes 1-3: 12 points of a golden-angle spiral in the unit disk,")
    out.append("#     turned by 0, 40 and 80 degrees, times Cmax / 2 / 256 (Cmax = 10 pixels)")
    for turn in (0.0, 40.0, 80.0):
        taps = []
        for i in range(12):
            rad = math.sqrt((i + 0.5) / 12)
            ang = i * math.pi * (3 - math.sqrt(5)) + math.radians(turn)
            taps.append(vec(rad * math.cos(ang) * 5 / 256, rad * math.sin(ang) * 5 / 256, 0, 0))
        out.append("   ".join(taps))
    return "\n".join(out)


def main():
    files = {}
    files["15_torus.vb"], files["15_torus.ib"] = torus_tangent(12, 8)
    files["15_sphere.vb"] = sphere_tangent(32, 16)
    files["15_tiles_64.bin"] = tiles_a8r8g8b8(64)
    files["15_rivets_64.bin"] = rivets_q8w8v8u8(64)
    files["16_noise_32.bin"] = perlin_volume(32, 8)
    files["16_marble_ramp.bin"] = marble_ramp(64)
    for f in range(6):
        files["17_cube_%s.bin" % CUBE_FACES[f].lower()] = cube_face(f, 64)
    files["18_scene.vb"], ground_tris, object_tris = shadow_scene()
    pos, faces = merge_meshes([cube_mesh(-1.2, 1.3, 0.5, 0.45, (20.0, 35.0)),
                               torus_mesh(12, 6, 0.55, 0.2, [0.9, 1.7, -0.2], -30.0)])
    files["19_occluders.vb"], files["19_occluders.ib"], face_tris, edge_tris = shadow_volume_mesh(pos, faces)
    files["21_hdr_128.bin"], lums = hdr_image(128, 128)
    if "--constants" in sys.argv:
        print(constants())
        print("# 18: %d ground triangles, %d object triangles" % (ground_tris, object_tris))
        print("# 19: %d vertices, %d face triangles, %d edge triangles" %
              (len(files["19_occluders.vb"]) // 24, face_tris, edge_tris))
        # scene 21: the log-average luminance as the passes compute it: the mean of log2 over
        # 2x2 blocks, then 4x4 means (exactly the mean of all pixels), then exp2
        delta = 1e-4
        mean = sum(math.log2(delta + l) for l in lums) / len(lums)
        print("# 21: log-average lightness exp2(mean(log2(1e-4 + L))) = %.6f (min %.4f max %.2f)" %
              (2 ** mean, min(lums), max(lums)))
        return
    total = 0
    for name in sorted(files):
        total += write(name, files[name])
    print("wrote %d files, %d bytes, into %s" % (len(files), total, DATA))


if __name__ == "__main__":
    main()
