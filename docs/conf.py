"""Sphinx configuration of the rancf documentation (built by ``tests/test_docs_build.py``).

Build: ``python -m sphinx -W --keep-going -b html docs docs/_build/html`` (see
``docs/building.md``: why Sphinx, what each extension does, how long it takes).
"""

from __future__ import annotations

import sys
from pathlib import Path

import rancf

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

project = "rancf"
author = "the rancf developers"
copyright = "the rancf developers, MIT licence"  # noqa: A001 (Sphinx's name)
version = release = rancf.__version__

extensions = [
    "myst_parser",  # Markdown pages
    "sphinx.ext.autodoc",  # the Python API from the docstrings
    "sphinx.ext.napoleon",  # ... written in the numpydoc style
    "sphinx.ext.mathjax",
    "sphinxarg.ext",  # the CLI reference from the argparse parser
    "sphinx_gallery.gen_gallery",  # the examples gallery, executed at build time
    "scenario_reference",  # docs/_ext: the scenario keys from the typed models
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "examples"]  # examples: the gallery's sources
root_doc = "index"
smartquotes = False  # keys and values are quoted as TOML writes them: "pin", not “pin”

myst_enable_extensions = ["colon_fence", "deflist", "dollarmath"]
myst_heading_anchors = 4

# autodoc: documented members in source order; type hints in the description, not the signature
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "short"
autodoc_typehints_description_target = "documented_params"  # types of what the docstring names
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False

html_theme = "furo"
html_title = f"rancf {release}"
html_static_path = ["_static"]
html_logo = None
html_theme_options = {"navigation_with_keys": True}

sphinx_gallery_conf = {
    "examples_dirs": ["examples"],
    "gallery_dirs": ["gallery"],
    "filename_pattern": r"/plot_",  # every script is executed
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "gallery_order.GalleryOrder",
    "abort_on_example_error": False,  # every failing example is reported; -W fails the build
    "only_warn_on_example_error": False,
    "show_memory": False,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "min_reported_time": 0,
}
