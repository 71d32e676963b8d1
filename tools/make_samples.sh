#!/usr/bin/env bash
# Regenerates the sample map polygons in shapefiles/ from Natural Earth 1:10m data,
# as packaged (TopoJSON) by the npm package `world-atlas` (tested with 2.0.2).
#
# Usage:
#   (cd /tmp && npm pack world-atlas && mkdir -p wa && tar xzf world-atlas-*.tgz -C wa)
#   tools/make_samples.sh /tmp/wa/package
#
# Needs: GDAL >= 3.3 command-line tools (ogr2ogr reads TopoJSON), Debian's
# python3-gdal under /usr/bin/python3 (GEOS-enabled, for MakeValid/clipping),
# SpatiaLite in GDAL's SQLite dialect (only for the geodesic areas printed at the end).
#
# Outputs (each as <name>.shp/.shx/.dbf/.prj/.cpg and <name>.geojson, EPSG:4326,
# attributes: id Integer, name String):
#   france         mainland France: the largest polygon of the France feature of countries-10m
#   brittany_land  land-10m clipped to lon -5.6..-1.5, lat 46.6..49.6, one polygon per feature
#   corsica        Corsica: the largest France part within lon 8..10, lat 41..43.5
#
# Deterministic: same input + same GDAL/GEOS give byte-identical files (the DBF
# "last update" date in the header is pinned to 2000-01-01).
set -euo pipefail

WA=${1:?usage: $0 /path/to/world-atlas (directory holding countries-10m.json and land-10m.json)}
PY=${PYTHON:-/usr/bin/python3}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=$ROOT/shapefiles

for f in countries-10m.json land-10m.json; do
  [ -f "$WA/$f" ] || { echo "missing $WA/$f" >&2; exit 1; }
done
command -v ogr2ogr >/dev/null || { echo "ogr2ogr not found" >&2; exit 1; }
"$PY" -c 'from osgeo import ogr' || { echo "$PY cannot import osgeo.ogr (install python3-gdal)" >&2; exit 1; }

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"

# ---------------------------------------------------------------------------
# 1. Select / repair / clip geometries (Python + OGR/GEOS) into plain GeoJSON.
# ---------------------------------------------------------------------------
"$PY" - "$WA" "$TMP" <<'PYEOF'
import json, sys
from osgeo import gdal, ogr
ogr.UseExceptions()
gdal.PushErrorHandler('CPLQuietErrorHandler')   # GEOS validity chatter; we check ourselves

wa, tmp = sys.argv[1], sys.argv[2]

CLIP = (-5.6, 46.6, -1.5, 49.6)      # brittany_land clip extent: xmin, ymin, xmax, ymax
CORSICA_BOX = (8.0, 41.0, 10.0, 43.5)
# Interior rings smaller than this (deg^2, ~0.08 km^2) are dropped. They only arise
# from MakeValid on TopoJSON quantisation bow-ties (one at the Rance estuary near
# Saint-Malo, -2.13 48.61, 2.2e-6 deg^2, touching the shell at one point).
# Genuine holes (Llivia exclave in France: 1.5e-3 deg^2) are kept.
MIN_HOLE = 1e-5
# Polygons smaller than this (deg^2) are dropped (guards against clip slivers).
MIN_POLY = 1e-6

# Names for brittany_land pieces: a point inside each expected polygon.
LABELS = [
    ("France mainland (Brittany, Pays de la Loire)", -3.00, 48.00),
    ("France mainland (Cotentin, west coast)",        -1.60, 49.20),
    ("Ouessant (Ushant)",                             -5.09, 48.46),
    ("Belle-Ile",                                     -3.17, 47.34),
    ("Ile de Noirmoutier",                            -2.25, 46.99),
    ("Ile d'Yeu",                                     -2.34, 46.72),
    ("Jersey",                                        -2.13, 49.21),
    ("Guernsey",                                      -2.58, 49.46),
    ("Sark",                                          -2.365, 49.43),
]

def log(*a):
    print('make_samples:', *a, file=sys.stderr)

def rect(x0, y0, x1, y1):
    return ogr.CreateGeometryFromWkt(
        'POLYGON((%r %r,%r %r,%r %r,%r %r,%r %r))' % (x0, y0, x1, y0, x1, y1, x0, y1, x0, y0))

