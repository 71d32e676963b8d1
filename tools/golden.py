#!/usr/bin/python3
"""Golden-file regression tests of `isoquad mesh`.

Each case is a directory tests/golden/<case>/ holding:
  args.txt       the isoquad mesh arguments, one per line; {dir} stands for the case
                 directory and {src} for the source tree (inputs live in either)
  expected.json  the expected report values: {"path.to.value": {"value": v, "tol": t}}
                 where path follows the --report JSON ("quality.num_quads", ...), and
                 tol is absolute ("tol") or relative ("rtol")

  tools/golden.py check tests/golden/<case> --isoquad build/isoquad
  tools/golden.py update tests/golden/*            (after an intended change; review
                                                    the diff of expected.json)
  tools/golden.py init my_cases/bay -- INPUT --hmax 5000 ...
                                                   (a new case: writes args.txt from the
                                                    arguments after --, runs them and
                                                    writes expected.json with the default
                                                    values and tolerances below; an -o
                                                    without a directory, such as -o
                                                    mesh.geojson, goes in the case
                                                    directory, written again by each run)

Only values listed in expected.json are compared, with their tolerances; the mesh
itself is not stored (byte-exact floating point would fail across compilers).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

SRC = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def run_case(case, isoquad):
    with open(os.path.join(case, "args.txt")) as f:
        args = [l.strip().replace("{dir}", case).replace("{src}", SRC) for l in f if l.strip()]
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "report.json")
        # --overwrite: a case's own outputs (-o {dir}/mesh.geojson) are written again.
        cmd = [isoquad, "mesh", *args, "-o", os.path.join(tmp, "mesh.gpkg"), "--report", report,
               "-q", "--overwrite"]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            sys.exit(f"golden: {case}: isoquad failed ({proc.returncode}): {proc.stderr.strip()}")
        with open(report) as f:
            return json.load(f)


def lookup(report, path):
    node = report
    for part in path.split("."):
        node = node[int(part)] if isinstance(node, list) else node[part]
    return node


def check(case, isoquad):
    case = os.path.abspath(case)
    report = run_case(case, isoquad)
    with open(os.path.join(case, "expected.json")) as f:
        expected = json.load(f)
    failures = []
    for path, spec in sorted(expected.items()):
        got = lookup(report, path)
        want = spec["value"]
        tol = spec.get("tol", 0.0) + spec.get("rtol", 0.0) * abs(want)
        ok = abs(got - want) <= tol
        print(f"{'ok  ' if ok else 'FAIL'} {os.path.basename(case)}: {path} = {got!r} "
              f"(expected {want!r} +- {tol:g})")
        if not ok:
            failures.append(path)
    if failures:
        sys.exit(f"golden: {case}: {len(failures)} value(s) out of tolerance: {', '.join(failures)}")


def update(case, isoquad):
    case = os.path.abspath(case)
    report = run_case(case, isoquad)
    path = os.path.join(case, "expected.json")
    with open(path) as f:
        expected = json.load(f)
    for key, spec in expected.items():
        spec["value"] = lookup(report, key)
    with open(path, "w") as f:
        json.dump(expected, f, indent=2, sort_keys=True)
        f.write("\n")
    print(f"updated {path}")


# What `init` records, with its tolerances: the counts and shares of the quality report,
# the domain's components and holes, and the open boundary (edges, and segments).
DEFAULT_EXPECTED = {
    "quality.num_quads": {"rtol": 0.1},
    "quality.num_triangles": {"tol": 0},
    "quality.num_nonconvex": {"tol": 0},
    "quality.share_angles_75_105": {"tol": 0.03},
    "quality.share_regular_interior": {"tol": 0.05},
    "quality.size_ratio_median": {"tol": 0.05},
    "quality.share_size_ratio_08_125": {"tol": 0.05},
    "quality.orientation_mean_deg": {"tol": 1.0},
    "quality.mesh_area_m2": {"rtol": 0.01},
    "domain.num_components": {"tol": 0},
    "domain.num_holes": {"tol": 0},
    "boundary.num_open_edges": {"rtol": 0.1},
    "boundary.num_open_segments": {"tol": 0},
}


def init(case, isoquad, args):
    case = os.path.abspath(case)
    if not args:
        sys.exit("golden: init needs the isoquad mesh arguments after --")
    for name in ("args.txt", "expected.json"):
        if os.path.exists(os.path.join(case, name)):
            sys.exit(f"golden: {case}: {name} exists; use update")
    os.makedirs(case, exist_ok=True)
    # Paths inside the case directory are written as {dir}, so the case can move; an
    # output named without a directory (-o mesh.geojson) is kept in the case directory.
    lines = []
    for i, a in enumerate(args):
        full = os.path.abspath(a)
        output = i > 0 and args[i - 1] in ("-o", "--output")
        if output and not os.path.dirname(a):
            lines.append("{dir}" + os.sep + a)
        elif (os.path.exists(a) or output) and full.startswith(case + os.sep):
            lines.append("{dir}" + full[len(case):])
        else:
            lines.append(a)
    with open(os.path.join(case, "args.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    report = run_case(case, isoquad)
    expected = {key: dict(spec, value=lookup(report, key)) for key, spec in DEFAULT_EXPECTED.items()}
    with open(os.path.join(case, "expected.json"), "w") as f:
        json.dump(expected, f, indent=2, sort_keys=True)
        f.write("\n")
    print(f"created {os.path.join(case, 'args.txt')} and expected.json")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["check", "update", "init"])
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--isoquad", default=os.path.join(SRC, "build", "isoquad"))
    argv = sys.argv[1:]
    mesh_args = []
    if "--" in argv:
        mesh_args = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    a = ap.parse_args(argv)
    if a.command == "init":
        if len(a.cases) != 1:
            sys.exit("golden: init takes one case directory")
        init(a.cases[0], a.isoquad, mesh_args)
        return
    if mesh_args:
        sys.exit("golden: arguments after -- are for init only")
    for case in a.cases:
        if not os.path.isfile(os.path.join(case, "args.txt")):
            sys.exit(f"golden: {case} is not a case (no args.txt); make one with init")
        (check if a.command == "check" else update)(case, a.isoquad)


if __name__ == "__main__":
    main()
