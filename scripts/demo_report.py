#!/usr/bin/env python3
"""The end of scripts/demo.sh: a one-screen summary and OUT/index.html, a contact sheet of frames.

    scripts/demo_report.py --out OUT --runs OUT/scenes/runs.tsv [--shaders N] [--shader-failures N]

runs.tsv has one line per replayed scene: name, ok|FAIL, seconds (the replay's own time). The
probes of samples/scenes/probes.txt for those scenes are checked against OUT/scenes/<name>/.
The summary lists every scene (frames, time, probes passed), then the totals and where the
frames and the contact sheet are. index.html links every frame by a relative path and uses no
external resource (inline style, no scripts), so the OUT folder can be moved or archived.
Exit status 0 when every scene replayed, every shader passed and every probe passed; 1 otherwise.
Standard library only.
"""
import argparse
import glob
import html
import os
import sys
import urllib.parse
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_probes  # noqa: E402  (scripts/check_probes.py: the probe list and a PNG reader)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

STYLE = """body{font-family:sans-serif;margin:1em;background:#202020;color:#ddd}
h1{font-size:1.4em}h2{font-size:1.1em;margin:1.2em 0 .3em}a{color:#9cf}
.frames{display:flex;flex-wrap:wrap;gap:8px}figure{margin:0}
img{width:256px;height:auto;image-rendering:pixelated;border:1px solid #444;background:#000}
figcaption{font-size:.8em}.fail{color:#f66}.ok{color:#6c6}"""


def read_runs(path):
    runs = []
    with open(path) as f:
        for line in f:
            parts = line.rstrip("\n").split("\t")
            if len(parts) == 3:
                runs.append((parts[0], parts[1] == "ok", float(parts[2] or 0)))
    return runs


def check_scene_probes(out, name, probes):
    """(passed, total, failure lines) of the probes of scene `name`."""
    passed, failures, images = 0, [], {}
    mine = [p for p in probes if p[1] == name + ".sm2cs"]
    for number, _, frame, x, y, expected, tol, why in mine:
        path = os.path.join(out, "scenes", name, frame)
        if path not in images:
            try:
                images[path] = check_probes.read_png(path)
            except (OSError, check_probes.PngError, zlib.error) as e:
                images[path] = e
        image = images[path]
        if isinstance(image, Exception):
            failures.append("probes.txt:%d: %s %s: missing (%s)" % (number, name, frame, image))
            continue
        width, height, rows = image
        if 0 <= x < width and 0 <= y < height and all(
                abs(g - e) <= tol for g, e in zip(rows[y][x], expected)):
            passed += 1
        else:
            got = "%02X%02X%02X%02X" % rows[y][x] if 0 <= x < width and 0 <= y < height else "outside"
            failures.append("probes.txt:%d: %s %s (%d, %d) got %s expected %02X%02X%02X%02X  # %s"
                            % (number, name, frame, x, y, got, *expected, why))
    return passed, len(mine), failures


def write_index(out, scenes, totals):
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             "<title>sm2emu demo: %d scenes, %d frames</title>" % (totals["scenes"], totals["frames"]),
             "<style>%s</style></head><body>" % STYLE,
             "<h1>sm2emu demo: %d scenes, %d frames</h1>" % (totals["scenes"], totals["frames"]),
             "<p>probes %d/%d passed; %.3f s replaying</p>" % (totals["probes_passed"], totals["probes"], totals["seconds"])]
    for s in scenes:
        state = '<span class="ok">ok</span>' if s["ok"] else '<span class="fail">FAILED</span>'
        parts.append('<section id="%s"><h2>%s</h2>' % (html.escape(s["name"]), html.escape(s["name"])))
        parts.append("<p>%s, %d frame%s, %.3f s, probes %d/%d</p>" % (
            state, len(s["frames"]), "" if len(s["frames"]) == 1 else "s", s["seconds"], s["probes_passed"], s["probes"]))
        parts.append('<div class="frames">')
        for frame in s["frames"]:
            href = urllib.parse.quote("scenes/%s/%s" % (s["name"], frame))
            parts.append('<figure><a href="%s"><img src="%s" alt="%s %s" loading="lazy"></a>'
                         "<figcaption>%s</figcaption></figure>"
                         % (href, href, html.escape(s["name"]), html.escape(frame), html.escape(frame)))
        parts.append("</div></section>")
    parts.append("</body></html>")
    path = os.path.join(out, "index.html")
    with open(path, "w") as f:
        f.write("\n".join(parts) + "\n")
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--runs", required=True)
    parser.add_argument("--probes", default=os.path.join(ROOT, "samples", "scenes", "probes.txt"))
    parser.add_argument("--shaders", type=int, default=0)
    parser.add_argument("--shader-failures", type=int, default=0)
    args = parser.parse_args()
    probes = check_probes.parse_probes(args.probes)

    scenes, failures = [], []
    for name, ok, seconds in read_runs(args.runs):
        frames = sorted(os.path.basename(p) for p in glob.glob(os.path.join(args.out, "scenes", name, "frame_*.png")))
        passed, total, probe_failures = check_scene_probes(args.out, name, probes)
        failures += probe_failures
        scenes.append({"name": name, "ok": ok, "seconds": seconds, "frames": frames,
                       "probes_passed": passed, "probes": total})
    totals = {"scenes": len(scenes), "frames": sum(len(s["frames"]) for s in scenes),
              "seconds": sum(s["seconds"] for s in scenes),
              "probes": sum(s["probes"] for s in scenes),
              "probes_passed": sum(s["probes_passed"] for s in scenes)}
    index = write_index(args.out, scenes, totals)

    width = max([len(s["name"]) for s in scenes] + [5])
    print()
    print("%-*s  %6s  %9s  %7s" % (width, "scene", "frames", "time (s)", "probes"))
    for s in scenes:
        print("%-*s  %6d  %9.3f  %7s%s" % (width, s["name"], len(s["frames"]), s["seconds"],
                                           "%d/%d" % (s["probes_passed"], s["probes"]) if s["probes"] else "-",
                                           "" if s["ok"] else "  replay FAILED"))
    for line in failures:
        print("FAIL  " + line)
    failed_scenes = [s["name"] for s in scenes if not s["ok"]]
    print("demo: %d scenes (%d failed), %d frames, %.3f s replaying; probes %d/%d passed; "
          "%d shaders validated, assembled and disassembled%s"
          % (totals["scenes"], len(failed_scenes), totals["frames"], totals["seconds"], totals["probes_passed"],
             totals["probes"], args.shaders,
             " (%d failed)" % args.shader_failures if args.shader_failures else ""))
    print("demo: frames in %s/<scene>/frame_NNNN.png, bytecode in %s, contact sheet %s"
          % (os.path.join(args.out, "scenes"), os.path.join(args.out, "shaders") + "/", index))
    ok = not failed_scenes and not failures and args.shader_failures == 0
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
