#!/usr/bin/env python3
"""Read time and peak memory of a large CDB archive (docs/benchmarks.md, "Reading a CDB").

Writes an n x n x n node block of SOLID185 bricks as MAPDL's CDWRITE lays it out (NBLOCK
(3i9,6e21.13e3), EBLOCK solid format (19i10), a CMBLOCK of the bottom face), then runs
`impactfe run` on a deck that only reads it (CDREAD,DB) and lists the counts, --repeat times,
under /usr/bin/time. Reports the file size, the median and minimum wall time, the CPU time,
the peak resident memory, and the same figures for an empty deck (start-up), so that
`read = wall - start-up` is the archive's own cost.

    python3 bench/cdb_read.py                    # 100^3 = 10^6 nodes, 970,299 bricks
    python3 bench/cdb_read.py --nodes-per-edge 50 --repeat 1
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TIME_BIN = "/usr/bin/time"


def write_archive(path, n, h=1.0):
    """An n^3-node block of (n-1)^3 SOLID185 bricks with spacing h, and component BOTTOM."""
    def node_id(i, j, k):
        return 1 + i + n * (j + n * k)

    with open(path, "w") as f:
        f.write("/COM,ANSYS RELEASE 2022 R2     (bench/cdb_read.py)\n/PREP7\n")
        f.write("ET,       1,185\n")
        f.write("MPTEMP,R5.0, 1, 1,  0.00000000    ,\n")
        f.write("MPDATA,R5.0, 1,EX  ,       1, 1,  2.00000000E+11,\n")
        f.write("MPDATA,R5.0, 1,PRXY,       1, 1, 0.300000000    ,\n")
        f.write("MPDATA,R5.0, 1,DENS,       1, 1,  7850.00000    ,\n")
        nn = n ** 3
        f.write("NBLOCK,6,SOLID,%10d,%10d\n(3i9,6e21.13e3)\n" % (nn, nn))
        lines = []
        for k in range(n):
            for j in range(n):
                for i in range(n):
                    lines.append("%9d%9d%9d%21.13E%21.13E%21.13E\n"
                                 % (node_id(i, j, k), 0, 0, i * h, j * h, k * h))
            f.write("".join(lines))
            lines = []
        f.write("N,R5.3,LOC,       -1,\n")
        ne = (n - 1) ** 3
        f.write("EBLOCK,19,SOLID,%10d,%10d\n(19i10)\n" % (ne, ne))
        e = 0
        for k in range(n - 1):
            for j in range(n - 1):
                for i in range(n - 1):
                    e += 1
                    c = [node_id(i, j, k), node_id(i + 1, j, k), node_id(i + 1, j + 1, k),
                         node_id(i, j + 1, k), node_id(i, j, k + 1), node_id(i + 1, j, k + 1),
                         node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1)]
                    fields = [1, 1, 1, 1, 0, 0, 0, 0, 8, 0, e] + c
                    lines.append("".join("%10d" % v for v in fields) + "\n")
            f.write("".join(lines))
            lines = []
        f.write("        -1\n")
        # The bottom face's nodes as ranges (a negative entry closes a range), 8 per record.
        f.write("CMBLOCK,BOTTOM  ,NODE,%8d\n(8i10)\n" % 2)
        f.write("%10d%10d\n" % (1, -(n * n)))
        f.write("/GO\nFINISH\n")
    return nn, ne


def timed(cmd, cwd):
    """(wall s, cpu s, peak RSS kB) of one run; raises on failure."""
    stats = os.path.join(cwd, ".time_stats")
    t0 = time.perf_counter()
    proc = subprocess.run([TIME_BIN, "-o", stats, "-f", "%M %U %S"] + cmd, cwd=cwd,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError("%s failed (exit %d):\n%s%s" % (" ".join(cmd), proc.returncode,
                                                           proc.stdout[-3000:], proc.stderr[-3000:]))
    with open(stats) as f:
        fields = f.read().split()
    return wall, float(fields[-2]) + float(fields[-1]), int(fields[-3]), proc.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default=os.path.join(HERE, "..", "build", "impactfe"))
    ap.add_argument("--nodes-per-edge", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    exe = os.path.abspath(args.binary)
    n = args.nodes_per_edge
    with tempfile.TemporaryDirectory(prefix="impactfe_cdb_") as work:
        archive = os.path.join(work, "block.cdb")
        t0 = time.perf_counter()
        nn, ne = write_archive(archive, n)
        t_write = time.perf_counter() - t0
        size_mb = os.path.getsize(archive) / 1e6
        with open(os.path.join(work, "read.inp"), "w") as f:
            f.write("/PREP7\nCDREAD,DB,block,cdb\n*GET,NN,NODE,0,COUNT\n*GET,NE,ELEM,0,COUNT\n"
                    "*GET,NB,NODE,0,COUNT\nCMSEL,S,BOTTOM\n*GET,NB,NODE,0,COUNT\nALLSEL\n"
                    "*STATUS,NN\n*STATUS,NE\n*STATUS,NB\nFINISH\n")
        with open(os.path.join(work, "empty.inp"), "w") as f:
            f.write("/PREP7\nFINISH\n")
        rows = {}
        for name in ("empty", "read"):
            runs = []
            for _ in range(args.repeat):
                out_dir = os.path.join(work, "out")
                runs.append(timed([exe, "run", name + ".inp", "-o", out_dir], work))
            rows[name] = runs
        out = rows["read"][-1][3]
        for label, expect in (("NN", nn), ("NE", ne), ("NB", n * n)):
            if not any(label in line and str(expect) in line.replace(".000", "")
                       for line in out.splitlines()):
                print("warning: %s = %d not found in the run's *STATUS output" % (label, expect),
                      file=sys.stderr)
    walls = [r[0] for r in rows["read"]]
    startup = statistics.median(r[0] for r in rows["empty"])
    print("| nodes | bricks | archive MB | write (Python) s | wall median s | wall min s | "
          "CPU s | start-up s | read s | peak RSS MB | nodes/s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    read = statistics.median(walls) - startup
    print("| %d | %d | %.0f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.2g |"
          % (nn, ne, size_mb, t_write, statistics.median(walls), min(walls),
             statistics.median(r[1] for r in rows["read"]), startup, read,
             max(r[2] for r in rows["read"]) / 1024, nn / read if read > 0 else float("nan")))


if __name__ == "__main__":
    main()
