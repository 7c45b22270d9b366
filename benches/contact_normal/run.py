#!/usr/bin/env python3
"""The frictionless normal problem solved by CONTACT's program and by
`railcontact solve`, whole processes alternated; see README.md here."""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time

# CONTACT's `tractcurv` example ellipse (examples/tractcurv.inp, case 1):
# A1 = 0.8e-3 /mm, B1 = 0.2814e-3 /mm (its printed B1 for AA/BB = 0.5),
# FN = 106.7 kN, G = 82 GPa, nu = 0.28; here the potential contact is 1.2
# times the Hertz semi-axes, railcontact's default window (2.4 a x 2.4 b).
A_PER_M = 0.8
B_PER_M = 0.2814
FORCE_N = 106700.0
G_PA = 82.0e9
NU = 0.28
SCALE = 1.2

CONTACT_INP = """ 3 MODULE
  200100     P-B-T-N-F-S        PVTIME, BOUND , TANG  , NORM , FORCE, STRESS
  022020     L-D-C-M-Z-E        FRCLAW, DISCNS, INFLCF, MATER, RZNORM, EXRHS
  000141     G-I-A-O-W-R        GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW, RETURN
   999   100   30    1      {eps:g}    MAXGS , MAXIN , MAXNR , MAXOUT, EPS
 {fn:.1f}      0.0        0.000      0.000           FN, CKSI, CETA, CPHI
   0.300      0.300                                 FSTAT, FKIN
   {nu}      {nu}      {g:.1f}     {g:.1f}          POISS 1,2,  GG 1,2
   -1                                               IPOTCN
  {mx}  {my}    {a:.6e}     {b:.6e}      {scale}    MX,MY,A1,B1,SCALE
 0  MODULE
"""

CASE_TOML = """model = "exact"

[material]
shear_modulus_pa = {g:e}
poisson_ratio = {nu}

[geometry]
kind = "quadratic"
a_per_m = {a}
b_per_m = {b}

[load]
normal_force_n = {fn}

[grid]
nx = {mx}
ny = {my}
"""


def write_cases(workdir, mx, my, eps_list):
    names = {}
    for eps in eps_list:
        name = f"hz_{mx}x{my}_eps{eps:g}"
        with open(os.path.join(workdir, name + ".inp"), "w") as f:
            f.write(
                CONTACT_INP.format(
                    eps=eps,
                    fn=FORCE_N,
                    nu=NU,
                    g=G_PA * 1e-6,
                    mx=mx,
                    my=my,
                    a=A_PER_M * 1e-3,
                    b=B_PER_M * 1e-3,
                    scale=SCALE,
                )
            )
        names[eps] = name
    case = CASE_TOML.format(g=G_PA, nu=NU, a=A_PER_M, b=B_PER_M, fn=FORCE_N, mx=mx, my=my)
    toml = os.path.join(workdir, f"hz_{mx}x{my}.toml")
    with open(toml, "w") as f:
        f.write(case)
    # One iteration: the kernel build and the first iteration, to tell the
    # iterations' time from the rest of the process.
    with open(toml.replace(".toml", "_1it.toml"), "w") as f:
        f.write(case + "\n[solver]\nmax_iterations = 1\n")
    return names, toml


def run_contact(prog, workdir, name):
    t0 = time.perf_counter()
    subprocess.run(
        [prog, "2", name], cwd=workdir, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True
    )
    wall = time.perf_counter() - t0
    out = open(os.path.join(workdir, name + ".out")).read()
    its = [int(m) for m in re.findall(r"ItCG=\s*(\d+)", out)]
    norm = re.search(r"\|Algorithm Norm\s*\|\s*\d+\s*\|\s*\S+\s*\|\s*\S+\s*\|\s*(\S+)", out)
    pmax = re.search(r"PMAX\s*\n\s*(\S+)\s+\S+\s+\S+\s+(\S+)\s+(\S+)", out)
    return {
        "wall_s": wall,
        "iterations": sum(its),
        "norm_s": float(norm.group(1)) if norm else float("nan"),
        "pmax_pa": float(pmax.group(3)) * 1e6 if pmax else float("nan"),
    }


