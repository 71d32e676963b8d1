#!/usr/bin/python3
"""Side-by-side comparison of isoquad and Gmsh on the same projected domain and size.

Runs `isoquad domain` to get the planar domain (meshing CRS, simplified), writes it as a
Gmsh .geo, meshes it with Gmsh (Frontal-Delaunay for quads, Blossom full-quad
recombination, uniform size H) and with `isoquad mesh --size H`, then computes the same
metrics for both meshes here, independently of isoquad's own report:

  angles in [75,105], min and max angle, non-convex quads, triangles left,
  sqrt(area)/H median and share in [0.8,1.25], orientation deviation from isoquad's
  boundary-aligned cross field (mean, p90; and over the quads with a vertex on the
  boundary alone), regular interior vertices, SCHISM's two
  checks (quads whose smallest over largest angle is under 0.5, and whose longest over
  shortest side is over 5, as isoquad's report counts them), the mesh's area against the
  domain's and how far the domain's boundary vertices lie from the mesh's boundary (Gmsh
  puts a node on every one of them; isoquad's boundary edges are chords), wall time and
  peak memory (each process's own, from GNU time: the wait4 of a process forked from
  this one would count this script's own memory, copied at the fork).

In --auto mode every isoquad run (and `isoquad domain`, which writes Gmsh's domain) gets
the simplification, minimum width and island area that `isoquad fields` reports it used,
so that Gmsh meshes the same cleaned boundary (the script stops if the two domains'
vertex counts differ).

Then `isoquad quality` measures Gmsh's mesh too, and the last lines say whether its
figures (counts, angles, regularity, SCHISM's and D-Flow FM's counts; orientation to half
a degree, the cross field being interpolated otherwise here) are this script's: the two
are computed apart, so each checks the other.

Each program runs --repeat times (default 3), alternately, so that a slow spell of the
machine falls on both: the table gives the median wall time with the range, and the
ratio of the medians. isoquad's repeated outputs must be byte-identical.

With --auto instead of --size, both follow isoquad's automatic sizing field (pass its
options after --, e.g. -- --hmax 28000): Gmsh reads it as a background mesh view, and
sqrt(area)/h is measured against it at the quad centroids.

Usage: tools/compare_gmsh.py INPUT (--size H | --auto) [--isoquad build/isoquad]
       [--workdir DIR] [--simplify M] [--repeat N] [extra isoquad options after --]
Needs Debian's gmsh, time, python3-meshio, python3-gdal, python3-scipy (tools/install-deps.sh).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import meshio
import numpy as np
from osgeo import ogr
from scipy.spatial import cKDTree


def run(cmd):
    """Runs cmd; returns its wall time in seconds and its peak resident memory in MB, as
    GNU time reads it from wait4 (time forks the command from its own small process)."""
    with tempfile.NamedTemporaryFile("r", suffix=".rss") as rss:
        t0 = time.perf_counter()
        proc = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", rss.name, *cmd],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        elapsed = time.perf_counter() - t0
        if proc.returncode != 0:
            sys.exit(f"compare_gmsh: {' '.join(cmd)} failed ({proc.returncode}):\n{proc.stderr}")
        return elapsed, int(rss.read().split()[-1]) / 1024.0


def domain_to_geo(gpkg, geo_path, size, background=None):
    """Writes every ring of the domain layer as Gmsh points/lines/plane surfaces; with
    `background` (a .pos view of h), sizes come from that view instead of `size`."""
    ds = ogr.Open(gpkg)
    layer = ds.GetLayerByName("domain")
    lines, point_id, line_id, loop_id, surfaces = [], 0, 0, 0, []
    for feature in layer:
        poly = feature.GetGeometryRef()
        loops = []
        for r in range(poly.GetGeometryCount()):
            ring = poly.GetGeometryRef(r)
            pts = ring.GetPoints()[:-1]
            first = point_id + 1
            for x, y, *_ in pts:
                point_id += 1
                lines.append(f"Point({point_id}) = {{{x!r}, {y!r}, 0, {size or 1.0!r}}};")
            ids = list(range(first, point_id + 1))
            seg_ids = []
            for i, a in enumerate(ids):
                b = ids[(i + 1) % len(ids)]
                line_id += 1
                lines.append(f"Line({line_id}) = {{{a}, {b}}};")
                seg_ids.append(line_id)
            loop_id += 1
            lines.append(f"Curve Loop({loop_id}) = {{{', '.join(map(str, seg_ids))}}};")
            loops.append(loop_id)
        surfaces.append(loops)
    for s, loops in enumerate(surfaces, start=1):
        lines.append(f"Plane Surface({s}) = {{{', '.join(map(str, loops))}}};")
    lines += [
        "Mesh.Algorithm = 8;",
        "Mesh.CrossFieldClosestPoint = 0;",
        "Mesh.RecombineAll = 1;",
        "Mesh.RecombinationAlgorithm = 3;",
        "Mesh.MeshSizeExtendFromBoundary = 0;",
        "Mesh.MeshSizeFromPoints = 0;",
        "Mesh.MeshSizeFromCurvature = 0;",
    ]
    if background:
        lines += [f'Merge "{background}";', "Field[1] = PostView;", "Field[1].ViewIndex = 0;",
                  "Background Field = 1;"]
    else:
        lines += [f"Mesh.MeshSizeMin = {size!r};", f"Mesh.MeshSizeMax = {size!r};"]
    with open(geo_path, "w") as f:
        f.write("\n".join(lines) + "\n")


def field_at(fields_vtu, name, scale=1.0):
    """Nearest-vertex lookup of one of isoquad's fields (cross_angle in radians)."""
    f = meshio.read(fields_vtu)
    tree = cKDTree(f.points[:, :2])
    values = f.point_data[name] * scale
    return lambda pts: values[tree.query(pts)[1]]


