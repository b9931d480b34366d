#!/usr/bin/env python3
"""Writes the side files of the deferred-rendering scenes 22-27 into samples/scenes/data/deferred_*.

Standard library only, deterministic; the output is committed, so replaying the scenes does not
need Python. Every file is raw little-endian data as the stream's Lock / LockRect expects it.

    python3 samples/scenes/make_deferred_data.py              # (re)writes data/deferred_*
    python3 samples/scenes/make_deferred_data.py --constants  # prints the shader constants and
                                                              # draw ranges the streams use

The scene (one world for all six streams, 002 l.487-1467): a tiled floor, three boxes, two
spheres and a thin emissive "neon" tube, baked in world space (left-handed, y up) into one
vertex buffer. Vertex layout (44 bytes): position FLOAT3, normal FLOAT3, tangent FLOAT3 (the
direction of increasing u), texcoord FLOAT2. Every mesh is built so that the direction of
increasing v is cross(normal, tangent), so the vertex shader rebuilds the binormal with `crs`.
Triangles are clockwise seen from outside (D3D9's front faces under the default CULLMODE CCW).

Light volumes (positions only, FLOAT3, also clockwise from outside):
  deferred_icosphere  an icosahedron subdivided once (42 vertices, 80 triangles), scaled so
                      that every face lies outside the unit sphere (002 l.739: "covers the whole
                      volume of the unit sphere").
  deferred_cone       apex at the origin, base a 16-gon circumscribed about the unit circle
                      centred at (0, -1, 0) in a plane parallel to XZ (002 l.1054).
  deferred_capsule    a unit sphere cut by the XZ plane, the halves moved 0.5 up and down and
                      joined by a cylinder (002 l.767), parallels and meridians, scaled out so
                      the tessellated surface encloses the round capsule.

Textures (A8R8G8B8, stored as the 32-bit value 0xAARRGGBB):
  deferred_tiles_albedo_128   2 x 2 floor tiles with grout, a little colour variation per tile
  deferred_tiles_normal_128   the matching tangent-space normal map: bevelled tile edges, grout
                              grooves, a gentle waviness (R = x, G = y, B = z, each * 0.5 + 0.5)
  deferred_bumps_normal_64    one round dome per texture (tiled: a grid of bumps on the spheres)
"""
import math
import sys

import scene_data
from scene_data import DATA, write, f32, u16, argb, dot, smoothstep


class Lcg(scene_data.Lcg):
    def uniform(self):
        return (self.next() & 0xFFFF) / 65536.0

WIDTH, HEIGHT = 320, 240          # the G-buffer and light-buffer size of every deferred scene


def clamp8(v):
    return max(0, min(255, int(math.floor(v + 0.5))))


# ---------------------------------------------------------------- small vector algebra
def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return scale(a, 1.0 / n)


def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def mat_inverse(m):
    """Gauss-Jordan with partial pivoting (4x4, in double)."""
    a = [list(row) + [1.0 if i == j else 0.0 for j in range(4)] for i, row in enumerate(m)]
    for c in range(4):
        p = max(range(c, 4), key=lambda r: abs(a[r][c]))
        a[c], a[p] = a[p], a[c]
        inv = 1.0 / a[c][c]
        a[c] = [x * inv for x in a[c]]
        for r in range(4):
            if r != c and a[r][c] != 0.0:
                f = a[r][c]
                a[r] = [x - f * y for x, y in zip(a[r], a[c])]
    return [row[4:] for row in a]


def yaw(angle_deg):
    """Rotation about +y by angle (left-handed: +x turns towards -z... as D3DXMatrixRotationY)."""
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    return lambda p: (c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2])


# ---------------------------------------------------------------- camera
EYE = (0.0, 4.6, -7.2)
AT = (0.2, 0.4, 1.6)
FOV_Y = math.radians(46.0)
Z_NEAR, Z_FAR = 0.5, 30.0


