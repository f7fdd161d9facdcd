"""The package around the extension: the interpreter check of __init__.py and the type stubs."""
import inspect
import pathlib
import shutil
import subprocess
import sys

import plateball as pb

PACKAGE = pathlib.Path(pb.__file__).resolve().parent
SOURCE = pathlib.Path(__file__).resolve().parents[1] / "plateball"


def test_build_info_names_this_interpreter():
    from plateball import _build_info
    assert _build_info.PYTHON_VERSION.split(".")[:2] == [str(v) for v in sys.version_info[:2]]


def test_other_python_version_names_the_interpreter_it_needs(tmp_path):
    """A copy of the package whose build info says Python 2.7 (a version this interpreter is not):
    the import must fail with an ImportError naming that interpreter, before loading the extension."""
    copy = tmp_path / "plateball"
    shutil.copytree(PACKAGE, copy)
    (copy / "_build_info.py").write_text('PYTHON_EXECUTABLE = "/opt/python2.7/bin/python"\nPYTHON_VERSION = "2.7.18"\n')
    result = subprocess.run([sys.executable, "-c", "import plateball"], cwd=tmp_path, capture_output=True, text=True,
                            env={"PYTHONPATH": str(tmp_path), "PYTHONDONTWRITEBYTECODE": "1"})
    assert result.returncode != 0
    last = result.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: plateball: the compiled module was built for /opt/python2.7/bin/python "
                           "(Python 2.7.18), this interpreter is " + sys.executable), last
    assert "the Python versions differ" in last


def test_stubs_cover_every_public_name():
    """The committed stubs (python/plateball/*.pyi) declare every public name of the built module."""
    stubs = (SOURCE / "_plateball.pyi").read_text() + (SOURCE / "__init__.pyi").read_text()
    names = [n for n in dir(pb) if not n.startswith("_") and not inspect.ismodule(getattr(pb, n))]
    missing = [n for n in names if f"class {n}" not in stubs and f"def {n}(" not in stubs and f"{n}:" not in stubs]
    assert not missing, f"names without a stub (regenerate with tools/python/make_stubs.py): {missing}"
    assert (SOURCE / "py.typed").exists()