def fields_to_pos(fields_vtu, pos_path, factor):
    """isoquad's size field on its background triangles as a Gmsh scalar view, times
    `factor`."""
    f = meshio.read(fields_vtu)
    p, h = f.points, f.point_data["size"] * factor
    with open(pos_path, "w") as out:
        out.write('View "h" {\n')
        for a, b, c in f.cells_dict["triangle"]:
            out.write(f"ST({p[a,0]!r},{p[a,1]!r},0,{p[b,0]!r},{p[b,1]!r},0,{p[c,0]!r},{p[c,1]!r},0)"
                      f"{{{h[a]!r},{h[b]!r},{h[c]!r}}};\n")
        out.write("};\n")


def domain_vertices_and_area(gpkg):
    """The domain's boundary vertices (every ring) and its area."""
    ds = ogr.Open(gpkg)
    vertices, area = [], 0.0
    for f in ds.GetLayer(0):
        g = f.GetGeometryRef()
        area += g.GetArea()
        polygons = [g.GetGeometryRef(i) for i in range(g.GetGeometryCount())] \
            if g.GetGeometryType() in (ogr.wkbMultiPolygon, ogr.wkbMultiPolygon25D) else [g]
        for poly in polygons:
            for k in range(poly.GetGeometryCount()):
                ring = poly.GetGeometryRef(k)
                vertices += [(ring.GetX(i), ring.GetY(i)) for i in range(ring.GetPointCount())]
    return np.array(vertices), area


def coast_departure(points, quads, domain_vertices):
    """The farthest any vertex of the domain's boundary lies from the mesh's boundary
    edges, measured against points every 0.2% of the median boundary edge along them (so
    within 0.1% of an edge of the exact distance)."""
    edges = np.sort(np.stack([quads, np.roll(quads, -1, axis=1)], -1).reshape(-1, 2), axis=1)
    uniq, counts = np.unique(edges, axis=0, return_counts=True)
    seg = points[uniq[counts == 1]][:, :, :2]  # (m, 2, 2)
    length = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    step = 0.002 * np.median(length)
    samples = []
    for (a, b), l in zip(seg, length):
        t = np.linspace(0.0, 1.0, max(2, int(math.ceil(l / step)) + 1))
        samples.append(a + t[:, None] * (b - a))
    d, _ = cKDTree(np.concatenate(samples)).query(domain_vertices)
    return float(d.max())


