"""Jupyter's settings for reading the book in JupyterLab (`make lab`).

scripts/lab.py puts this folder first on JUPYTER_CONFIG_PATH; a plain `jupyter lab` does not read it.
- A chapter (notebooks/NN_slug.ipynb, paired with its percent script) is saved without outputs:
  the pre-save hook `clean_chapter` of scripts/lab.py.
- The extension in labextensions/skilllib-book: citations and figure references as on the site.
"""

import importlib.util
import sys
from pathlib import Path

c = get_config()  # noqa: F821  (given by Jupyter when it reads this file)

HERE = Path(__file__).resolve().parent
# scripts/lab.py, imported once under its own name (the server and JupyterLab both read this file)
_lab = sys.modules.get("skilllib_book_lab")
if _lab is None:
    _spec = importlib.util.spec_from_file_location("skilllib_book_lab", HERE.parent / "scripts" / "lab.py")
    _lab = sys.modules["skilllib_book_lab"] = importlib.util.module_from_spec(_spec)
    _spec.loader.exec_module(_lab)

c.ContentsManager.pre_save_hook = _lab.clean_chapter
c.LabApp.extra_labextensions_path = [str(HERE / "labextensions")]