def run_ours(prog, toml):
    t0 = time.perf_counter()
    p = subprocess.run([prog, "solve", toml, "--json"], capture_output=True, text=True, check=True)
    wall = time.perf_counter() - t0
    j = json.loads(p.stdout)
    return {
        "wall_s": wall,
        "iterations": j["normal_iterations"],
        "solve_s": j["solve_time_s"],
        "pmax_pa": j["max_pressure_pa"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--contact", default="/tmp/cntc-prog/bin/contact_linux64")
    ap.add_argument("--railcontact", default="target/release/railcontact")
    ap.add_argument("--railcontact-old", help="another railcontact binary, alternated with the rest")
    ap.add_argument("--grids", default="48x44,128x128,256x256,512x512,575x647")
    ap.add_argument("--eps", default="1e-5,1e-6", help="CONTACT's EPS values (its default 1e-5)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--workdir", default="/tmp/contact_normal_bench")
    ap.add_argument("--json-out", help="write all samples to this file")
    args = ap.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    eps_list = [float(e) for e in args.eps.split(",")]
    grids = [tuple(int(v) for v in g.split("x")) for g in args.grids.split(",")]
    # A trivial case of each program: process start-up and I/O.
    grids_all = [(16, 16)] + grids
    cases = {g: write_cases(args.workdir, g[0], g[1], eps_list) for g in grids_all}
    ours = ["ours"] + (["old"] if args.railcontact_old else [])
    binary = {"ours": args.railcontact, "old": args.railcontact_old}
    samples = {g: {**{o: [] for o in ours}, **{e: [] for e in eps_list}} for g in grids_all}
    for r in range(args.rounds):
        for g in grids_all:
            names, toml = cases[g]
            order = ours + eps_list
            if r % 2 == 1:
                order.reverse()
            for who in order:
                if who in binary:
                    s = run_ours(binary[who], toml)
                    one = run_ours(binary[who], toml.replace(".toml", "_1it.toml"))
                    s["one_iteration_solve_s"] = one["solve_s"]
                else:
                    s = run_contact(args.contact, args.workdir, names[who])
                samples[g][who].append(s)
                print(f"round {r} {g[0]}x{g[1]} {who}: {s}", file=sys.stderr, flush=True)
    if args.json_out:
        with open(args.json_out, "w") as f:
            json.dump({f"{g[0]}x{g[1]}": {str(k): v for k, v in s.items()} for g, s in samples.items()}, f, indent=1)
    med = lambda xs, k: statistics.median(x[k] for x in xs)
    base_ours = med(samples[(16, 16)]["ours"], "wall_s")
    base_c = {e: med(samples[(16, 16)][e], "wall_s") for e in eps_list}
    print(f"start-up (16x16 case): railcontact {base_ours*1e3:.1f} ms, CONTACT "
          + ", ".join(f"EPS {e:g} {base_c[e]*1e3:.1f} ms" for e in eps_list))
    head = ("| grid | ours: iterations | ours: process [s] | ours: solve [s] | ours: kernels + first"
            " iteration [s] | ours: per further iteration [ms] |")
    sep = "|---|---|---|---|---|---|"
    for e in eps_list:
        head += f" CONTACT EPS {e:g}: ItCG | process [s] | Norm timer [s] | ratio CONTACT/ours process | ratio less start-up |"
        sep += "---|---|---|---|---|"
    print(head)
    print(sep)
    for g in grids:
        s = samples[g]
        it = med(s["ours"], "iterations")
        w = med(s["ours"], "wall_s")
        sv = med(s["ours"], "solve_s")
        one = med(s["ours"], "one_iteration_solve_s")
        per = (sv - one) / (it - 1) if it > 1 else float("nan")
        row = f"| {g[0]} x {g[1]} | {it:g} | {w:.3f} | {sv:.3f} | {one:.3f} | {per * 1e3:.2f} |"
        for e in eps_list:
            cw = med(s[e], "wall_s")
            # Less each program's start-up, while ours is well above its own.
            less = (f"{(cw - base_c[e]) / (w - base_ours):.2f}" if w > 2 * base_ours else "-")
            row += f" {med(s[e], 'iterations'):g} | {cw:.3f} | {med(s[e], 'norm_s'):.1f} | {cw / w:.2f} | {less} |"
        print(row)
    if args.railcontact_old:
        print("\n| grid | old binary: process [s] | solve [s] | this binary: process [s] | solve [s] | old / this, process |")
        print("|---|---|---|---|---|---|")
        for g in grids:
            s = samples[g]
            wo, w = med(s["old"], "wall_s"), med(s["ours"], "wall_s")
            print(f"| {g[0]} x {g[1]} | {wo:.3f} | {med(s['old'], 'solve_s'):.3f} | {w:.3f} |"
                  f" {med(s['ours'], 'solve_s'):.3f} | {wo / w:.2f} |")
    for g in grids:
        po = med(samples[g]["ours"], "pmax_pa")
        pc = med(samples[g][eps_list[-1]], "pmax_pa")
        print(f"p_max {g[0]}x{g[1]}: ours {po/1e6:.2f} MPa, CONTACT {pc/1e6:.2f} MPa", file=sys.stderr)


if __name__ == "__main__":
    main()
