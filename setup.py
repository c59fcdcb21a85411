"""The package's layout, the one part of the build that pyproject.toml cannot say.

The chapters live in ``book/`` beside ``src/`` and ship inside the package as
``trackbook/_book`` (``trackbook notebooks`` exports them from any installed copy), mapped here
rather than linked: pyproject.toml's package discovery takes one folder, and a second root
needs ``package_dir``. Everything else (metadata, dependencies, package data) is in
pyproject.toml.
"""

from setuptools import find_namespace_packages, setup

setup(
    # every folder of src/ (data/ too, as pyproject's own discovery finds it), and book/
    packages=[*find_namespace_packages("src", exclude=["*__pycache__"]), "trackbook._book"],
    package_dir={"": "src", "trackbook._book": "book"},
)
