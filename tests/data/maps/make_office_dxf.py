#!/usr/bin/env python3
"""Writes office_floor_mm.dxf: maps/office_floor.xml as an architect would
hand it over, an ASCII DXF (AutoCAD R2000, AC1015) in millimetres
($INSUNITS = 4), for the tests of `structloc map import --dxf` (issue 11).

Layers:
  WALLS      the 17 walls of office_floor.xml, drawn as a mix of entities:
             the outer walls as one closed LWPOLYLINE, walls 13+40 and 22+41
             as old-style POLYLINEs with VERTEX entities, wall 20 as an open
             LWPOLYLINE, the others as LINEs;
  PILLARS    the three pillars as CIRCLEs;
  CORNERS    the free-standing corner 100 (a cabinet edge at 2 m, 12 m) as a
             POINT; a drawing has no other way to say "corner here";
  FURNITURE  desks and a cabinet as closed LWPOLYLINE rectangles, a round
             table as a CIRCLE, a TEXT label;
  ANNOTATION room names as TEXT;
  DOORS      one INSERT of the block DOOR, whose definition (in the BLOCKS
             section) holds LINEs on layer WALLS that must not be imported.

Run from this folder: python3 make_office_dxf.py  (rewrites the .dxf).
"""

LAYERS = ["0", "WALLS", "PILLARS", "CORNERS", "FURNITURE", "ANNOTATION", "DOORS"]


def pairs(*items):
    """Group code / value pairs as DXF text lines."""
    out = []
    for code, value in zip(items[0::2], items[1::2]):
        if isinstance(value, float):
            value = f"{value:.3f}"
        out += [str(code), str(value)]
    return out


def line(layer, x1, y1, x2, y2):
    return pairs(0, "LINE", 8, layer, 10, x1, 20, y1, 30, 0.0, 11, x2, 21, y2, 31, 0.0)


def lwpolyline(layer, points, closed):
    out = pairs(0, "LWPOLYLINE", 100, "AcDbEntity", 8, layer, 100, "AcDbPolyline",
                90, len(points), 70, 1 if closed else 0)
    for x, y in points:
        out += pairs(10, x, 20, y)
    return out


def polyline(layer, points):
    out = pairs(0, "POLYLINE", 8, layer, 66, 1, 10, 0.0, 20, 0.0, 30, 0.0, 70, 0)
    for x, y in points:
        out += pairs(0, "VERTEX", 8, layer, 10, x, 20, y, 30, 0.0)
    return out + pairs(0, "SEQEND", 8, layer)


def circle(layer, x, y, r):
    return pairs(0, "CIRCLE", 8, layer, 10, x, 20, y, 30, 0.0, 40, r)


def point(layer, x, y):
    return pairs(0, "POINT", 8, layer, 10, x, 20, y, 30, 0.0)


def text(layer, x, y, words):
    return pairs(0, "TEXT", 8, layer, 10, x, 20, y, 30, 0.0, 40, 250.0, 1, words)


def rectangle(layer, x0, y0, x1, y1):
    return lwpolyline(layer, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)], True)


