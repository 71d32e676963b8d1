#!/usr/bin/python3
"""Renders an isoquad mesh GeoPackage with QGIS (headless), using the styles embedded in
its layer_styles table, to a PNG. Checks that every layer opened with its embedded
default style and prints one line per layer: name, features, renderer, style.

    /usr/bin/python3 tools/render_gpkg_qgis.py mesh.gpkg mesh.png [--size 1200]

Needs Debian's python3-qgis and qgis-providers (QGIS 3.22). Exit 1 when a layer does not
load or is not styled from the GeoPackage.
"""
import argparse
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")

from qgis.core import (QgsApplication, QgsMapRendererParallelJob, QgsMapSettings,  # noqa: E402
                       QgsProject, QgsVectorLayer)
from qgis.PyQt.QtCore import QSize  # noqa: E402
from qgis.PyQt.QtGui import QColor  # noqa: E402

EXPECTED = {"quads": "graduatedSymbol", "vertices": "categorizedSymbol",
            "boundary": "categorizedSymbol"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("gpkg")
    ap.add_argument("png")
    ap.add_argument("--size", type=int, default=1200)
    ap.add_argument("--layers", default="quads,boundary",
                    help="layers to draw, top last (default: quads,boundary)")
    args = ap.parse_args()

    app = QgsApplication([], False)
    app.initQgis()
    ok = True
    layers = []
    for name in args.layers.split(","):
        layer = QgsVectorLayer(f"{args.gpkg}|layername={name}", name, "ogr")
        if not layer.isValid():
            print(f"{name}: does not load", file=sys.stderr)
            ok = False
            continue
        renderer = layer.renderer().type()
        style = layer.styleManager().currentStyle()
        print(f"{name}: {layer.featureCount()} features, renderer {renderer}, style '{style}'")
        if name in EXPECTED and renderer != EXPECTED[name]:
            print(f"{name}: not styled from the GeoPackage (renderer {renderer})", file=sys.stderr)
            ok = False
        QgsProject.instance().addMapLayer(layer)
        layers.append(layer)
    if not layers:
        return 1
    settings = QgsMapSettings()
    settings.setLayers(list(reversed(layers)))  # first drawn last: the first is on top
    settings.setDestinationCrs(layers[0].crs())
    extent = layers[0].extent()
    for layer in layers[1:]:
        extent.combineExtentWith(layer.extent())
    extent.scale(1.05)
    ratio = extent.height() / extent.width() if extent.width() > 0 else 1.0
    settings.setOutputSize(QSize(args.size, max(1, int(args.size * ratio))))
    settings.setExtent(extent)
    settings.setBackgroundColor(QColor(255, 255, 255))
    job = QgsMapRendererParallelJob(settings)
    job.start()
    job.waitForFinished()
    if not job.renderedImage().save(args.png, "png"):
        print(f"cannot write {args.png}", file=sys.stderr)
        ok = False
    app.exitQgis()
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
