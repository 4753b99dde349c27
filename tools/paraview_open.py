"""Open a ddafem run in ParaView, coloured for reading: blocks by |displacement|, contacts and
ties by state, the far field by |displacement|, in a 2D view at the last time step, framed on
the blocks (the near field; the far field around it), the blocks drawn above the far field, one
scalar bar per part in its own corner, the time in the top left.

Tested headless with Debian's ParaView 5.11 (pvpython under xvfb-run, Xvfb -noreset) by
tests/tools/check_paraview.py (CI test cli.paraview_pictures): the picture's pixels.

    pvpython tools/paraview_open.py RUN_DIR                      # opens a window
    pvpython tools/paraview_open.py RUN_DIR --screenshot end.png # or saves a picture
    # ParaView GUI: View > Python Shell > Run Script, then in the shell:
    #   open_run("/path/to/RUN_DIR")

RUN_DIR/model.pvd holds every part at every snapshot time (part 0 blocks, 1 contacts, 2 far
field, 3 ties, 4 bolts). This script opens each part's own series (blocks.pvd, contacts.pvd,
far_field.pvd, ties.pvd: the same files) so that each gets its own colouring. Colour ranges
cover every time step: |u| from 0 to its largest value over the run (the displacement since
t = 0, static settling included); contact states are categories (0 open, 1 slide, 2 lock,
3 bonded joint end).
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
from paraview import servermanager
from vtk.numpy_interface import dataset_adapter as dsa

from paraview.simple import (AnnotateTimeFilter, ColorBy, GetActiveViewOrCreate,
                             GetAnimationScene, GetColorTransferFunction, GetScalarBar,
                             PVDReader, Render, RenameSource, ResetCamera, SaveScreenshot, Show,
                             Transform)

# File name prefix of each part's VTU files in model.pvd, in part order (app/run/run_outputs.cc).
PARTS = ("blocks", "contacts", "far_field", "ties", "bolts")
STATES = (("0", "open", (0.75, 0.75, 0.75)), ("1", "slide", (1.0, 0.55, 0.0)),
          ("2", "lock", (0.1, 0.45, 0.85)), ("3", "bonded", (0.1, 0.6, 0.2)))
# Each part's colour map and the corner of its scalar bar (normalised view coordinates of the
# bar's lower left corner), so that no two bars or titles overlap and none covers the blocks'
# middle: blocks right, far field left, states top right; the time stays top left.
MAPS = {"blocks": ("Viridis (matplotlib)", (0.89, 0.05)),
        "far_field": ("Cool to Warm", (0.02, 0.05)),
        "state": (None, (0.89, 0.62))}
# Depth of each part [m along z, towards the viewer]: the blocks above the far field, the
# contacts and ties above the blocks.
DEPTH = {"far_field": -1.0, "blocks": 0.0, "contacts": 0.5, "ties": 0.5, "bolts": 0.6}


def parts_of(run_dir):
    """The parts present in RUN_DIR/model.pvd, as (name, path of the part's own PVD)."""
    root = ET.parse(os.path.join(run_dir, "model.pvd")).getroot()
    numbers = sorted({int(d.get("part", "0")) for d in root.findall("./Collection/DataSet")})
    parts = []
    for number in numbers:
        name = PARTS[number] if number < len(PARTS) else "part_%d" % number
        path = os.path.join(run_dir, name + ".pvd")
        if os.path.isfile(path):
            parts.append((name, path))
    return parts


def time_steps(source):
    values = source.TimestepValues
    if values is None:
        return [None]
    return list(values) if hasattr(values, "__len__") else [values]


def magnitude_range_over_time(source, association, name):
    """(0, the 98th percentile of |name| at the time step where it is largest): a block that
    fell metres does not turn every other block the colour of zero."""
    largest = 0.0
    for t in time_steps(source):
        source.UpdatePipeline(t)
        data = dsa.WrapDataObject(servermanager.Fetch(source))
        arrays = data.CellData if association == "CELLS" else data.PointData
        if name in arrays.keys():
            for block in (arrays[name].Arrays if hasattr(arrays[name], "Arrays")
                          else [arrays[name]]):
                values = np.linalg.norm(np.asarray(block).reshape(len(block), -1), axis=1)
                if values.size:
                    largest = max(largest, float(np.percentile(values, 98)))
    return 0.0, largest if largest > 0.0 else 1.0


def place_bar(lut, view, part, title):
    """The scalar bar of `lut` in its part's corner, small, with a one-line title."""
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.WindowLocation = "Any Location"
    bar.Position = list(MAPS[part][1])
    bar.ScalarBarLength = 0.3
    bar.TitleFontSize = 12
    bar.LabelFontSize = 11
    bar.TitleJustification = "Left"
    return bar


def colour_by_magnitude(source, display, view, association, name, part, title):
    """Colours `display` by |name| with its own map (a per-part array name), over every time."""
    ColorBy(display, (association, name, "Magnitude"), separate=True)
    lut = GetColorTransferFunction(name, display, separate=True)
    lut.ApplyPreset(MAPS[part][0], True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(*magnitude_range_over_time(source, association, name))
    display.SetScalarBarVisibility(view, True)
    place_bar(lut, view, part, title)


def colour_by_state(display, view, title):
    ColorBy(display, ("CELLS", "state"))
    lut = GetColorTransferFunction("state")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = [text for value, label, _ in STATES for text in (value, label)]
    lut.IndexedColors = [c for _, _, colour in STATES for c in colour]
    display.SetScalarBarVisibility(view, True)
    place_bar(lut, view, "state", title)
    display.PointSize = 4.0
    display.RenderPointsAsSpheres = 1


def frame_on(view, bounds, margin=0.08):
    """A parallel 2D camera on bounds (xmin, xmax, ymin, ymax) with a margin."""
    cx, cy = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])
    half = 0.5 * max(bounds[1] - bounds[0], bounds[3] - bounds[2]) * (1.0 + 2.0 * margin)
    view.CameraParallelProjection = 1
    view.CameraPosition = [cx, cy, 100.0 * half]
    view.CameraFocalPoint = [cx, cy, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = half


def open_run(run_dir):
    """Opens the parts of RUN_DIR in the active render view; returns the view."""
    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [1600, 1200]
    sources = {}
    titles = {"contacts": "contact state", "ties": "contact and tie state"}
    for name, path in parts_of(run_dir):
        reader = PVDReader(FileName=path)
        RenameSource(name, reader)
        shown = Transform(Input=reader)
        shown.Transform.Translate = [0.0, 0.0, DEPTH.get(name, 0.0)]
        RenameSource(name + " (drawn at z = %g)" % DEPTH.get(name, 0.0), shown)
        display = Show(shown, view)
        display.Ambient, display.Diffuse = 1.0, 0.0  # a flat 2D picture: the maps' own colours
        display.SetScalarBarVisibility(view, False)  # of the shared map Show picked
        ColorBy(display, ("POINTS", None))  # each part's own colouring below
        sources[name] = reader
        if name == "blocks":
            colour_by_magnitude(reader, display, view, "CELLS", "displacement", "blocks",
                                "blocks |u| [m]")
            display.EdgeColor = [0.2, 0.2, 0.2]
            display.SetRepresentationType("Surface With Edges")
        elif name == "far_field":
            colour_by_magnitude(reader, display, view, "POINTS", "displacement", "far_field",
                                "far field |u| [m]")
        elif name in ("contacts", "ties"):
            colour_by_state(display, view, titles["ties" if "ties" in sources else name])
        elif name == "bolts":  # black polylines, head to anchor through the crossings
            display.AmbientColor = display.DiffuseColor = [0.0, 0.0, 0.0]
            display.LineWidth = 3.0
    if "blocks" in sources:
        time = Show(AnnotateTimeFilter(Input=sources["blocks"], Format="t = {time:.4f} s"), view)
        time.WindowLocation = "Upper Left Corner"
        time.FontSize = 14
    view.InteractionMode = "2D"
    view.OrientationAxesVisibility = 0
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = max((t for s in sources.values() for t in time_steps(s)
                               if t is not None), default=0.0)
    ResetCamera(view)
    if "blocks" in sources:
        sources["blocks"].UpdatePipeline(scene.AnimationTime)
        frame_on(view, sources["blocks"].GetDataInformation().GetBounds())
    Render(view)
    return view


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return
    view = open_run(argv[0])
    if len(argv) >= 3 and argv[1] == "--screenshot":
        SaveScreenshot(argv[2], view, ImageResolution=[1600, 1200])
        print("wrote %s" % argv[2])
        return
    from paraview.simple import Interact
    Interact(view)


if __name__ == "__main__" and len(sys.argv) > 1:
    main(sys.argv[1:])