def entities():
    mm = 1000.0
    e = []
    # Walls 1-4: the outline, one closed polyline.
    e += lwpolyline("WALLS", [(0.0, 0.0), (24 * mm, 0.0), (24 * mm, 14 * mm), (0.0, 14 * mm)],
                    True)
    # Corridor walls (y = 5 m and 8 m) with door openings.
    e += line("WALLS", 0.0, 5 * mm, 3.5 * mm, 5 * mm)      # 10
    e += line("WALLS", 4.5 * mm, 5 * mm, 9.5 * mm, 5 * mm)  # 11
    e += line("WALLS", 10.5 * mm, 5 * mm, 15.5 * mm, 5 * mm)  # 12
    e += polyline("WALLS", [(16.5 * mm, 5 * mm), (18 * mm, 5 * mm), (18 * mm, 2 * mm)])  # 13, 40
    e += lwpolyline("WALLS", [(0.0, 8 * mm), (5.5 * mm, 8 * mm)], False)  # 20
    e += line("Walls", 6.5 * mm, 8 * mm, 11.5 * mm, 8 * mm)  # 21: layer case as a user typed it
    e += polyline("WALLS", [(12.5 * mm, 8 * mm), (18 * mm, 8 * mm), (18 * mm, 11 * mm)])  # 22, 41
    # Office partitions.
    e += line("WALLS", 6 * mm, 0.0, 6 * mm, 5 * mm)  # 30
    e += line("WALLS", 12 * mm, 0.0, 12 * mm, 5 * mm)  # 31
    e += line("WALLS", 9 * mm, 8 * mm, 9 * mm, 14 * mm)  # 32
    # Pillars.
    e += circle("PILLARS", 21 * mm, 4 * mm, 300.0)
    e += circle("PILLARS", 21 * mm, 10 * mm, 300.0)
    e += circle("PILLARS", 14 * mm, 6.5 * mm, 200.0)
    # The cabinet edge that office_floor.xml has as corner 100.
    e += point("CORNERS", 2 * mm, 12 * mm)
    # Furniture: desks, the cabinet, a round table.
    e += rectangle("FURNITURE", 1000.0, 1000.0, 2600.0, 1800.0)
    e += rectangle("FURNITURE", 7000.0, 1000.0, 8600.0, 1800.0)
    e += rectangle("FURNITURE", 13000.0, 3000.0, 14600.0, 3800.0)
    e += rectangle("FURNITURE", 10000.0, 12000.0, 11600.0, 12800.0)
    e += rectangle("FURNITURE", 1400.0, 12000.0, 2000.0, 14000.0)  # cabinet
    e += circle("FURNITURE", 4500.0, 11000.0, 600.0)  # round table
    e += text("FURNITURE", 4000.0, 10000.0, "meeting table")
    # Room names.
    e += text("ANNOTATION", 2000.0, 2500.0, "Office 1")
    e += text("ANNOTATION", 20000.0, 7000.0, "Hall")
    # A door symbol, inserted once.
    e += pairs(0, "INSERT", 8, "DOORS", 2, "DOOR", 10, 3500.0, 20, 5000.0, 30, 0.0)
    return e


def blocks():
    b = pairs(0, "BLOCK", 8, "0", 2, "DOOR", 70, 0, 10, 0.0, 20, 0.0, 30, 0.0, 3, "DOOR")
    b += line("WALLS", 0.0, 0.0, 1000.0, 0.0)
    b += line("WALLS", 0.0, 0.0, 0.0, 1000.0)
    return b + pairs(0, "ENDBLK", 8, "0")


def drawing():
    d = ["999", "office_floor_mm.dxf: maps/office_floor.xml in millimetres, written by "
         "tests/data/maps/make_office_dxf.py"]
    d += pairs(0, "SECTION", 2, "HEADER", 9, "$ACADVER", 1, "AC1015", 9, "$INSUNITS", 70, 4,
               0, "ENDSEC")
    d += pairs(0, "SECTION", 2, "TABLES", 0, "TABLE", 2, "LAYER", 70, len(LAYERS))
    for name in LAYERS:
        d += pairs(0, "LAYER", 2, name, 70, 0, 62, 7, 6, "CONTINUOUS")
    d += pairs(0, "ENDTAB", 0, "ENDSEC")
    d += pairs(0, "SECTION", 2, "BLOCKS") + blocks() + pairs(0, "ENDSEC")
    d += pairs(0, "SECTION", 2, "ENTITIES") + entities() + pairs(0, "ENDSEC")
    d += pairs(0, "EOF")
    return "\n".join(d) + "\n"


if __name__ == "__main__":
    with open("office_floor_mm.dxf", "w", encoding="ascii", newline="\n") as f:
        f.write(drawing())
