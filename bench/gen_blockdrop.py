#!/usr/bin/env python3
# Copied unchanged (apart from these header lines) from /work/shared/decks/bench/gen_blockdrop.py,
# the block-drop benchmark generator shared with the project (README there): it writes the same
# model for impactfe (APDL) and CalculiX. Keep it in step with that original.
"""Block-drop benchmark generator: one model, two decks (CalculiX + ANSYS MAPDL).

usage: gen_blockdrop.py NX NY NZ OUTDIR [--dt 1e-5] [--tend 0.03] [--freq 10]
                                       [--alpha 0.0] [--etype C3D8|C3D8I]

Model
  Elastic brick block, NX x NY x NZ hexahedra of 1 in edge, bottom face at z = 0,
  E = 10e6 psi, nu = 0.33, rho = 2.588e-4 lbf*s^2/in^4, gravity 386.4 in/s^2 in -Z,
  starting from rest.  Under every bottom-face node a one-DOF (UZ) gap element to
  its own fixed ground node: clearance 0.05 in, k = 2000 lbf/in, no friction.
  Fixed-step implicit direct integration, dt = 1e-5 s, t = 0 .. 0.03 s.
  Output: UZ of the bottom corner node and the top-centre node every FREQ steps.

Numbering (identical in both decks)
  block node (i,j,k), i=0..NX, j=0..NY, k=0..NZ : 1 + i + (NX+1)*j + (NX+1)*(NY+1)*k
  ground node under bottom node (i,j,0)        : NBLOCK + 1 + i + (NX+1)*j
  hex element (i,j,k)                           : 1 + i + NX*j + NX*NY*k
  gap element under (i,j)                       : NHEX + 1 + i + (NX+1)*j
  Ground nodes are placed at z = -0.05 (the physical ground plane).  Neither gap
  element uses the node distance: the clearance is the *GAP / real-constant
  value 0.05 in both programs.
  Corner monitor = node 1 at (0,0,0); top monitor = node (NX//2, NY//2, NZ)
  (the exact top centre when NX and NY are even, otherwise the nearest node).

Time integration (default alpha = 0, i.e. the same integrator in both decks)
  ccx : *DYNAMIC,DIRECT,ALPHA=0  -> HHT with alpha = 0 = Newmark beta=1/4, gamma=1/2
  APDL: TRNOPT,FULL + TINTP,0    -> Newmark with GAMMA (amplitude decay) = 0,
        i.e. ALPHA = 0.25, DELTA = 0.5 (same trapezoidal rule)
  With --alpha a (a in [-1/3, 0), e.g. the ccx default -0.05) the ccx deck uses
  HHT alpha = a and the APDL deck uses TRNOPT,FULL,,,,,HHT with
  TINTP,,beta,gamma,,,,,,,ALPHAF,ALPHAM = (1-a)^2/4, 1/2-a, -a, 0.
"""
import argparse
import os
import sys

E_MOD = 10.0e6
NU = 0.33
RHO = 2.588e-4
GRAV = 386.4
GAP = 0.05
KGAP = 2000.0
FINF = 1.0e-9          # ccx GAPUNI force at infinite clearance (open-gap "leak")


