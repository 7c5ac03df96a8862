#!/usr/bin/python3
"""Draws docs/figures/pointing_model.svg: the terms of the pointing model (SPEC.md §3.1) for
docs/rk-calibrate-pointing.md. Angles are exaggerated to be visible. Needs matplotlib (Debian's
/usr/bin/python3 has it):   /usr/bin/python3 docs/figures/pointing_model.py
"""
import math
import os

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "rangekit"  # the same file from the same script
matplotlib.rcParams["svg.fonttype"] = "none"      # text stays text
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Arc, FancyArrowPatch, Polygon, Rectangle  # noqa: E402

BLUE, RED, GREY = "#1f5fa8", "#c0392b", "#7f7f7f"


def arrow(ax, p0, p1, color="k", lw=1.6, ls="-"):
    ax.add_patch(FancyArrowPatch(p0, p1, arrowstyle="-|>", mutation_scale=12, color=color, lw=lw, linestyle=ls))


def rot(v, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def frame(ax, title):
    ax.set_aspect("equal")
    ax.set_xlim(-1.25, 1.25)
    ax.set_ylim(-1.15, 1.3)
    ax.axis("off")
    ax.set_title(title, fontsize=10)


def top_view(ax):
    frame(ax, "a) Top view: azimuth zero")
    arrow(ax, (0, 0), (0, 1.05), GREY)
    ax.text(0.04, 1.08, "true north", color=GREY, fontsize=8)
    off = 50.0  # az_offset, clockwise from north
    z = rot((0, 1.0), -off)
    arrow(ax, (0, 0), z, BLUE, ls="--")
    ax.text(z[0] + 0.03, z[1] - 0.02, "logged A = 0", color=BLUE, fontsize=8)
    ax.add_patch(Arc((0, 0), 0.7, 0.7, theta1=90 - off, theta2=90, color=RED, lw=1.5))
    ax.text(0.1, 0.42, "az_offset", color=RED, fontsize=9)
    a = 75.0  # logged A
    b = rot((0, 0.95), -(off + a))
    arrow(ax, (0, 0), b, "k", lw=2.2)
    ax.text(b[0] - 0.05, b[1] - 0.16, "boresight", fontsize=8)
    ax.add_patch(Arc((0, 0), 1.1, 1.1, theta1=90 - off - a, theta2=90 - off, color=BLUE, lw=1.2))
    ax.text(0.58, -0.05, "A (logged)", color=BLUE, fontsize=8)
    ax.text(-1.2, -1.1, "true azimuth = A + az_offset\n(anywhere in 0-360°)", fontsize=8)


def tilt_view(ax):
    frame(ax, "b) From the south: tilt_east")
    ax.plot([-1.1, 1.1], [-0.7, -0.7], color=GREY, lw=1)
    ax.text(-1.1, -0.85, "level", color=GREY, fontsize=8)
    ax.text(0.95, -0.85, "east", color=GREY, fontsize=8)
    arrow(ax, (0, -0.7), (0, 1.0), GREY, ls="--")
    ax.text(-0.35, 1.08, "vertical", color=GREY, fontsize=8)
    t = 14.0
    top = rot((0, 1.7), -t)
    arrow(ax, (0, -0.7), (top[0], -0.7 + top[1]), BLUE, lw=2.2)
    ax.text(top[0] + 0.03, -0.7 + top[1] - 0.05, "azimuth axis", color=BLUE, fontsize=8)
    ax.add_patch(Arc((0, -0.7), 1.6, 1.6, theta1=90 - t, theta2=90, color=RED, lw=1.5))
    ax.text(0.12, 0.2, "tilt_east", color=RED, fontsize=9)
    ax.add_patch(Polygon([(-0.35, -0.7), (0.35, -0.7), (0.25, -0.95), (-0.25, -0.95)], closed=True, color="#dddddd"))
    ax.text(-1.2, -1.12, "tilt_north: the same seen from the east\n(top of the axis toward north)", fontsize=8)


def el_axis_view(ax):
    frame(ax, "c) From behind: el_axis_tilt")
    ax.plot([-1.1, 1.1], [0, 0], color=GREY, lw=1, ls="--")
    ax.text(0.22, 0.07, "square to the\nazimuth axis", color=GREY, fontsize=8)
    t = 12.0
    r = rot((1.0, 0), -t)
    ax.plot([-r[0], r[0]], [-r[1], r[1]], color=BLUE, lw=2.4)
    ax.text(r[0] - 0.45, r[1] - 0.17, "elevation axis", color=BLUE, fontsize=8)
    ax.add_patch(Arc((0, 0), 1.5, 1.5, theta1=-t, theta2=0, color=RED, lw=1.5))
    ax.text(0.78, -0.02, "el_axis_tilt", color=RED, fontsize=9, va="top", ha="left")
    arrow(ax, (0, -1.0), (0, 0.95), GREY)
    ax.text(0.04, 0.95, "azimuth axis", color=GREY, fontsize=8)
    ax.add_patch(Rectangle((-0.2, -0.2), 0.4, 0.4, fill=False, color="k", lw=1.2))
    ax.text(-1.2, -1.1, "positive lowers the right-hand end\n(seen from behind the boresight)", fontsize=8)


def mount_view(ax):
    frame(ax, "d) Camera on the turret (from behind)")
    ax.plot([-1.0, 1.0], [0, 0], color=GREY, lw=0.8)
    ax.plot([0, 0], [-0.9, 0.9], color=GREY, lw=0.8)
    ax.plot(0, 0, "+", color="k", ms=12, mew=2)
    ax.text(-0.52, -0.16, "boresight b", fontsize=8)
    oa = (0.35, 0.25)
    ax.plot(*oa, "o", color=RED, ms=6)
    arrow(ax, (0, 0), oa, RED)
    ax.text(oa[0] + 0.06, oa[1] + 0.04, "optical axis:\nyaw right, pitch up", color=RED, fontsize=8)
    roll = -15.0  # image x turned toward image down (clockwise on the page)
    w, h = 0.9, 0.7
    corners = [rot(p, roll) for p in [(-w, -h), (w, -h), (w, h), (-w, h)]]
    ax.add_patch(Polygon([(c[0] + oa[0] * 0.3, c[1] + oa[1] * 0.3) for c in corners], closed=True, fill=False,
                         color=BLUE, lw=1.4))
    x = rot((0.55, 0), roll)
    arrow(ax, (0, 0), x, BLUE)
    ax.text(x[0] - 0.1, x[1] - 0.17, "image x", color=BLUE, fontsize=8)
    ax.text(-1.2, -1.1, "roll turns image x toward image down;\nmount angles live in the camera model", fontsize=8)


def main():
    fig, axes = plt.subplots(1, 4, figsize=(14, 3.9))
    top_view(axes[0])
    tilt_view(axes[1])
    el_axis_view(axes[2])
    mount_view(axes[3])
    fig.suptitle("R_enu_cam = Ry(tilt_east) · Rx(-tilt_north) · Rz(-(A + az_offset)) · Ry(el_axis_tilt) · Rx(E) · C"
                 " · Ry(yaw) · Rx(pitch) · Rz(roll)   (SPEC.md §3.1; angles exaggerated)", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "pointing_model.svg")
    fig.savefig(out, metadata={"Date": None})
    print(out)


if __name__ == "__main__":
    main()
