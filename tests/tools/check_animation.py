#!/usr/bin/python3
"""tools/animate.py on a run (CI test cli.animate_small_tunnel): the GIF has one frame per
snapshot of blocks.pvd, the frames change (the cursor and the blocks move), and the near-field
panel is coloured (the viridis blocks, many distinct colours, not a blank or one-colour plot).

    check_animation.py RUN_DIR
"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import matplotlib
import numpy as np
from PIL import Image


def main():
    run_dir = sys.argv[1]
    tool = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))), "tools", "animate.py")
    gif = os.path.join(run_dir, "animation.gif")
    subprocess.run([sys.executable, tool, run_dir, "--gif"], check=True)
    snapshots = len(ET.parse(os.path.join(run_dir, "blocks.pvd")).getroot()
                    .findall("./Collection/DataSet"))
    image = Image.open(gif)
    assert image.n_frames == snapshots, (image.n_frames, snapshots)
    frames = []
    for k in (0, image.n_frames - 1):
        image.seek(k)
        frames.append(np.asarray(image.convert("RGB"), dtype=int))
    assert np.abs(frames[0] - frames[1]).sum() > 0, "the first and last frames are the same"
    width = frames[1].shape[1]
    panel = frames[1][:, : width // 2].reshape(-1, 3)[::5]
    # Pixels of the blocks: within a few levels of a colour of the viridis map (the GIF's
    # palette quantises them), not the white, black and grey of axes, text and edges.
    viridis = np.array(matplotlib.colormaps["viridis"](np.linspace(0, 1, 256))[:, :3] * 255)
    distance = np.min(np.linalg.norm(panel[:, None, :] - viridis[None, :, :], axis=2), axis=1)
    grey = (panel.max(axis=1) - panel.min(axis=1)) < 20
    blocks = panel[(distance < 12) & ~grey]
    colours = {tuple(c) for c in blocks}
    assert len(blocks) > 0.2 * len(panel) and len(colours) >= 5, (len(blocks), len(colours))
    print("animation: %d frames, %d block colours in the near-field panel"
          % (image.n_frames, len(colours)))


if __name__ == "__main__":
    main()
