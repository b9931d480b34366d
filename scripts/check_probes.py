#!/usr/bin/env python3
"""Checks the probe pixels of samples/scenes/probes.txt against replayed frames.

Each probe line is
    NN_name.sm2cs frame_0000.png x y RRGGBBAA tolerance  # why
and passes when every channel of pixel (x, y) of out/scenes/NN_name/frame_0000.png is within
`tolerance` (0..255) of the expected value. Blank lines and lines starting with '#' are skipped.

    scripts/check_probes.py [--probes samples/scenes/probes.txt] [--out out/scenes]

Exit status 0 when every probe passes, 1 when any fails or an image is missing, 2 on bad usage
or a malformed probe line. Standard library only: the PNG decoder below handles the 8-bit
grey, grey+alpha, RGB, RGBA and palette images of any filter type (no interlacing).
"""
import argparse
import os
import struct
import sys
import zlib


class PngError(Exception):
    pass


def read_png(path):
    """Returns (width, height, rows) with rows[y] a list of (r, g, b, a) tuples."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise PngError("%s: not a PNG file" % path)
    pos, idat, palette, trns = 8, [], None, None
    width = height = depth = colour = interlace = None
    while pos < len(data):
        if pos + 8 > len(data):
            raise PngError("%s: truncated chunk header" % path)
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"PLTE":
            palette = [tuple(body[i:i + 3]) for i in range(0, len(body), 3)]
        elif kind == b"tRNS":
            trns = body
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    if width is None:
        raise PngError("%s: no IHDR" % path)
    if depth != 8 or interlace != 0:
        raise PngError("%s: only 8-bit, non-interlaced PNGs are supported (depth %d, interlace %d)"
                       % (path, depth, interlace))
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}.get(colour)
    if channels is None:
        raise PngError("%s: unknown colour type %d" % (path, colour))
    raw = zlib.decompress(b"".join(idat))
    stride = width * channels
    bpp = channels
    rows, prev, at = [], bytearray(stride), 0
    for _ in range(height):
        ftype = raw[at]
        line = bytearray(raw[at + 1:at + 1 + stride])
        at += 1 + stride
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + ((a + b) >> 1)) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
            elif ftype != 0:
                raise PngError("%s: bad filter type %d" % (path, ftype))
        prev = line
        pixels = []
        for x in range(width):
            px = line[x * channels:(x + 1) * channels]
            if colour == 0:
                pixels.append((px[0], px[0], px[0], 255))
            elif colour == 4:
                pixels.append((px[0], px[0], px[0], px[1]))
            elif colour == 2:
                pixels.append((px[0], px[1], px[2], 255))
            elif colour == 6:
                pixels.append(tuple(px))
            else:
                r, g, b = palette[px[0]]
                alpha = trns[px[0]] if trns is not None and px[0] < len(trns) else 255
                pixels.append((r, g, b, alpha))
        rows.append(pixels)
    return width, height, rows


def parse_probes(path):
    probes = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            text = line.split("#", 1)[0].strip()
            if not text:
                continue
            why = line.split("#", 1)[1].strip() if "#" in line else ""
            parts = text.split()
            if len(parts) != 6:
                raise ValueError("%s:%d: expected 'stream frame x y RRGGBBAA tolerance'" % (path, number))
            stream, frame, x, y, colour, tol = parts
            if len(colour) != 8:
                raise ValueError("%s:%d: colour must be RRGGBBAA" % (path, number))
            expected = tuple(int(colour[i:i + 2], 16) for i in (0, 2, 4, 6))
            probes.append((number, stream, frame, int(x), int(y), expected, int(tol), why))
    return probes


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--probes", default=os.path.join(root, "samples", "scenes", "probes.txt"))
    parser.add_argument("--out", default=os.path.join(root, "out", "scenes"),
                        help="folder with one subfolder of frames per stream (scripts/replay_scenes.sh)")
    parser.add_argument("-v", "--verbose", action="store_true", help="print passing probes too")
    args = parser.parse_args()
    try:
        probes = parse_probes(args.probes)
    except (OSError, ValueError) as e:
        print("check_probes: %s" % e, file=sys.stderr)
        return 2
    images, failures, missing = {}, 0, 0
    for number, stream, frame, x, y, expected, tol, why in probes:
        name = stream[:-len(".sm2cs")] if stream.endswith(".sm2cs") else stream
        path = os.path.join(args.out, name, frame)
        if path not in images:
            try:
                images[path] = read_png(path)
            except (OSError, PngError, zlib.error) as e:
                images[path] = e
        image = images[path]
        where = "%s %s (%d, %d)" % (stream, frame, x, y)
        if isinstance(image, Exception):
            print("MISSING line %d: %s: %s" % (number, where, image))
            missing += 1
            continue
        width, height, rows = image
        if not (0 <= x < width and 0 <= y < height):
            print("FAIL line %d: %s outside the %dx%d image" % (number, where, width, height))
            failures += 1
            continue
        got = rows[y][x]
        ok = all(abs(g - e) <= tol for g, e in zip(got, expected))
        if not ok or args.verbose:
            print("%s line %d: %s got %02X%02X%02X%02X expected %02X%02X%02X%02X +-%d  # %s"
                  % ("ok  " if ok else "FAIL", number, where, *got, *expected, tol, why))
        if not ok:
            failures += 1
    total = len(probes)
    print("check_probes: %d probes, %d passed, %d failed, %d missing images"
          % (total, total - failures - missing, failures, missing))
    return 0 if failures == 0 and missing == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