def polys(g):
    """All Polygon members of any geometry (lines/points from clipping are dropped)."""
    t = ogr.GT_Flatten(g.GetGeometryType())
    if t == ogr.wkbPolygon:
        return [g.Clone()]
    out = []
    if t in (ogr.wkbMultiPolygon, ogr.wkbGeometryCollection):
        for i in range(g.GetGeometryCount()):
            out += polys(g.GetGeometryRef(i))
    return out

def ring_area(r):
    p = ogr.Geometry(ogr.wkbPolygon)
    p.AddGeometry(r)
    return p.GetArea()

def drop_small_holes(p, what):
    q = ogr.Geometry(ogr.wkbPolygon)
    q.AddGeometry(p.GetGeometryRef(0))
    for k in range(1, p.GetGeometryCount()):
        r = p.GetGeometryRef(k)
        a = ring_area(r)
        if a < MIN_HOLE:
            x0, x1, y0, y1 = r.GetEnvelope()
            log('%s: dropped artefact hole (%d pts, %.2e deg2) at %.4f %.4f' % (what, r.GetPointCount(), a, x0, y0))
        else:
            q.AddGeometry(r)
    return q

def clean(g, what):
    """Valid polygons of g, largest first, without artefact holes."""
    if not g.IsValid():
        log('%s: invalid input, applying MakeValid' % what)
        g = g.MakeValid()
    out = []
    for p in polys(g):
        if p.GetArea() < MIN_POLY:
            log('%s: dropped sliver polygon %.2e deg2' % (what, p.GetArea()))
            continue
        p = drop_small_holes(p, what)
        if not p.IsValid():
            raise SystemExit('%s: polygon still invalid after repair' % what)
        out.append(p)
    out.sort(key=lambda p: (-p.GetArea(), p.GetEnvelope()))
    return out

def write(name, feats):
    fc = {"type": "FeatureCollection", "name": name, "features": [
        {"type": "Feature", "properties": {"id": i, "name": n},
         "geometry": json.loads(g.ExportToJson())} for i, (n, g) in enumerate(feats, 1)]}
    with open('%s/%s.geojson' % (tmp, name), 'w') as f:
        json.dump(fc, f)

def country_parts(name):
    ds = ogr.Open(wa + '/countries-10m.json')
    lyr = ds.GetLayer('countries')
    lyr.SetAttributeFilter("name = '%s'" % name)
    feat = lyr.GetNextFeature()
    if feat is None:
        raise SystemExit('country %s not found' % name)
    return polys(feat.GetGeometryRef())

def inside(p, box):
    x0, x1, y0, y1 = p.GetEnvelope()
    return x0 >= box[0] and y0 >= box[1] and x1 <= box[2] and y1 <= box[3]

# --- france: largest part of the France feature, repaired ---------------------
fr = country_parts('France')
main = max(fr, key=lambda p: p.GetArea())
write('france', [('France (mainland)', clean(main, 'france')[0])])

# --- corsica ------------------------------------------------------------------
cor = max((p for p in fr if inside(p, CORSICA_BOX)), key=lambda p: p.GetArea())
write('corsica', [('Corsica', clean(cor, 'corsica')[0])])

# --- brittany_land: land-10m clipped to CLIP -------------------------------------
box = rect(*CLIP)
ds = ogr.Open(wa + '/land-10m.json')
lyr = ds.GetLayer(0)
pieces = []
for feat in lyr:
    for p in polys(feat.GetGeometryRef()):
        if not p.Intersects(box):
            continue
        if not p.IsValid():          # the Eurasia polygon; MakeValid before clipping
            p = p.MakeValid()
        pieces += clean(p.Intersection(box), 'brittany_land')
pieces.sort(key=lambda p: (-p.GetArea(), p.GetEnvelope()))
named, used = [], set()
for p in pieces:
    hits = [n for n, x, y in LABELS if p.Contains(ogr.CreateGeometryFromWkt('POINT(%r %r)' % (x, y)))]
    if len(hits) != 1 or hits[0] in used:
        raise SystemExit('brittany_land: cannot name polygon %s (%s)' % (p.GetEnvelope(), hits))
    used.add(hits[0])
    named.append((hits[0], p))
