"""tools/deposit/picture_colorbar.py: the bar shows in.deposit's own tilt colour map, beside the
picture, in degrees; a file that is not a picture gets a clear error."""
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import picture_colorbar  # noqa: E402

ROOT = os.environ.get("ELLIPSOID_DEP_ROOT",
                      os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
TOOL = os.path.join(ROOT, "tools", "deposit", "picture_colorbar.py")


def test_the_map_is_in_deposits():
    with open(os.path.join(ROOT, "examples", "deposit", "in.deposit")) as f:
        assert picture_colorbar.amap_words() in f.read()


def test_bar_beside_the_picture(tmp_path):
    picture = np.full((400, 500, 3), 0.5)
    path = str(tmp_path / "deposit.png")
    plt.imsave(path, picture)
    picture_colorbar.add_colorbar(path)
    image = plt.imread(path)[:, :, :3]
    assert image.shape[0] == 400 and image.shape[1] == 500 + 170
    np.testing.assert_allclose(image[200, 250], 0.5, atol=0.01)    # the picture unchanged
    # the bar spans 15-85 % of the height at 40-65 px right of the picture: blue (90 degrees)
    # at the top, yellow (45) in the middle, red (0) at the bottom
    column = 500 + 52
    np.testing.assert_allclose(image[64, column], (0, 0, 1), atol=0.05)
    np.testing.assert_allclose(image[200, column], (1, 1, 0), atol=0.05)
    np.testing.assert_allclose(image[336, column], (1, 0, 0), atol=0.05)


def test_not_a_picture(tmp_path):
    bad = tmp_path / "deposit.png"
    bad.write_text("not a png")
    out = subprocess.run([sys.executable, TOOL, str(bad)], capture_output=True, text=True)
    assert out.returncode != 0 and "cannot read" in out.stderr and "Traceback" not in out.stderr