def dflowfm_orthogonality(p, quads):
    """D-Flow FM's orthogonality of each link between two quads (the |cosine| of the angle
    between the edge and the segment joining the quads' centres), with the quads' centres
    as D-Flow FM takes them (as isoquad's report does: quad_quality.h, dflowfm_centre)."""
    q = p[quads]
    signed = 0.5 * ((q[:, 2, 0] - q[:, 0, 0]) * (q[:, 3, 1] - q[:, 1, 1]) -
                    (q[:, 3, 0] - q[:, 1, 0]) * (q[:, 2, 1] - q[:, 0, 1]))
    quads = np.where(signed[:, None] < 0, quads[:, ::-1], quads)  # counter-clockwise
    q = p[quads]
    key = np.sort(np.stack([quads, np.roll(quads, -1, axis=1)], -1), axis=-1).reshape(-1, 2)
    _, inv, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inv = inv.ravel()
    shared = (counts[inv] == 2).reshape(-1, 4)
    a, b = q, np.roll(q, -1, axis=1)
    mid, d = 0.5 * (a + b), b - a
    length = np.linalg.norm(d, axis=-1, keepdims=True)
    u = d / np.where(length > 0, length, 1)
    mean = q.mean(axis=1)
    c = mean.copy()
    done = shared.sum(axis=1) < 2  # the corners' mean
    for sweep in range(100):
        before = c.copy()
        for i in range(4):
            move = shared[:, i] & ~done
            along = ((c - mid[:, i]) * u[:, i]).sum(-1)
            c[move] -= 0.1 * along[move, None] * u[move, i]
        if sweep > 0:
            done |= (np.abs(c - before) < 1e-3).all(axis=-1)
        if done.all():
            break
    # A centre outside its quad: back to where the segment from the mean leaves it.
    side = d[..., 0] * (c[:, None, 1] - a[..., 1]) - d[..., 1] * (c[:, None, 0] - a[..., 0])
    for k in np.nonzero((side < 0).any(axis=1))[0]:
        w = c[k] - mean[k]
        best = mean[k]
        for i in range(4):
            m = np.array([[w[0], -d[k, i, 0]], [w[1], -d[k, i, 1]]])
            if abs(np.linalg.det(m)) == 0:
                continue
            s_, t_ = np.linalg.solve(m, a[k, i] - mean[k])
            if 0 <= s_ <= 1 and 0 <= t_ <= 1:
                best = mean[k] + s_ * w
                break
        c[k] = best
    order = np.argsort(inv, kind="stable")
    sorted_inv = inv[order]
    pair = np.nonzero(sorted_inv[1:] == sorted_inv[:-1])[0]
    first, second = order[pair], order[pair + 1]  # (quad * 4 + side) of each link's two sides
    e = d.reshape(-1, 2)[first]
    f = c[second // 4] - c[first // 4]
    norms = np.linalg.norm(e, axis=-1) * np.linalg.norm(f, axis=-1)
    return np.where(norms > 0, np.abs((e * f).sum(-1)) / np.where(norms > 0, norms, 1), 1.0)


def metrics(points, quads, triangles, size, cross, domain=None):
    p = points[:, :2]
    q = p[quads]  # (n, 4, 2)
    prev = np.roll(q, 1, axis=1) - q
    nxt = np.roll(q, -1, axis=1) - q
    # Interior angle of a counter-clockwise polygon: from the next edge to the previous.
    ang = np.degrees(np.arctan2(nxt[..., 0] * prev[..., 1] - nxt[..., 1] * prev[..., 0],
                                (prev * nxt).sum(-1)))
    ang = np.where(ang < 0, ang + 360, ang)
    area = 0.5 * ((q[:, 2, 0] - q[:, 0, 0]) * (q[:, 3, 1] - q[:, 1, 1]) -
                  (q[:, 3, 0] - q[:, 1, 0]) * (q[:, 2, 1] - q[:, 0, 1]))
    edge = np.roll(q, -1, axis=1) - q
    turn = edge[..., 0] * np.roll(edge, -1, axis=1)[..., 1] - edge[..., 1] * np.roll(edge, -1, axis=1)[..., 0]
    nonconvex = int(np.sum(~np.all(turn > 0, axis=1)))
    side = np.linalg.norm(edge, axis=-1)
    under_angle_ratio = int(np.sum(ang.min(axis=1) < 0.5 * ang.max(axis=1)))
    over_aspect = int(np.sum(side.max(axis=1) > 5 * side.min(axis=1)))
    ratio = np.sqrt(np.abs(area)) / size(q.mean(axis=1))
    theta = cross(q.mean(axis=1))
    phi = np.arctan2(edge[..., 1], edge[..., 0])
    d = np.mod(phi - theta[:, None] + math.pi / 4, math.pi / 2) - math.pi / 4
    dev = np.degrees(np.abs(d)).mean(axis=1)
    # Interior vertex degrees: vertices not on an edge used once.
    edges = np.sort(np.stack([quads, np.roll(quads, -1, axis=1)], -1).reshape(-1, 2), axis=1)
    uniq, counts = np.unique(edges, axis=0, return_counts=True)
    boundary = np.zeros(len(points), bool)
    boundary[uniq[counts == 1].ravel()] = True
    degree = np.bincount(quads.ravel(), minlength=len(points))
    used = degree > 0
    interior = used & ~boundary
    at_coast = boundary[quads].any(axis=1)
    ortho = dflowfm_orthogonality(p, quads) if len(quads) else np.zeros(0)
    coast = {}
    if domain is not None:
        vertices, domain_area = domain
        coast = {
            "mesh area / domain area": f"{100 * np.abs(area).sum() / domain_area:.2f}%",
            "coast: farthest off the mesh (m)": f"{coast_departure(points, quads, vertices):.0f}",
        }
    return {
        "quads": len(quads),
        "triangles": int(triangles),
        "non-convex quads": nonconvex,
        "angles in [75,105]": f"{100 * np.mean((ang >= 75) & (ang <= 105)):.1f}%",
        "min / max angle": f"{ang.min():.1f} / {ang.max():.1f}",
        "sqrt(area)/h median": f"{np.median(ratio):.3f}",
        "sqrt(area)/h in [0.8,1.25]": f"{100 * np.mean((ratio >= 0.8) & (ratio <= 1.25)):.1f}%",
        "orientation dev. mean / p90": f"{dev.mean():.1f} / {np.percentile(dev, 90):.1f} deg",
        **({"orientation at the boundary mean / p90": f"{dev[at_coast].mean():.1f} / "
            f"{np.percentile(dev[at_coast], 90):.1f} deg"} if at_coast.any() else {}),
        "regular interior vertices": f"{100 * np.mean(degree[interior] == 4):.1f}%",
        "SCHISM: angle ratio < 0.5": under_angle_ratio,
        "SCHISM: aspect ratio > 5": over_aspect,
        **({"D-Flow FM: orthogonality max / mean": f"{ortho.max():.3f} / {ortho.mean():.3f}",
            "D-Flow FM: links over 0.5": int(np.sum(ortho > 0.5))} if len(ortho) else {}),
        **coast,
    }


def quality_agreement(isoquad, common, msh, gm_metrics, work):
    """`isoquad quality` on Gmsh's mesh, against this script's own figures for it: the
    two are computed apart (C++ and numpy), so they check each other."""
    report = os.path.join(work, "gmsh_quality.json")
    run([isoquad, "quality", *common, "--mesh", msh, "--report", report])
    with open(report) as f:
        q = json.load(f)["quality"]
    theirs = {
        "quads": q["num_quads"],
        "angles in [75,105]": f"{100 * q['share_angles_75_105']:.1f}%",
        "min / max angle": f"{q['min_angle_deg']:.1f} / {q['max_angle_deg']:.1f}",
        "SCHISM: angle ratio < 0.5": q["schism_angle_ratio_violations"],
        "SCHISM: aspect ratio > 5": q["schism_aspect_ratio_violations"],
    }
    if "share_regular_interior" in q:
        theirs["regular interior vertices"] = f"{100 * q['share_regular_interior']:.1f}%"
        theirs["D-Flow FM: links over 0.5"] = q["dflowfm_orthogonality_violations"]
    differ = [f"{k}: {gm_metrics[k]} here, {v} by isoquad quality"
              for k, v in theirs.items() if k in gm_metrics and str(gm_metrics[k]) != str(v)]
    # The cross field at the centroids is interpolated otherwise here (fields_vtu): the
    # orientation agrees to a few tenths of a degree.
    key = "orientation dev. mean / p90"
    here = [float(x) for x in gm_metrics[key].split()[0:3:2]]
    there = [q["orientation_mean_deg"], q["orientation_p90_deg"]]
    if any(abs(a - b) > 0.5 for a, b in zip(here, there)):
        differ.append(f"{key}: {gm_metrics[key]} here, {there[0]:.1f} / {there[1]:.1f} deg by "
                      "isoquad quality")
    if differ:
        return "(isoquad quality on Gmsh's mesh differs: " + "; ".join(differ) + ")"
    return "(isoquad quality on Gmsh's mesh gives the same figures)"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input")
    mode = ap.add_mutually_exclusive_group(required=True)
    mode.add_argument("--size", type=float, help="uniform element size H, metres")
    mode.add_argument("--auto", action="store_true", help="isoquad's automatic sizing for both")
    ap.add_argument("--isoquad", default=os.path.join(os.path.dirname(__file__), "..", "build", "isoquad"))
    ap.add_argument("--simplify", type=float, help="boundary simplification (default H/4)")
    ap.add_argument("--workdir")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each program (default 3)")
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    a = ap.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    a.extra = extra
    if a.repeat < 1:
        sys.exit("compare_gmsh: --repeat must be at least 1")
    # Absolute: Gmsh reads the .geo's includes and views relative to the .geo's folder.
    work = os.path.abspath(a.workdir or tempfile.mkdtemp(prefix="isoquad-vs-gmsh-"))
    os.makedirs(work, exist_ok=True)
    common = [a.input, "--overwrite", "-q"] + a.extra
    if a.size:
        simplify = a.simplify if a.simplify is not None else a.size / 4
        common += ["--size", repr(a.size), "--simplify", repr(simplify)]
    elif a.simplify is not None:
        common += ["--simplify", repr(a.simplify)]
    fields = os.path.join(work, "fields.vtu")
    fields_report = os.path.join(work, "fields.json")

    def fields_domain_summary():
        run([a.isoquad, "fields", *common, "-o", fields, "--report", fields_report])
        with open(fields_report) as f:
            return json.load(f)["domain"]

    used = fields_domain_summary()
    # `isoquad domain` takes no sizing options, and without --size it leaves the domain
    # as read. So the cleaning that `fields` and `mesh` derive from the automatic hmin
    # (their report's) is given to every run: Gmsh meshes the same simplified boundary.
    # The report rounds to 10 digits, and a tolerance that differs in its tenth digit can
    # keep one more vertex (the Baltic at 1:10m): the fields run again with the rounded
    # values, and isoquad's meshes use them too.
    # With --size H, `domain` derives the same cleaning from H itself.
    cleaning = []
    for option, key in (("--simplify", "simplify_m"), ("--min-width", "min_width_m"),
                        ("--min-island-area", "min_island_area_m2")):
        if a.auto and option not in common:
            cleaning += [option, repr(float(used[key]))]
    if cleaning:
        common += cleaning
        used = fields_domain_summary()
    domain = os.path.join(work, "domain.gpkg")
    sizing = {"--hmax", "--hmin", "--gradation", "--cells-across", "--size-expr", "--size-raster"}
    domain_args, skip = [], False
    for arg in common:
        if skip:
            skip = False
        elif arg in sizing:
            skip = True
        else:
            domain_args.append(arg)
    domain_report = os.path.join(work, "domain.json")
    run([a.isoquad, "domain", *domain_args, "-o", domain, "--report", domain_report])
    with open(domain_report) as f:
        given = json.load(f)
    for key in ("num_vertices_after", "num_rings"):
        if given.get(key) != used.get(key):
            sys.exit(f"compare_gmsh: the domain written for Gmsh has {key} {given.get(key)}, "
                     f"isoquad's mesh {used.get(key)}")
    cross = field_at(fields, "cross_angle", math.pi / 180)
    size = field_at(fields, "size") if a.auto else (lambda pts: np.full(len(pts), a.size))

    geo = os.path.join(work, "domain.geo")
    background = None
    if a.auto:
        background = os.path.join(work, "size.pos")
        fields_to_pos(fields, background, 1.0)
    domain_to_geo(domain, geo, a.size, background)

    iq_vtu = os.path.join(work, "isoquad.vtu")
    msh = os.path.join(work, "gmsh.msh")
    times_iq, times_gm, mem_iq, mem_gm = [], [], 0.0, 0.0
    for k in range(a.repeat):
        out = iq_vtu if k == 0 else os.path.join(work, f"isoquad_{k}.vtu")
        t, mem = run([a.isoquad, "mesh", *common, "-o", out])
        times_iq.append(t)
        mem_iq = max(mem_iq, mem)
        if k > 0:
            with open(iq_vtu, "rb") as first, open(out, "rb") as again:
                if first.read() != again.read():
                    sys.exit(f"compare_gmsh: isoquad's run {k + 1} wrote a different mesh ({out})")
            os.remove(out)
        t, mem = run(["gmsh", geo, "-2", "-format", "msh22", "-o", msh, "-v", "1"])
        times_gm.append(t)
        mem_gm = max(mem_gm, mem)
    t_iq, t_gm = float(np.median(times_iq)), float(np.median(times_gm))

    coast = domain_vertices_and_area(domain)
    iq = meshio.read(iq_vtu)
    iq_metrics = metrics(iq.points, iq.cells_dict["quad"], 0, size, cross, coast)
    gm = meshio.read(msh)
    gm_quads = gm.cells_dict.get("quad", np.zeros((0, 4), int))
    gm_tris = len(gm.cells_dict.get("triangle", []))
    # (Gmsh's leftover triangles, if any, are not counted in its area or boundary.)
    gm_metrics = metrics(gm.points, gm_quads, gm_tris, size, cross, coast if not gm_tris else None)

    agreement = quality_agreement(a.isoquad, common, msh, gm_metrics, work)

    seconds = "seconds (read to write)" if a.repeat == 1 else f"seconds, median of {a.repeat}"
    rows = list(iq_metrics.keys()) + [seconds, "peak memory (MB)"]
    iq_metrics[seconds] = f"{t_iq:.2f}"
    gm_metrics[seconds] = f"{t_gm:.2f}"
    if a.repeat > 1:
        rows.insert(-1, "seconds, range")
        iq_metrics["seconds, range"] = f"{min(times_iq):.2f} - {max(times_iq):.2f}"
        gm_metrics["seconds, range"] = f"{min(times_gm):.2f} - {max(times_gm):.2f}"
    iq_metrics["peak memory (MB)"] = f"{mem_iq:.0f}"
    gm_metrics["peak memory (MB)"] = f"{mem_gm:.0f}"
    w = max(len(r) for r in rows)
    print(f"{'':{w}}  {'isoquad':>16}  {'gmsh 4.8':>16}")
    for r in rows:
        print(f"{r:{w}}  {str(iq_metrics[r]):>16}  {str(gm_metrics[r]):>16}")
    print(f"{'time ratio gmsh / isoquad':{w}}  {t_gm / t_iq:>16.2f}")
    if a.repeat > 1:
        print(f"(isoquad's {a.repeat} runs wrote byte-identical meshes)")
    print(agreement)
    print(f"(files in {work})")


if __name__ == "__main__":
    main()
