"""The topic folders of tools/ and their layers: the one list that puts them on the import path.

Each tool keeps its module name (`import deposit_run`), so the folders go on sys.path:
./ellipsoid-dep and tests/CMakeLists.txt run this file, which prints them as a PYTHONPATH; a
script run as a file (`python3 tools/study/study_doc.py`) finds its siblings by importing
this module first (its folder's parent on sys.path, then `import _paths`).
"""
import os
import sys

# topic: the topics its modules may import (besides their own); tools never import bench
LAYERS = {
    "deposit": (),                      # the runner, its report and checkpoints, remeasuring
    "containers": ("deposit",),         # the oedometer, the silo's wall stress
    "study": ("deposit",),              # the study's table, claims, verdicts, doc page
    "pores": ("deposit", "study"),      # the porous view and the flow solve
    "plot": ("deposit", "study"),       # the study's figures
}
FOLDERS = [os.path.join(os.path.dirname(os.path.abspath(__file__)), topic) for topic in LAYERS]

sys.path[1:1] = [folder for folder in FOLDERS if folder not in sys.path]

if __name__ == "__main__":
    print(os.pathsep.join(FOLDERS))
