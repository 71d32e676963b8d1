#!/usr/bin/env bash
# Acceptance of the mesh outputs (issue 6): a sea area with islands (Brittany) meshed
# and written to every format in one run, each file loaded by its reader (GDAL, gmsh,
# meshio, python3-netcdf4, our gr3, fort.14 and MIKE .mesh checks, QGIS's mesh reader for .2dm) and the GeoPackage
# rendered by QGIS with its embedded styles. Writes into out/acceptance/ (or $1); needs build/isoquad.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-$ROOT/out/acceptance}
mkdir -p "$OUT"
cd "$ROOT"
PY=/usr/bin/python3
time build/isoquad mesh shapefiles/brittany_land.shp --domain water \
  --bbox -5.3,46.8,-1.95,49.35 --hmax 8000 --overwrite \
  -o "$OUT/brittany.gpkg" -o "$OUT/brittany.msh" -o "$OUT/hgrid.gr3" \
  -o "$OUT/brittany.vtk" -o "$OUT/brittany.vtu" -o "$OUT/brittany.nc" \
  -o "$OUT/brittany.2dm" -o "$OUT/brittany.slf" -o "$OUT/fort.14" -o "$OUT/brittany.mesh" \
  --report "$OUT/brittany.json"

echo "== GDAL"
ogrinfo -q "$OUT/brittany.gpkg" -sql "SELECT kind, COUNT(*) AS segments, SUM(num_nodes) AS nodes FROM boundary GROUP BY kind"
ogrinfo -q "$OUT/brittany.gpkg" -sql "SELECT f_table_name, styleName, useAsDefault FROM layer_styles"
echo "== gmsh (read, write back as MSH 2.2: elements by type and physical group)"
gmsh "$OUT/brittany.msh" -0 -format msh22 -o "$OUT/brittany_gmsh22.msh" > /dev/null
awk '/\$Elements/{f=1;getline;next}/\$EndElements/{f=0}f{c["type " $2 " physical " $4]++}END{for(k in c)print k": "c[k]}' \
  "$OUT/brittany_gmsh22.msh" | sort
echo "== meshio, netCDF4, gr3, fort.14, MIKE .mesh"
"$PY" - "$OUT" <<'PYEOF'
import sys, meshio, netCDF4
out = sys.argv[1]
for f in ("brittany.vtk", "brittany.vtu", "brittany.msh"):
    m = meshio.read(f"{out}/{f}")
    print(f, len(m.points), "points", {k: len(v) for k, v in m.cells_dict.items()})
d = netCDF4.Dataset(f"{out}/brittany.nc")
mesh = d["mesh"]
print("brittany.nc", mesh.cf_role, {k: v.size for k, v in d.dimensions.items()},
      "start_index", d[mesh.face_node_connectivity].start_index)
lines = open(f"{out}/hgrid.gr3").read().split("\n")
ne, np_ = map(int, lines[1].split())
print("hgrid.gr3", ne, "quads,", np_, "nodes;", *(l for l in lines if "Number of open boundaries" in l or "Number of land boundaries" in l))
lines = open(f"{out}/fort.14").read().split("\n")
ne, np_ = map(int, lines[1].split())
ibtypes = [l.split()[1] for l in lines if "Number of nodes for land boundary" in l]
print("fort.14", ne, "triangles,", np_, "nodes; IBTYPE", {t: ibtypes.count(t) for t in sorted(set(ibtypes))},
      *(l for l in lines if "Number of open boundaries" in l or "Number of land boundaries" in l))
lines = open(f"{out}/brittany.mesh").read().split("\n")
item, unit, np_, projection = lines[0].split(maxsplit=3)
codes = [int(l.split()[4]) for l in lines[1:1 + int(np_)]]
print("brittany.mesh", np_, "nodes,", lines[1 + int(np_)], "(elements, nodes each, 25: quads);",
      "node codes", {c: codes.count(c) for c in sorted(set(codes))}, "projection", projection[:40] + "...")
PYEOF
echo "== QGIS: the .2dm, .nc and .slf as mesh layers (MDAL)"
"$PY" - "$OUT"/brittany.{2dm,nc,slf} 2> >(grep -v "QStandardPaths\|HDF5\|^ *#\|major:\|minor:" >&2) <<'PYEOF'
import os, sys
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
from qgis.core import QgsApplication, QgsMesh, QgsMeshLayer
app = QgsApplication([], False)
app.initQgis()
for path in sys.argv[1:]:
    layer = QgsMeshLayer(path, "m", "mdal")
    mesh = QgsMesh()
    layer.dataProvider().populateMesh(mesh)
    print(os.path.basename(path), "valid", layer.isValid(), mesh.vertexCount(), "vertices,",
          mesh.faceCount(), "faces, CRS", layer.crs().description() or "none")
PYEOF
echo "== TELEMAC boundary conditions: lines by codes"
awk '{print $1, $2, $3}' "$OUT/brittany.cli" | sort | uniq -c
echo "== QGIS"
"$PY" tools/render_gpkg_qgis.py "$OUT/brittany.gpkg" "$OUT/brittany.png" 2> >(grep -v QStandardPaths >&2)
echo "wrote $OUT/brittany.png"
