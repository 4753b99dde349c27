"""Open a ddafem run in ParaView, coloured for reading: blocks by |displacement|, contacts and
ties by state, the far field by |displacement|, in a 2D view at the last time step.

Untested here (no ParaView on the development machine): written against paraview.simple's
documented API (ParaView 5.9 and later).

    pvpython tools/paraview_open.py RUN_DIR                      # opens a window
    pvpython tools/paraview_open.py RUN_DIR --screenshot end.png # or saves a picture
    # ParaView GUI: View > Python Shell > Run Script, then in the shell:
    #   open_run("/path/to/RUN_DIR")

RUN_DIR/model.pvd holds every part at every snapshot time (part 0 blocks, 1 contacts, 2 far
field, 3 ties). This script opens each part's own series (blocks.pvd, contacts.pvd,
far_field.pvd, ties.pvd: the same files) so that each gets its own colouring. Colour ranges
cover every time step: |u| from 0 to its largest value over the run (the displacement since
t = 0, static settling included); contact states are categories (0 open, 1 slide, 2 lock,
3 bonded joint end).
"""
import os
import sys
import xml.etree.ElementTree as ET

from paraview.simple import (AnnotateTimeFilter, ColorBy, GetActiveViewOrCreate,
                             GetAnimationScene, GetColorTransferFunction, GetScalarBar,
                             PVDReader, Render, RenameSource, ResetCamera, SaveScreenshot, Show)

# File name prefix of each part's VTU files in model.pvd, in part order (app/run_outputs.cc).
PARTS = ("blocks", "contacts", "far_field", "ties")
STATES = (("0", "open", (0.75, 0.75, 0.75)), ("1", "slide", (1.0, 0.55, 0.0)),
          ("2", "lock", (0.1, 0.45, 0.85)), ("3", "bonded", (0.1, 0.6, 0.2)))


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
    """(0, largest |name|) over every time step of `source`."""
    largest = 0.0
    for t in time_steps(source):
        source.UpdatePipeline(t)
        data = source.CellData if association == "CELLS" else source.PointData
        if name in data.keys():
            largest = max(largest, data[name].GetRange(-1)[1])
    return 0.0, largest if largest > 0.0 else 1.0


def colour_by_magnitude(source, display, view, association, name, title):
    ColorBy(display, (association, name, "Magnitude"))
    lut = GetColorTransferFunction(name)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(*magnitude_range_over_time(source, association, name))
    display.SetScalarBarVisibility(view, True)
    GetScalarBar(lut, view).Title = title


def colour_by_state(display, view):
    ColorBy(display, ("CELLS", "state"))
    lut = GetColorTransferFunction("state")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = [text for value, label, _ in STATES for text in (value, label)]
    lut.IndexedColors = [c for _, _, colour in STATES for c in colour]
    display.SetScalarBarVisibility(view, True)
    display.PointSize = 5.0
    display.RenderPointsAsSpheres = 1


def open_run(run_dir):
    """Opens the parts of RUN_DIR in the active render view; returns the view."""
    view = GetActiveViewOrCreate("RenderView")
    sources = {}
    for name, path in parts_of(run_dir):
        source = PVDReader(FileName=path)
        RenameSource(name, source)
        display = Show(source, view)
        sources[name] = source
        if name == "blocks":
            colour_by_magnitude(source, display, view, "CELLS", "displacement",
                                "blocks |u| [m]")
            display.EdgeColor = [0.2, 0.2, 0.2]
            display.SetRepresentationType("Surface With Edges")
        elif name == "far_field":
            colour_by_magnitude(source, display, view, "POINTS", "displacement",
                                "far field |u| [m]")
        elif name in ("contacts", "ties"):
            colour_by_state(display, view)
    if "blocks" in sources:
        Show(AnnotateTimeFilter(Input=sources["blocks"]), view)
    view.InteractionMode = "2D"
    view.OrientationAxesVisibility = 0
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = max((t for s in sources.values() for t in time_steps(s)
                               if t is not None), default=0.0)
    ResetCamera(view)
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
