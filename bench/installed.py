"""Make the source tree start like an installed txtool before timing fresh interpreters.

Installing a wheel byte-compiles its modules, and the packages a benchmark compares against
(click, lxml, pydantic, rich) were compiled when they were installed. An editable install
compiles txtool on first import and caches the result, except where the cache is not written
(``PYTHONDONTWRITEBYTECODE=1``, a read-only tree): then every run would compile all of txtool
from source again (about 30 ms), which no installed copy does. The cache goes to the ignored
``__pycache__`` folders, as Python itself would write it.
"""

from __future__ import annotations

import compileall
import importlib.util
from pathlib import Path


def byte_compile() -> Path:
    """Compile the txtool package this interpreter imports; returns its folder."""
    spec = importlib.util.find_spec("txtool")
    if spec is None or spec.origin is None:
        raise SystemExit("txtool is not importable: pip install -e . first")
    package = Path(spec.origin).parent
    if not compileall.compile_dir(package, quiet=1):
        raise SystemExit(f"could not byte-compile {package}")
    return package
