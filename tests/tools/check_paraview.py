#!/usr/bin/python3
"""tools/paraview_open.py headless (CI test cli.paraview_pictures): ParaView 5.11's pvpython
under xvfb-run takes a screenshot of a run, and its pixels must show what the script promises:

- the near field framed: in the middle 60 % of the picture, blocks (pixels of the blocks'
  viridis map) cover at least a third, the far field (its cool-to-warm map) less than a tenth,
  so the blocks are neither a speck nor hidden under the far field;
- the blocks coloured (their map, not one flat colour of another map);
- one scalar bar per part, each in its own corner: the blocks' viridis bar bottom right, the far
  field's cool-to-warm bar bottom left (coupled runs), the contact states' orange, blue and
  green top right;
- the time written top left.

    check_paraview.py RUN_DIR SCREENSHOT.png [--coupled]
"""
import os
import subprocess
import sys
import time

import matplotlib
import numpy as np
from PIL import Image

TOOL = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                    "tools", "paraview_open.py")


def near(pixels, colours, within):
    """Mask of pixels within `within` (RGB distance) of any of `colours`."""
    d = np.min(np.linalg.norm(pixels[:, None, :] - colours[None, :, :], axis=2), axis=1)
    return d < within


def palette(name):
    return np.array(matplotlib.colormaps[name](np.linspace(0, 1, 64))[:, :3] * 255)


def region(image, x0, x1, y0, y1, step=3):
    h, w, _ = image.shape
    return image[int(y0 * h):int(y1 * h):step, int(x0 * w):int(x1 * w):step].reshape(-1, 3)


def screenshot(run_dir, png):
    """pvpython under xvfb-run, as docs/outputs.md gives it; two retries if the X server or
    pvpython dies at start-up. -noreset: by default Xvfb resets when its last client leaves,
    and pvpython, which opens the display, closes it and opens it again at start-up, then finds
    no server ("bad X server connection", SIGABRT; CI lost this test so, twice in a row). A
    failure prints the head of pvpython's stderr, where VTK's message is."""
    command = ["xvfb-run", "-a", "-s", "-screen 0 1600x1200x24 -noreset", "pvpython", TOOL,
               run_dir, "--screenshot", png]
    for attempt in range(3):
        r = subprocess.run(command, capture_output=True, text=True)
        if r.returncode == 0 and os.path.isfile(png):
            return
        print("pvpython exit %d (attempt %d): %s" % (r.returncode, attempt + 1, r.stderr[:1500]))
        time.sleep(2)
    sys.exit("check_paraview.py: no screenshot")


def main():
    run_dir, png = sys.argv[1], sys.argv[2]
    coupled = "--coupled" in sys.argv
    screenshot(run_dir, png)
    image = np.asarray(Image.open(png).convert("RGB"), dtype=float)
    viridis, warm = palette("viridis"), np.array(
        [[59, 76, 192], [221, 221, 221], [180, 4, 38], [144, 178, 254], [245, 156, 125]])
    middle = region(image, 0.2, 0.8, 0.2, 0.8)
    blocks = near(middle, viridis, 12)
    assert blocks.mean() > 1.0 / 3.0, "blocks cover %.0f %% of the middle" % (100 * blocks.mean())
    if coupled:
        far = near(middle, palette("coolwarm"), 12) & ~blocks
        assert far.mean() < 0.1, "far field covers %.0f %% of the middle" % (100 * far.mean())
    bottom_right = region(image, 0.86, 1.0, 0.6, 1.0, 1)
    assert near(bottom_right, viridis, 12).sum() > 500, "no blocks' bar bottom right"
    if coupled:
        bottom_left = region(image, 0.0, 0.14, 0.6, 1.0, 1)
        assert near(bottom_left, palette("coolwarm"), 20).sum() > 500, "no far-field bar"
    top_right = region(image, 0.86, 1.0, 0.0, 0.45, 1)
    states = np.array([[255, 140, 0], [25, 115, 217], [25, 153, 51]])
    for colour in states:
        assert near(top_right, colour[None, :], 30).sum() > 200, "state bar misses %s" % colour
    top_left = region(image, 0.0, 0.15, 0.0, 0.05, 1)
    assert (top_left.min(axis=1) > 200).sum() > 30, "no time text top left"
    print("paraview picture: blocks %.0f %% of the middle, bars in their corners"
          % (100 * blocks.mean()))


if __name__ == "__main__":
    main()