if len(used) != len(LABELS):
    raise SystemExit('brittany_land: missing %s' % sorted(set(n for n, _, _ in LABELS) - used))
write('brittany_land', named)
PYEOF

# ---------------------------------------------------------------------------
# 2. Write the shapefile and GeoJSON outputs with ogr2ogr.
# ---------------------------------------------------------------------------
SAMPLES=(france brittany_land corsica)
for s in "${SAMPLES[@]}"; do
  rm -f "$OUT/$s".{shp,shx,dbf,prj,cpg,geojson}
  ogr2ogr -q -f "ESRI Shapefile" -a_srs EPSG:4326 -nlt POLYGON -nln "$s" \
    -lco ENCODING=UTF-8 "$OUT/$s.shp" "$TMP/$s.geojson"
  # RFC 7946: WGS84 lon/lat, exterior rings counter-clockwise; 15 decimals = full precision.
  ogr2ogr -q -f GeoJSON -a_srs EPSG:4326 -nlt POLYGON -nln "$s" \
    -lco RFC7946=YES -lco COORDINATE_PRECISION=15 "$OUT/$s.geojson" "$TMP/$s.geojson"
  # Pin the DBF header "last update" date (bytes 1-3: YY-1900, MM, DD) to 2000-01-01.
  printf '\144\001\001' | dd of="$OUT/$s.dbf" bs=1 seek=1 conv=notrunc status=none
done

# ---------------------------------------------------------------------------
# 3. Check: every feature valid, print vertex counts and geodesic areas.
# ---------------------------------------------------------------------------
"$PY" - "$OUT" "${SAMPLES[@]}" <<'PYEOF'
import sys
from osgeo import gdal, ogr, osr
ogr.UseExceptions()
out, names = sys.argv[1], sys.argv[2:]
wgs = osr.SpatialReference(); wgs.ImportFromEPSG(4326)
wgs.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
l93 = osr.SpatialReference(); l93.ImportFromEPSG(2154)
l93.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
ct = osr.CoordinateTransformation(wgs, l93)
bad = 0
print('%-26s %4s %-46s %6s %5s %8s %14s %14s' % ('file', 'id', 'name', 'rings', 'valid', 'vertices', 'geodesic km2', 'EPSG:2154 km2'))
for n in names:
    for ext in ('shp', 'geojson'):
        path = '%s/%s.%s' % (out, n, ext)
        ds = ogr.Open(path)
        lyr = ds.GetLayer(0)
        # SpatiaLite ST_Area(geom, 1): area on the WGS84 ellipsoid. It is slightly
        # orientation dependent (CW rings read ~4e-6 low), so force CCW rings first;
        # then it agrees with GeographicLib's PolygonArea to < 1e-6.
        sql = ds.ExecuteSQL('SELECT id, ST_Area(ST_ForcePolygonCCW(GEOMETRY), 1) AS a FROM "%s"' % lyr.GetName(),
                            dialect='SQLite')
        geod = {f.GetField('id'): f.GetField('a') for f in sql}
        ds.ReleaseResultSet(sql)
        tot_v = 0
        for f in lyr:
            g = f.GetGeometryRef()
            v = sum(g.GetGeometryRef(k).GetPointCount() - 1 for k in range(g.GetGeometryCount()))
            tot_v += v
            ok = g.IsValid()
            bad += not ok
            p = g.Clone(); p.Transform(ct)
            print('%-26s %4d %-46s %6d %5s %8d %14.1f %14.1f' % (
                n + '.' + ext, f.GetField('id'), f.GetField('name'), g.GetGeometryCount(), ok, v,
                geod[f.GetField('id')] / 1e6, p.GetArea() / 1e6))
        print('%-26s features=%d vertices=%d extent=%s' % (n + '.' + ext, lyr.GetFeatureCount(), tot_v,
              tuple(round(c, 4) for c in lyr.GetExtent())))
if bad:
    sys.exit('make_samples: %d invalid feature(s)' % bad)
print('make_samples: all features valid')
PYEOF
