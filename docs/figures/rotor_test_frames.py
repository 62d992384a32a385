"""Draws docs/figures/rotor_test_frames.png: the test frame T of a rig and the flight frame G
(nps.rig.case, docs/reference/rigs.md). Run: python docs/figures/rotor_test_frames.py"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Circle, FancyArrowPatch


def arrow(ax, start, end, color, text, offset=(0.0, 0.0), **kw):
    ax.add_patch(FancyArrowPatch(start, end, arrowstyle="-|>", mutation_scale=14, color=color, lw=1.8, **kw))
    ax.text(end[0] + offset[0], end[1] + offset[1], text, color=color, fontsize=11, ha="center", va="center")


def main(path=Path(__file__).with_name("rotor_test_frames.png")):
    fig, (side, top) = plt.subplots(1, 2, figsize=(12, 5.4))
    alpha = np.radians(12.0)  # shaft angle, exaggerated for the picture
    # side view: x_T to the right (downstream), z_T up
    disk = np.array([[-1.0, 1.0], [0.0, 0.0]])
    rot = np.array([[np.cos(alpha), np.sin(alpha)], [-np.sin(alpha), np.cos(alpha)]])  # disk tilted aft
    d = rot @ disk
    side.plot(d[0], d[1], "k", lw=4)
    axis = np.array([np.sin(alpha), np.cos(alpha)])
    side.plot([0, 0.9 * axis[0]], [0, 0.9 * axis[1]], "k--", lw=1)
    side.text(0.95 * axis[0] + 0.08, 0.9 * axis[1], "shaft (thrust axis)", fontsize=9)
    side.annotate("", xy=(0.0, 0.55), xytext=0.55 * axis, arrowprops=dict(arrowstyle="<->", lw=0.8))
    side.text(-0.45, 0.5, "α_s > 0\n(aft tilt)", fontsize=9)
    arrow(side, (0, 0), (0.8, 0), "tab:blue", "x_T", (0.12, 0))
    arrow(side, (0, 0), (0, 0.8), "tab:blue", "z_T", (0, 0.1))
    arrow(side, (0, -0.05), (-0.8, -0.05), "tab:red", "x_G", (-0.12, 0))
    for y in (-0.35, 0.25, 0.85):
        arrow(side, (-1.9, y), (-1.3, y), "tab:gray", "")
    side.text(-1.6, 1.05, "tunnel flow V", color="tab:gray", ha="center")
    arrow(side, (1.5, -0.6), (0.9, -0.6), "tab:red", "")
    side.text(1.05, -0.45, "flight frame: the rotor flies at V along +x_G", color="tab:red", ha="center", fontsize=9)
    side.plot(np.linspace(-1.6, 1.6, 9), np.full(9, -1.1), "o", color="tab:green", ms=5)
    side.text(0.0, -1.3, "microphones fixed to the hub (T coordinates), e.g. z_T = −2.215 m for HART-II",
              color="tab:green", ha="center", fontsize=9)
    side.set_title("side view: x_T downstream, z_T up (vertical)", fontsize=11)
    side.set_xlim(-2.1, 2.1), side.set_ylim(-1.45, 1.25), side.set_aspect("equal"), side.axis("off")
    # top view: x_T to the right, y_T up the page (z_T out of the page)
    top.add_patch(Circle((0, 0), 1.0, fill=False, lw=2))
    top.annotate("", xy=(-0.55, 0.84), xytext=(0.55, 0.84), arrowprops=dict(arrowstyle="-|>", lw=1.5))
    top.text(0.0, 1.08, "advancing blade (counterclockwise from above)", ha="center", fontsize=9)
    arrow(top, (0, 0), (0.8, 0), "tab:blue", "x_T", (0.12, 0))
    arrow(top, (0, 0), (0, 0.8), "tab:blue", "y_T", (0.12, 0.05))
    arrow(top, (0, -0.05), (-0.8, -0.05), "tab:red", "x_G", (-0.12, 0))
    arrow(top, (-0.05, 0), (-0.05, -0.8), "tab:red", "y_G", (-0.14, 0))
    top.text(0.0, -0.06, "⊙ z_T = z_G", fontsize=9, ha="left", va="top")
    for y in (-0.6, 0.0, 0.6):
        arrow(top, (-1.9, y), (-1.35, y), "tab:gray", "")
    top.text(-1.62, 0.85, "tunnel flow", color="tab:gray", ha="center")
    top.text(0.0, -1.3, "G = T turned 180° about z:  (x_G, y_G, z_G) = (−x_T, −y_T, z_T)", ha="center", fontsize=10)
    top.set_title("top view: y_T = z_T × x_T (advancing side)", fontsize=11)
    top.set_xlim(-2.1, 2.1), top.set_ylim(-1.45, 1.25), top.set_aspect("equal"), top.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