def view_projection():
    """Column-vector matrix (clip = M p): rows go to c0..c3 for `m4x4 oPos, v0, c0`.
    D3DXMatrixLookAtLH * D3DXMatrixPerspectiveFovLH, transposed."""
    z = normalize(sub(AT, EYE))
    x = normalize(cross((0.0, 1.0, 0.0), z))
    y = cross(z, x)
    view = [list(x) + [-dot(x, EYE)], list(y) + [-dot(y, EYE)], list(z) + [-dot(z, EYE)], [0.0, 0.0, 0.0, 1.0]]
    ys = 1.0 / math.tan(FOV_Y / 2)
    xs = ys * HEIGHT / WIDTH
    q = Z_FAR / (Z_FAR - Z_NEAR)
    proj = [[xs, 0, 0, 0], [0, ys, 0, 0], [0, 0, q, -Z_NEAR * q], [0, 0, 1, 0]]
    return mat_mul(proj, view)


# ---------------------------------------------------------------- scene meshes
class Mesh:
    def __init__(self):
        self.vertices = []   # (p, n, t, uv)
        self.indices = []

    def vertex(self, p, n, t, uv):
        self.vertices.append((p, n, t, uv))
        return len(self.vertices) - 1

    def check(self):
        """Every triangle clockwise from outside: cross(b - a, c - a) along the normals."""
        for i in range(0, len(self.indices), 3):
            a, b, c = (self.vertices[k] for k in self.indices[i:i + 3])
            face = cross(sub(b[0], a[0]), sub(c[0], a[0]))
            if length(face) > 1e-12:
                assert dot(face, add(add(a[1], b[1]), c[1])) > 0, "triangle %d winds inwards" % (i // 3)


def quad(mesh, corner, du, dv, uv_scale, normal=None):
    """A rectangle corner + s du + t dv; u along du, v along dv; dv must be along
    cross(normal, tangent), so the normal is cross(du, dv)."""
    n = normalize(cross(du, dv)) if normal is None else normal
    t = normalize(du)
    assert dot(cross(n, t), normalize(dv)) > 0.999
    lu, lv = length(du) * uv_scale, length(dv) * uv_scale
    k = [mesh.vertex(add(add(corner, scale(du, s)), scale(dv, r)), n, t, (s * lu, r * lv))
         for (s, r) in ((0, 0), (1, 0), (1, 1), (0, 1))]
    # cross(b - a, c - a) = cross(du, dv) points along n: clockwise from outside
    tri = [k[0], k[1], k[2], k[0], k[2], k[3]]
    mesh.indices += tri


def box(mesh, centre, size, yaw_deg, uv_scale):
    rot = yaw(yaw_deg)
    hx, hy, hz = (s / 2 for s in size)
    # each face: outward normal, a tangent (u direction) and the v direction cross(n, t)
    faces = [((0, 0, -1), (1, 0, 0)), ((0, 0, 1), (-1, 0, 0)), ((1, 0, 0), (0, 0, 1)),
             ((-1, 0, 0), (0, 0, -1)), ((0, 1, 0), (1, 0, 0)), ((0, -1, 0), (1, 0, 0))]
    half = (hx, hy, hz)
    for n, t in faces:
        v = cross(n, t)
        # corner = centre + n*h - t*h - v*h (in box space), du = 2 t h, dv = 2 v h
        ext = lambda d: tuple(d[i] * half[i] for i in range(3))
        corner = sub(sub(ext(n), ext(t)), ext(v))
        du, dv = scale(ext(t), 2), scale(ext(v), 2)
        quad(mesh, add(centre, rot(corner)), rot(du), rot(dv), uv_scale, normal=rot(n))


def sphere(mesh, centre, radius, slices, stacks, u_repeat, v_repeat):
    """Latitude/longitude sphere; u around (phi), v from the north pole down, tangent dP/du.
    v must run along cross(n, t): checked below."""
    base = len(mesh.vertices)
    for j in range(stacks + 1):
        theta = math.pi * j / stacks
        for i in range(slices + 1):
            phi = 2 * math.pi * i / slices
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            # u grows with phi; then cross(n, t) points down the sphere (along +theta)
            t = (-math.sin(phi), 0.0, math.cos(phi))
            p = add(centre, scale(n, radius))
            mesh.vertex(p, n, t, (u_repeat * i / slices, v_repeat * j / stacks))
            if 0 < j < stacks:
                dtheta = (math.cos(theta) * math.cos(phi), -math.sin(theta), math.cos(theta) * math.sin(phi))
                assert dot(cross(n, t), dtheta) > 0.999
    w = slices + 1
    for j in range(stacks):
        for i in range(slices):
            a, b, c, d = base + j * w + i, base + j * w + i + 1, base + (j + 1) * w + i + 1, base + (j + 1) * w + i
            mesh.indices += [a, b, c, a, c, d]


def tube(mesh, a, b, radius, segments):
    """An open cylinder from a to b (the visible neon tube)."""
    axis = normalize(sub(b, a))
    side = normalize(cross(axis, (0.0, 0.0, 1.0) if abs(axis[2]) < 0.9 else (1.0, 0.0, 0.0)))
    other = cross(axis, side)
    base = len(mesh.vertices)
    for end in (a, b):
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            n = add(scale(side, math.cos(phi)), scale(other, math.sin(phi)))
            t = axis
            mesh.vertex(add(end, scale(n, radius)), n, t, (0.25, 0.25))  # a flat spot of the map
    w = segments + 1
    for i in range(segments):
        q = [base + i, base + i + 1, base + w + i + 1, base + w + i]
        mesh.indices += [q[0], q[1], q[2], q[0], q[2], q[3]]
    # keep it clockwise from outside whichever way side/other turned out
    for k in range(len(mesh.indices) - 6 * segments, len(mesh.indices), 3):
        i0, i1, i2 = mesh.indices[k:k + 3]
        p0, p1, p2 = (mesh.vertices[x][0] for x in (i0, i1, i2))
        nsum = add(add(mesh.vertices[i0][1], mesh.vertices[i1][1]), mesh.vertices[i2][1])
        if dot(cross(sub(p1, p0), sub(p2, p0)), nsum) < 0:
            mesh.indices[k + 1], mesh.indices[k + 2] = i2, i1


NEON_A = (-1.2, 1.35, 0.1)       # the neon segment's end points (the tube and the light): a
NEON_B = (1.6, 1.35, 0.7)        # horizontal tube hanging between the objects

OBJECTS = [
    # name, builder
    ("floor", lambda m: quad(m, (-9.0, 0.0, 13.0), (18.0, 0.0, 0.0), (0.0, 0.0, -19.0), 0.5)),
    ("box_a", lambda m: box(m, (-2.5, 0.8, 1.1), (1.6, 1.6, 1.6), 32.0, 0.5)),
    ("box_b", lambda m: box(m, (2.7, 1.3, 2.9), (1.2, 2.6, 1.2), -24.0, 0.5)),
    ("box_c", lambda m: box(m, (2.3, 0.45, -1.0), (0.9, 0.9, 0.9), 14.0, 0.5)),
    ("sphere_a", lambda m: sphere(m, (-0.5, 1.1, 2.7), 1.1, 32, 16, 8, 4)),
    ("sphere_b", lambda m: sphere(m, (-1.1, 0.55, -1.4), 0.55, 24, 12, 6, 3)),
    ("tube", lambda m: tube(m, NEON_A, NEON_B, 0.06, 12)),
]


def scene_mesh():
    mesh = Mesh()
    ranges = []
    for name, build in OBJECTS:
        v0, i0 = len(mesh.vertices), len(mesh.indices)
        build(mesh)
        ranges.append((name, v0, len(mesh.vertices) - v0, i0, (len(mesh.indices) - i0) // 3))
    mesh.check()
    vb = b"".join(f32(*p, *n, *t, *uv) for (p, n, t, uv) in mesh.vertices)
    return vb, u16(mesh.indices), ranges


# ---------------------------------------------------------------- light volumes
def plane_distance(p0, p1, p2, centre=(0.0, 0.0, 0.0)):
    n = normalize(cross(sub(p1, p0), sub(p2, p0)))
    return dot(n, sub(p0, centre))


def orient_outwards(points, tris, centre_of):
    out = []
    for (a, b, c) in tris:
        face = cross(sub(points[b], points[a]), sub(points[c], points[a]))
        centroid = scale(add(add(points[a], points[b]), points[c]), 1 / 3)
        out.append((a, b, c) if dot(face, sub(centroid, centre_of(centroid))) > 0 else (a, c, b))
    return out


def icosphere():
    t = (1 + math.sqrt(5)) / 2
    pts = [normalize(p) for p in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                                  (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    mid = {}

    def midpoint(a, b):
        key = (min(a, b), max(a, b))
        if key not in mid:
            pts.append(normalize(scale(add(pts[a], pts[b]), 0.5)))
            mid[key] = len(pts) - 1
        return mid[key]

    sub_faces = []
    for a, b, c in faces:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        sub_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    sub_faces = orient_outwards(pts, sub_faces, lambda p: (0.0, 0.0, 0.0))
    k = 1.0 / min(plane_distance(*(pts[i] for i in f)) for f in sub_faces)
    pts = [scale(p, k) for p in pts]
    assert min(plane_distance(*(pts[i] for i in f)) for f in sub_faces) >= 1.0 - 1e-9
    return pts, sub_faces, k


def cone(sides=16):
    r = 1.0 / math.cos(math.pi / sides)      # the polygon circumscribes the unit circle
    pts = [(0.0, 0.0, 0.0), (0.0, -1.0, 0.0)]
    pts += [(r * math.cos(2 * math.pi * i / sides), -1.0, r * math.sin(2 * math.pi * i / sides)) for i in range(sides)]
    tris = []
    for i in range(sides):
        a, b = 2 + i, 2 + (i + 1) % sides
        tris.append((0, a, b))     # side
        tris.append((1, b, a))     # base
    # outward for the sides: away from the axis; for the base: down
    fixed = []
    for (a, b, c) in tris:
        face = cross(sub(pts[b], pts[a]), sub(pts[c], pts[a]))
        centroid = scale(add(add(pts[a], pts[b]), pts[c]), 1 / 3)
        out = (0.0, -1.0, 0.0) if a == 1 else (centroid[0], 0.0, centroid[2])
        fixed.append((a, b, c) if dot(face, out) > 0 else (a, c, b))
    return pts, fixed


def capsule(segments=16, rings=6):
    """Hemispheres of radius 1 centred at y = +-0.5 with `rings` parallels each, a cylinder
    between; every vertex moved out from its hemisphere's centre (the cylinder's from the axis)
    by k, the smallest factor that keeps every face outside the round capsule."""
    pts, centres = [], []
    rows = []
    for j in range(rings + 1):                 # top hemisphere: pole .. equator (y = 0.5)
        th = (math.pi / 2) * j / rings
        rows.append((th, 0.5))
    for j in range(rings + 1):                 # bottom: equator (y = -0.5) .. pole
        th = math.pi / 2 + (math.pi / 2) * j / rings
        rows.append((th, -0.5))
    row_index = []
    for th, cy in rows:
        if th == 0 or abs(th - math.pi) < 1e-12:
            pts.append((0.0, cy + math.cos(th), 0.0))
            centres.append(cy)
            row_index.append([len(pts) - 1] * segments)
        else:
            idx = []
            for i in range(segments):
                phi = 2 * math.pi * i / segments
                pts.append((math.sin(th) * math.cos(phi), cy + math.cos(th), math.sin(th) * math.sin(phi)))
                centres.append(cy)
                idx.append(len(pts) - 1)
            row_index.append(idx)
    tris = []
    for j in range(len(rows) - 1):
        top, bot = row_index[j], row_index[j + 1]
        for i in range(segments):
            a, b, c, d = top[i], top[(i + 1) % segments], bot[(i + 1) % segments], bot[i]
            for tri in ((a, b, c), (a, c, d)):
                if len(set(tri)) == 3:
                    tris.append(tri)

    def axis_point(p):
        return (0.0, max(-0.5, min(0.5, p[1])), 0.0)

    tris = orient_outwards(pts, tris, axis_point)

    def min_distance(points):
        # the distance of each face plane from the nearest point of the axis segment, taken at
        # the face's centroid side (hemisphere faces: their centre; cylinder faces: the axis)
        d = 1e9
        for f in tris:
            p = [points[i] for i in f]
            centroid = scale(add(add(p[0], p[1]), p[2]), 1 / 3)
            d = min(d, plane_distance(*p, centre=axis_point(centroid)))
        return d

    k = 1.0 / min_distance(pts)
    pts = [(p[0] * k, c + (p[1] - c) * k, p[2] * k) for p, c in zip(pts, centres)]
    assert min_distance(pts) >= 1.0 - 1e-9
    return pts, tris, k


def positions_vb(points):
    return b"".join(f32(*p) for p in points)


def indices_ib(tris):
    return u16([i for t in tris for i in t])


# ---------------------------------------------------------------- textures
def tile_height(x, y, size):
    """Height of the 2 x 2 tile pattern at texel (x, y) of a size x size texture (wraps)."""
    tile = size // 2
    lx, ly = x % tile, y % tile
    edge = min(lx, ly, tile - 1 - lx, tile - 1 - ly)     # texels from the tile's border
    h = smoothstep(0.5, 5.0, edge) * 1.0                 # grout groove, bevel up to the tile top
    tx, ty = x // tile % 2, y // tile % 2
    wave = 0.08 * math.sin(2 * math.pi * (lx + 3 * tx) / tile) * math.sin(2 * math.pi * (ly + 5 * ty) / tile)
    return h + wave * smoothstep(4.0, 10.0, edge)


def normal_map(size, height, strength):
    out = b""
    for y in range(size):
        for x in range(size):
            dx = (height(x + 1, y) - height(x - 1, y)) * 0.5 * strength
            dy = (height(x, y + 1) - height(x, y - 1)) * 0.5 * strength
            n = normalize((-dx, -dy, 1.0))
            out += argb(255, *(clamp8((c * 0.5 + 0.5) * 255) for c in n))
    return out


def tiles_albedo(size):
    rng = Lcg(22)
    tile = size // 2
    tints = [(0.86, 0.82, 0.74), (0.78, 0.76, 0.72), (0.80, 0.74, 0.66), (0.84, 0.80, 0.76)]
    out = b""
    for y in range(size):
        for x in range(size):
            lx, ly = x % tile, y % tile
            edge = min(lx, ly, tile - 1 - lx, tile - 1 - ly)
            tint = tints[(x // tile) + 2 * (y // tile)]
            speck = 0.92 + 0.08 * rng.uniform()
            g = smoothstep(0.5, 2.5, edge)
            grout = (0.32, 0.30, 0.28)
            c = [(g * t * speck + (1 - g) * gr) * 255 for t, gr in zip(tint, grout)]
            out += argb(255, *(clamp8(v) for v in c))
    return out


def bump_height(x, y, size):
    cx = cy = (size - 1) / 2.0
    r = math.hypot((x % size) - cx, (y % size) - cy) / (size * 0.38)
    return math.sqrt(max(0.0, 1.0 - r * r)) * 0.35 * size / 8


# ---------------------------------------------------------------- constants for the streams
def fmt(values):
    return " ".join("%.9g" % v for v in values)


def print_constants(ranges, ico_k, capsule_k):
    vp = view_projection()
    inv = mat_inverse(vp)
    print("# view-projection rows (c0..c3):")
    print(fmt([x for row in vp for x in row]))
    print("# inverse view-projection rows:")
    print(fmt([x for row in inv for x in row]))
    print("# eye:", fmt(EYE))
    print("# half-pixel: 0.5 + 0.5/W, 0.5 + 0.5/H =", fmt((0.5 + 0.5 / WIDTH, 0.5 + 0.5 / HEIGHT)),
          " 1/W, 1/H =", fmt((1.0 / WIDTH, 1.0 / HEIGHT)))
    print("# draw ranges (name base_vertex min_index num_vertices start_index primitive_count):")
    for name, v0, nv, i0, np in ranges:
        print("%-9s DrawIndexedPrimitive TRIANGLELIST 0 %d %d %d %d" % (name, v0, nv, i0, np))
    print("# icosphere scale %.6f, capsule scale %.6f" % (ico_k, capsule_k))
    for name, d in [("key", (-0.55, 0.75, -0.35)), ("fill", (0.8, 0.35, -0.2)), ("rim", (0.2, 0.5, 0.85))]:
        print("# directional %s, towards the light:" % name, fmt(normalize(d)))
    # spot lights: apex, target, radius of the base, colour * intensity
    for apex, target, radius in [((-2.6, 4.2, -1.2), (-2.4, 0.0, 1.3), 1.7),
                                 ((1.2, 4.6, 0.2), (-0.4, 0.0, 2.6), 1.6),
                                 ((3.8, 3.6, -2.6), (2.4, 0.0, 0.4), 1.5)]:
        d = sub(target, apex)
        height = length(d) * 1.25
        rj = normalize(scale(d, -1))
        ri = normalize(cross((0.0, 0.0, 1.0), rj))
        rk = cross(ri, rj)
        cos_d = height / math.sqrt(radius * radius + height * height)
        print("# spot apex %s -> %s: Ri*r, Rj*h, Rk*r, apex, D:" % (fmt(apex), fmt(target)))
        print("   ", fmt(scale(ri, radius)), "|", fmt(scale(rj, height)), "|", fmt(scale(rk, radius)), "|",
              fmt(apex), "| D", "%.9g" % cos_d, "| -Rj*h", fmt(scale(rj, -height)), "| 1/h^2",
              "%.9g" % (1 / height ** 2), "| 1/(1-D)", "%.9g" % (1 / (1 - cos_d)))
    a, b = NEON_A, NEON_B
    s = scale(add(a, b), 0.5)
    half = sub(s, a)
    rj = normalize(half)
    ri = normalize(cross(rj, (0.0, 0.0, 1.0)))
    rk = cross(ri, rj)
    print("# neon: A", fmt(a), "B", fmt(b), "S", fmt(s), "H", "%.9g" % length(half),
          "dir", fmt(rj), "len", "%.9g" % length(sub(b, a)), "Ri", fmt(ri), "Rk", fmt(rk))


def main():
    vb, ib, ranges = scene_mesh()
    ico_pts, ico_tris, ico_k = icosphere()
    cone_pts, cone_tris = cone()
    cap_pts, cap_tris, cap_k = capsule()
    if "--constants" in sys.argv:
        print_constants(ranges, ico_k, cap_k)
        print("# sizes: scene vb %d ib %d; icosphere vb %d ib %d; cone vb %d ib %d; capsule vb %d ib %d"
              % (len(vb), len(ib), 12 * len(ico_pts), 6 * len(ico_tris), 12 * len(cone_pts), 6 * len(cone_tris),
                 12 * len(cap_pts), 6 * len(cap_tris)))
        print("# counts: icosphere %d verts %d tris; cone %d %d; capsule %d %d"
              % (len(ico_pts), len(ico_tris), len(cone_pts), len(cone_tris), len(cap_pts), len(cap_tris)))
        return
    files = {
        "deferred_scene.vb": vb,
        "deferred_scene.ib": ib,
        "deferred_icosphere.vb": positions_vb(ico_pts),
        "deferred_icosphere.ib": indices_ib(ico_tris),
        "deferred_cone.vb": positions_vb(cone_pts),
        "deferred_cone.ib": indices_ib(cone_tris),
        "deferred_capsule.vb": positions_vb(cap_pts),
        "deferred_capsule.ib": indices_ib(cap_tris),
        "deferred_tiles_albedo_128.bin": tiles_albedo(128),
        "deferred_tiles_normal_128.bin": normal_map(128, lambda x, y: tile_height(x % 128, y % 128, 128), 2.2),
        "deferred_bumps_normal_64.bin": normal_map(64, lambda x, y: bump_height(x, y, 64), 1.0),
    }
    total = 0
    for name in sorted(files):
        total += write(name, files[name])
    print("wrote %d files, %d bytes, into %s" % (len(files), total, DATA))


if __name__ == "__main__":
    main()
