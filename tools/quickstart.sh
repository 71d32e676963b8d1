#!/usr/bin/env bash
# One command for a new user on Debian 12: install the dependencies, build isoquad
# (Release) and run it on the bundled sample, writing a GeoPackage into out/.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
bash tools/install-deps.sh
bash tools/build.sh --target isoquad  # the tests build with tools/run-tests.sh
mkdir -p out
SAMPLE=${1:-shapefiles/corsica.shp}
OUT=out/$(basename "${SAMPLE%.*}")_mesh.gpkg
build/isoquad mesh "$SAMPLE" -o "$OUT" --overwrite --report "${OUT%.gpkg}.json" --plot "${OUT%.gpkg}.png"
echo "wrote $OUT (open it in QGIS)"
