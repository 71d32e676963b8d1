#!/usr/bin/python3
"""Renders an isoquad mesh GeoPackage with QGIS (headless), using the styles embedded in
its layer_styles table, to a PNG. Checks that every layer opened with its embedded
default style and prints one line per layer: name, features, renderer, style.
`--style quads=checks` draws a layer with another of its stored styles instead; a
rule-based style then prints a line per rule: `rule <label>: <features it selects>`.

    /usr/bin/python3 tools/render_gpkg_qgis.py mesh.gpkg mesh.png [--size 1200]
        [--style LAYER=NAME]...

Every style stored for a layer drawn is applied once (to a copy of the layer) and named
on a line `style <layer>/<name>: applies`. Needs Debian's python3-qgis and qgis-providers
(QGIS 3.22). Exit 1 when a layer does not load or is not styled from the GeoPackage, or
when a stored style of it is not XML or QGIS cannot apply it (QGIS itself then draws the
layer in a random colour and says nothing).
"""
import argparse
import os
import sys

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")

from qgis.core import (QgsApplication, QgsExpression, QgsFeatureRequest,  # noqa: E402
                       QgsMapRendererParallelJob, QgsMapSettings, QgsProject, QgsVectorLayer)
from qgis.PyQt.QtCore import QSize  # noqa: E402
from qgis.PyQt.QtGui import QColor  # noqa: E402
from qgis.PyQt.QtXml import QDomDocument  # noqa: E402

EXPECTED = {"quads": "graduatedSymbol", "vertices": "categorizedSymbol",
            "boundary": "categorizedSymbol"}


def layer_and_style(text):
    """--style's LAYER=NAME as (LAYER, NAME)."""
    layer, equals, name = text.partition("=")
    if not equals or not layer or not name:
        raise argparse.ArgumentTypeError(f"'{text}': expected LAYER=NAME, e.g. quads=checks")
    return layer, name


def use_stored_style(layer, style_name):
    """Applies the layer's style named style_name from the GeoPackage's layer_styles."""
    _, ids, names, _, _ = layer.listStylesInDatabase()
    if style_name not in names:
        print(f"{layer.name()}: no stored style '{style_name}' (has {names})", file=sys.stderr)
        return False
    qml, error = layer.getStyleFromDatabase(ids[names.index(style_name)])
    doc = QDomDocument()
    if not doc.setContent(qml):
        print(f"{layer.name()}: style '{style_name}' is not XML {error}", file=sys.stderr)
        return False
    applied, message = layer.importNamedStyle(doc)
    if not applied:
        print(f"{layer.name()}: style '{style_name}': {message}", file=sys.stderr)
    return applied


def check_stored_styles(path, name):
    """Applies each style stored for layer `name` to a copy of it; False when one fails."""
    copy = QgsVectorLayer(f"{path}|layername={name}", name, "ogr")
    count, ids, names, _, _ = copy.listStylesInDatabase()
    ok = True
    for style_name in names[:count]:  # the layer's own; those of other layers follow
        if use_stored_style(copy, style_name):
            print(f"style {name}/{style_name}: applies")
        else:
            ok = False
    return ok


def print_rules(layer):
    """Prints each rule of a rule-based renderer with the features its filter selects."""
    ok = True
    for rule in layer.renderer().rootRule().children():
        if rule.isElse():
            print(f"rule {rule.label()}: else")
            continue
        expression = QgsExpression(rule.filterExpression())
        if expression.hasParserError():
            print(f"rule {rule.label()}: {expression.parserErrorString()}", file=sys.stderr)
            ok = False
            continue
        count = sum(1 for _ in layer.getFeatures(QgsFeatureRequest(expression)))
        print(f"rule {rule.label()}: {count}")
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("gpkg")
    ap.add_argument("png")
    ap.add_argument("--size", type=int, default=1200)
    ap.add_argument("--layers", default="quads,boundary",
                    help="layers to draw, top last (default: quads,boundary)")
    ap.add_argument("--style", action="append", default=[], metavar="LAYER=NAME",
                    type=layer_and_style,
                    help="draw LAYER with its stored style NAME instead of the default")
    args = ap.parse_args()
    chosen = dict(args.style)

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
        expected = EXPECTED.get(name)
        if name in chosen:
            if not use_stored_style(layer, chosen[name]):
                ok = False
                continue
            expected = None
        ok = check_stored_styles(args.gpkg, name) and ok
        renderer = layer.renderer().type()
        style = layer.styleManager().currentStyle()
        print(f"{name}: {layer.featureCount()} features, renderer {renderer}, style '{style}'")
        if renderer == "RuleRenderer":
            ok = print_rules(layer) and ok
        if expected and renderer != expected:
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
