#!/usr/bin/env python3
"""Instructions executed by `sm2 bench` on one thread, counted by valgrind's callgrind: a count
that does not drift with the machine's load, where timings here drift by tens of percent.

    bench/instructions.py STREAM                       # self instructions per function, top 20
    bench/instructions.py STREAM --top 40
    bench/instructions.py STREAM --lines block_filter_level --files sampler_block.inc
        # one function's instructions per call, by the source line of FILES that inlined them
    bench/instructions.py STREAM --out cg.out --lines merge
        # keeps callgrind's output (with per-instruction counts) in cg.out, read again by a later
        # call with the same --out instead of a new run

Runs `sm2 bench --threads 1 --repeat 1 STREAM` under callgrind (valgrind runs the AVX2 block
instances; it has no AVX-512). The counts include parsing the stream and compiling its shaders.
--lines adds --dump-instr=yes, attributes each instruction of the functions whose name contains
the pattern to the first frame of its inline chain (`addr2line -i`) in one of FILES, and divides
by the calls made to them.
"""
import argparse
import collections
import os
import re
import subprocess
import sys
import tempfile


def run_callgrind(sm2, stream, out, per_instruction):
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"]
    if per_instruction:
        cmd.append("--dump-instr=yes")
    cmd += [sm2, "bench", "--threads", "1", "--repeat", "1", stream]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def per_function(out):
    """Self instructions per function (callgrind_annotate lists them per source file)."""
    text = subprocess.run(["callgrind_annotate", "--threshold=100", "--auto=no", out],
                          check=True, capture_output=True, text=True).stdout
    total, counts = 0, collections.Counter()
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+(.*)$", line)
        if not m:
            continue
        n = int(m.group(1).replace(",", ""))
        where = m.group(2)
        if "PROGRAM TOTALS" in where:
            total = n
            continue
        name = where.split(":", 1)[1] if ":" in where else where
        obj = re.search(r" \[([^\]]*)\]$", name)
        name = re.sub(r" \[[^\]]*\]$", "", name).replace("(anonymous namespace)", "anon")
        name = name.split("(")[0]
        if name.startswith("0x"):
            # An address without a symbol: the JIT's code (no object file) or a stripped
            # library's internals (libLLVM's, compiling that code).
            library = obj.group(1) if obj else "???"
            name = "(JIT-compiled code)" if library == "???" else f"({os.path.basename(library)}, no symbols)"
        counts[name] += n
    return total, counts


def per_instruction(out, pattern):
    """Self instructions per address of the functions whose name contains `pattern`, and the
    calls made to them, from a --dump-instr=yes file (positions: instr line)."""
    names, counts, calls = {}, collections.Counter(), 0
    inside = in_call = called = False
    last = 0
    for line in open(out):
        line = line.rstrip("\n")
        m = re.match(r"^(c?)fn=\((\d+)\)(?: (.*))?$", line)
        if m:
            if m.group(3):
                names[m.group(2)] = m.group(3)
            matches = pattern in names.get(m.group(2), "")
            if m.group(1):
                called = matches
            else:
                inside = matches
            continue
        if line.startswith("calls="):
            in_call = True
            if called:
                calls += int(line.split()[0][len("calls="):])
            continue
        if not line or line[0] not in "0+-*":
            continue
        fields = line.split()
        a = fields[0]
        if a.startswith("0x"):
            addr = int(a, 16)
        elif a.startswith("+"):
            addr = last + int(a[1:], 0)
        elif a.startswith("-"):
            addr = last - int(a[1:], 0)
        else:
            addr = last
        last = addr
        if in_call:  # the line after calls= is the call's inclusive cost
            in_call = False
            continue
        if inside and len(fields) >= 3:
            counts[addr] += int(fields[-1])
    return counts, calls


def by_line(sm2, counts, files):
    addresses = sorted(counts)
    text = subprocess.run(["addr2line", "-a", "-i", "-e", sm2] + [hex(a) for a in addresses],
                          check=True, capture_output=True, text=True).stdout
    chains, current = {}, None
    for line in text.splitlines():
        if line.startswith("0x"):
            current = int(line, 16)
            chains[current] = []
        else:
            chains[current].append(line)
    lines = collections.Counter()
    for a in addresses:
        chain = chains.get(a, [])
        frame = next((f for f in chain if any(name in f for name in files)), chain[0] if chain else "?")
        lines[frame.split("/")[-1].split(" ")[0]] += counts[a]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("stream")
    parser.add_argument("--sm2", default="build/release/tools/sm2")
    parser.add_argument("--top", type=int, default=20)
    parser.add_argument("--lines", metavar="FUNCTION", help="a function name pattern (substring)")
    parser.add_argument("--out", metavar="FILE",
                        help="keep callgrind's output in FILE; an existing FILE is read instead of a new run")
    parser.add_argument("--files", default="sampler_block.inc,unorm8_kernels.inc,output_merger_block.inc,"
                        "interpolation_block.inc,rasterizer_block.inc",
                        help="comma-separated source files whose lines --lines reports")
    args = parser.parse_args()
    for tool in ("valgrind", "callgrind_annotate", "addr2line"):
        if subprocess.run(["which", tool], capture_output=True).returncode != 0:
            sys.exit(f"instructions.py: {tool} not found (apt-get install valgrind binutils)")
    with tempfile.TemporaryDirectory() as tmp:
        out = args.out or os.path.join(tmp, "callgrind.out")
        if not (args.out and os.path.exists(out)):
            run_callgrind(args.sm2, args.stream, out, args.lines is not None or args.out is not None)
        total, counts = per_function(out)
        print(f"{args.stream}: {total:,} instructions (sm2 bench --threads 1 --repeat 1)")
        if args.lines is None:
            for name, n in counts.most_common(args.top):
                print(f"{n:>15,} {100 * n / total:5.1f}%  {name[-110:]}")
            return
        addresses, calls = per_instruction(out, args.lines)
        if calls == 0:
            sys.exit(f"instructions.py: no calls to a function matching '{args.lines}'")
        print(f"functions matching '{args.lines}': {sum(addresses.values()):,} instructions, {calls:,} calls, "
              f"{sum(addresses.values()) / calls:.1f} a call")
        for line, n in by_line(args.sm2, addresses, args.files.split(",")).most_common(args.top):
            print(f"{n / calls:9.1f}  {line}")


if __name__ == "__main__":
    main()