def build(nx, ny, nz):
    nxy = (nx + 1) * (ny + 1)
    nblock = nxy * (nz + 1)

    def nid(i, j, k):
        return 1 + i + (nx + 1) * j + nxy * k

    nodes = []
    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                nodes.append((nid(i, j, k), float(i), float(j), float(k)))
    ground = []
    gmap = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            g = nblock + 1 + i + (nx + 1) * j
            ground.append((g, float(i), float(j), -GAP))
            gmap[nid(i, j, 0)] = g
    hexes = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                e = 1 + i + nx * j + nx * ny * k
                hexes.append((e, [nid(i, j, k), nid(i + 1, j, k),
                                  nid(i + 1, j + 1, k), nid(i, j + 1, k),
                                  nid(i, j, k + 1), nid(i + 1, j, k + 1),
                                  nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]))
    nhex = nx * ny * nz
    gaps = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            b = nid(i, j, 0)
            gaps.append((nhex + 1 + i + (nx + 1) * j, gmap[b], b))  # (elem, I=ground, J=block)
    corner = nid(0, 0, 0)
    top = nid(nx // 2, ny // 2, nz)
    return dict(nodes=nodes, ground=ground, hexes=hexes, gaps=gaps,
                corner=corner, top=top, nblock=nblock, nhex=nhex)


def write_ccx(path, m, a):
    nx, ny, nz = a.nx, a.ny, a.nz
    L = []
    w = L.append
    w("** BLOCKDROP %dx%dx%d  MONITOR CORNER=%d TOP=%d" % (nx, ny, nz, m["corner"], m["top"]))
    w("** element %s, %d hex + %d GAPUNI; dt=%g tend=%g alpha=%g; output every %d inc"
      % (a.etype, m["nhex"], len(m["gaps"]), a.dt, a.tend, a.alpha, a.freq))
    w("*HEADING")
    w("Block drop %dx%dx%d on GAPUNI gaps" % (nx, ny, nz))
    w("*NODE, NSET=NBLOCK")
    for n, x, y, z in m["nodes"]:
        w("%d, %.6f, %.6f, %.6f" % (n, x, y, z))
    w("*NODE, NSET=NGROUND")
    for n, x, y, z in m["ground"]:
        w("%d, %.6f, %.6f, %.6f" % (n, x, y, z))
    w("*ELEMENT, TYPE=%s, ELSET=EBLOCK" % a.etype)
    for e, c in m["hexes"]:
        w("%d, %s" % (e, ", ".join(str(v) for v in c)))
    w("*ELEMENT, TYPE=GAPUNI, ELSET=EGAP")
    for e, gi, gj in m["gaps"]:
        w("%d, %d, %d" % (e, gi, gj))
    w("*NSET, NSET=NMON")
    w("%d, %d" % (m["corner"], m["top"]))
    w("*MATERIAL, NAME=BLOCK")
    w("*ELASTIC")
    w("%.6e, %.4f" % (E_MOD, NU))
    w("*DENSITY")
    w("%.6e" % RHO)
    w("*SOLID SECTION, ELSET=EBLOCK, MATERIAL=BLOCK")
    # ccx 2.20 gaps.f: fields 1-4 = clearance, n_x, n_y, n_z; field 5 unused;
    # field 6 = stiffness k; field 7 = f_inf.  (A blank field 6 is read as k = 0,
    # which silently disables the gap.)
    # gap closes when  d + n.(u_2 - u_1) <= 0 with node 1 = ground, node 2 = block
    w("*GAP, ELSET=EGAP")
    w("%.6g, 0., 0., 1., , %.6g, %.3g" % (GAP, KGAP, FINF))
    w("*BOUNDARY")
    w("NGROUND, 1, 3, 0.")
    w("*AMPLITUDE, NAME=CONST")
    w("0., 1., 1.e6, 1.")
    w("*STEP, INC=%d" % (int(round(a.tend / a.dt)) + 100))
    w("*DYNAMIC, DIRECT, ALPHA=%g" % a.alpha)
    w("%.6g, %.6g" % (a.dt, a.tend))
    w("*DLOAD, AMPLITUDE=CONST")
    w("EBLOCK, GRAV, %.6g, 0., 0., -1." % GRAV)
    w("*NODE PRINT, NSET=NMON, FREQUENCY=%d" % a.freq)
    w("U")
    w("*END STEP")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def write_apdl(path, m, a):
    nx, ny, nz = a.nx, a.ny, a.nz
    L = []
    w = L.append
    w("! MONITOR CORNER=%d TOP=%d" % (m["corner"], m["top"]))
    w("! Block drop %dx%dx%d: %d SOLID185 + %d COMBIN40 (KEYOPT(3)=3, UZ gap)"
      % (nx, ny, nz, m["nhex"], len(m["gaps"])))
    w("! units in, lbf, s.  dt=%g tend=%g, output every %d substeps" % (a.dt, a.tend, a.freq))
    w("/PREP7")
    # SOLID185 KEYOPT(2): 0 = B-bar (default); 3 = simplified enhanced strain
    # (incompatible-mode-like, closest to ccx C3D8I).  ccx C3D8 is plain full
    # integration; the block is ~1000x stiffer than the gap bed, so the monitored
    # UZ is insensitive to this choice.
    w("ET,1,SOLID185")
    if a.etype.upper() == "C3D8I":
        w("KEYOPT,1,2,3")
    w("ET,2,COMBIN40")
    w("KEYOPT,2,1,0        ! standard gap (no lock-up)")
    w("KEYOPT,2,3,3        ! UZ only")
    w("MP,EX,1,%.6e" % E_MOD)
    w("MP,PRXY,1,%.4f" % NU)
    w("MP,DENS,1,%.6e" % RHO)
    w("R,2,%.6g,0,0,%.6g    ! K1, C, M, GAP (FSLIDE=0: no slider, K2=0)" % (KGAP, GAP))
    w("! block nodes")
    for n, x, y, z in m["nodes"]:
        w("N,%d,%.6f,%.6f,%.6f" % (n, x, y, z))
    w("! ground nodes")
    for n, x, y, z in m["ground"]:
        w("N,%d,%.6f,%.6f,%.6f" % (n, x, y, z))
    w("TYPE,1")
    w("MAT,1")
    w("REAL,1")
    for e, c in m["hexes"]:
        w("EN,%d,%s" % (e, ",".join(str(v) for v in c)))
    w("TYPE,2")
    w("REAL,2")
    w("! COMBIN40: I = ground, J = block bottom; closed when UZ(J)-UZ(I)+GAP <= 0")
    for e, gi, gj in m["gaps"]:
        w("EN,%d,%d,%d" % (e, gi, gj))
    g0 = m["ground"][0][0]
    g1 = m["ground"][-1][0]
    w("NSEL,S,NODE,,%d,%d" % (g0, g1))
    w("D,ALL,ALL,0")
    w("NSEL,ALL")
    w("FINISH")
    w("/SOLU")
    w("ANTYPE,TRANS")
    if a.alpha == 0.0:
        w("TRNOPT,FULL")
        w("TINTP,0             ! Newmark beta=0.25 gamma=0.5 (= ccx ALPHA=0)")
    else:
        al = -a.alpha
        w("TRNOPT,FULL,,,,,HHT")
        w("TINTP,,%.8g,%.8g,,,,,,,%.8g,0   ! HHT = ccx ALPHA=%g"
          % ((1 + al) ** 2 / 4.0, 0.5 + al, al, a.alpha))
    w("NLGEOM,OFF")
    w("AUTOTS,OFF")
    w("ACEL,0,0,%.6g        ! +Z acceleration input = gravity acting in -Z" % GRAV)
    w("DELTIM,%.6g,%.6g,%.6g" % (a.dt, a.dt, a.dt))
    w("TIME,%.6g" % a.tend)
    w("KBC,1")
    w("OUTRES,ALL,NONE")
    w("OUTRES,NSOL,%d" % a.freq)
    w("SOLVE")
    w("FINISH")
    w("! optional: monitored-node UZ history as a text table (time, corner, top)")
    w("/POST26")
    w("NSOL,2,%d,U,Z,CORNER_UZ" % m["corner"])
    w("NSOL,3,%d,U,Z,TOP_UZ" % m["top"])
    w("/OUTPUT,blockdrop_apdl_hist,txt")
    w("PRVAR,2,3")
    w("/OUTPUT")
    w("FINISH")
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("nx", type=int)
    p.add_argument("ny", type=int)
    p.add_argument("nz", type=int)
    p.add_argument("outdir")
    p.add_argument("--dt", type=float, default=1e-5)
    p.add_argument("--tend", type=float, default=0.03)
    p.add_argument("--freq", type=int, default=10)
    p.add_argument("--alpha", type=float, default=0.0,
                   help="HHT alpha in [-1/3,0]; 0 = trapezoidal Newmark (default)")
    p.add_argument("--etype", default="C3D8", choices=["C3D8", "C3D8I"])
    a = p.parse_args(argv)
    if min(a.nx, a.ny, a.nz) < 1:
        sys.exit("NX NY NZ must be >= 1")
    if not (-1.0 / 3.0 <= a.alpha <= 0.0):
        sys.exit("alpha must be in [-1/3, 0]")
    os.makedirs(a.outdir, exist_ok=True)
    m = build(a.nx, a.ny, a.nz)
    write_ccx(os.path.join(a.outdir, "blockdrop.inp"), m, a)
    write_apdl(os.path.join(a.outdir, "blockdrop_apdl.inp"), m, a)
    nb = (a.nx + 1) * (a.ny + 1)
    print("nodes=%d ground=%d hex=%d gaps=%d block_dofs=%d corner=%d top=%d"
          % (m["nblock"], nb, m["nhex"], nb, 3 * m["nblock"], m["corner"], m["top"]))


if __name__ == "__main__":
    main()
