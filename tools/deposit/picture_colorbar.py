#!/usr/bin/env python3
"""A colour bar for the deposit's picture (in.deposit's dump image, Fig. 4 of the paper).

    ./ellipsoid-dep python tools/deposit/picture_colorbar.py deposit.png [--out with_bar.png]

in.deposit colours each particle by the tilt of its long axis from the vertical (compute
orient/histo's per-atom angle, 0 to pi/2) with dump_modify's continuous map
`amap 0.0 1.5708 cf 0.0 3 min red 0.5 yellow max blue`: LAMMPS interpolates linearly in RGB
between the colours at the fractions 0, 0.5 and 1 of the range. This tool draws the same map
as a bar labelled in degrees beside the picture (in place unless --out is given).
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap, Normalize  # noqa: E402

# (fraction of the range, LAMMPS colour name, its RGB in LAMMPS's colour table)
TILT_MAP = ((0.0, "red", (1.0, 0.0, 0.0)), (0.5, "yellow", (1.0, 1.0, 0.0)),
            (1.0, "blue", (0.0, 0.0, 1.0)))
TILT_RANGE = (0.0, 1.5708)    # radians, as in.deposit's amap


def amap_words():
    """the dump_modify words of the map, as in.deposit writes them"""
    names = {0.0: "min", 1.0: "max"}
    points = " ".join("%s %s" % (names.get(f, "%g" % f), colour) for f, colour, _ in TILT_MAP)
    return "amap %.1f %.4f cf 0.0 %d %s" % (TILT_RANGE + (len(TILT_MAP), points))


def add_colorbar(path, out=None):
    image = plt.imread(path)
    height, width = image.shape[:2]
    dpi = 100
    fig = plt.figure(figsize=((width + 170) / dpi, height / dpi), dpi=dpi)
    ax = fig.add_axes([0, 0, width / (width + 170), 1])
    ax.imshow(image)
    ax.axis("off")
    bar = fig.add_axes([(width + 40) / (width + 170), 0.15, 25 / (width + 170), 0.7])
    cmap = LinearSegmentedColormap.from_list("tilt", [(f, rgb) for f, _, rgb in TILT_MAP])
    scale = plt.cm.ScalarMappable(norm=Normalize(0, 90), cmap=cmap)
    cb = fig.colorbar(scale, cax=bar, ticks=[0, 15, 30, 45, 60, 75, 90])
    cb.set_label("tilt of the long axis from the vertical (degrees)", fontsize=10)
    fig.savefig(out or path, dpi=dpi, facecolor="white")
    plt.close(fig)
    return out or path


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("picture", help="the PNG that in.deposit's dump image wrote")
    ap.add_argument("--out", help="write here instead of in place")
    args = ap.parse_args(argv)
    try:
        print("picture_colorbar: wrote %s" % add_colorbar(args.picture, args.out))
    except (OSError, SyntaxError, ValueError) as e:
        sys.exit("picture_colorbar: ERROR: cannot read %s as a PNG picture: %s"
                 % (args.picture, e))


if __name__ == "__main__":
    main()
