#!/usr/bin/env python3
"""Every public C++ function has a doc comment and every public Python function of the module a docstring.

    check_docstrings.py --doxygen-xml build/docs/doxygen/xml [--python]   (PYTHONPATH=build/python)

C++: Doxygen's XML of include/plateball/*.h (docs/Doxyfile.in); every function, free or a public
member of a class, outside plateball::internal, needs a brief or detailed description (a `///`
comment, or the `//` comment block Doxygen reads as one). Python: every public function, class and
method of `plateball` (the wrappers and the pybind11 extension), every public class and every public
method (static ones included) of a class needs a docstring beyond the signature line pybind11 writes
itself; the classes' properties (the bound fields) are counted and their undocumented ones reported,
but not yet required. Prints every one that is missing; exit 1 when any required one is."""
import argparse
import inspect
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ET


def described(member):
    for tag in ("briefdescription", "detaileddescription"):
        node = member.find(tag)
        if node is not None and "".join(node.itertext()).strip():
            return True
    return False


def cpp_missing(xml_dir):
    missing, count = [], 0
    for path in sorted(pathlib.Path(xml_dir).glob("*.xml")):
        root = ET.parse(path).getroot()
        for compound in root.iter("compounddef"):
            if compound.get("kind") not in ("namespace", "class", "struct", "file"):
                continue
            name = compound.findtext("compoundname") or ""
            if "internal" in name.split("::") or (compound.get("kind") == "file" and not name.endswith(".h")):
                continue
            for member in compound.iter("memberdef"):
                if member.get("kind") != "function" or member.get("prot") != "public":
                    continue
                if compound.get("kind") == "file" and member.get("id", "").startswith("namespace"):
                    continue  # listed again under its namespace
                if member.findtext("definition", "").startswith("friend"):
                    continue
                count += 1
                if not described(member):
                    location = member.find("location")
                    where = f"{location.get('file')}:{location.get('line')}" if location is not None else path.name
                    missing.append(f"{where}: {name}::{member.findtext('name')}{member.findtext('argsstring')}")
    return count, sorted(set(missing))


def has_doc(obj):
    doc = inspect.getdoc(obj) or ""
    lines = [line for line in doc.splitlines() if line.strip()]
    name = getattr(obj, "__name__", "")
    # pybind11 writes "name(arg0: T) -> R" (and "Overloaded function." with numbered signatures).
    text = [line for line in lines if not line.startswith(f"{name}(") and not line.startswith("Overloaded function")
            and not (line[:1].isdigit() and f". {name}(" in line)]
    return bool(text)


def python_missing():
    """The module's public functions, classes and the classes' methods without a docstring, and its
    classes' properties: (count, missing, property count, properties missing)."""
    import plateball
    missing, count, properties, properties_missing = [], 0, 0, []
    for name, obj in sorted(vars(plateball).items()):
        if name.startswith("_") or inspect.ismodule(obj) or not callable(obj):
            continue
        count += 1
        kind = "class" if inspect.isclass(obj) else "function"
        if not has_doc(obj):
            missing.append(f"{kind} plateball.{name}")
        if kind == "function":
            continue
        for member_name, member in sorted(vars(obj).items()):
            if member_name.startswith("_"):
                continue
            if isinstance(member, property):
                properties += 1
                if not has_doc(member):
                    properties_missing.append(f"property plateball.{name}.{member_name}")
                continue
            function = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
            if callable(function):
                count += 1
                if not has_doc(function):
                    missing.append(f"method plateball.{name}.{member_name}")
    return count, missing, properties, properties_missing


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--doxygen-xml", type=pathlib.Path, required=True)
    parser.add_argument("--doxyfile", type=pathlib.Path, help="run doxygen with this file first (writes the XML)")
    parser.add_argument("--python", action="store_true", help="also check the Python module")
    args = parser.parse_args()
    if args.doxyfile:
        subprocess.run(["doxygen", str(args.doxyfile)], check=True, stdout=subprocess.DEVNULL)
    count, missing = cpp_missing(args.doxygen_xml)
    print(f"C++: {count} public functions, {len(missing)} without a doc comment")
    failed = bool(missing) or count == 0
    for line in missing:
        print(f"  missing: {line}")
    if args.python:
        count, py_missing, properties, properties_missing = python_missing()
        print(f"Python: {count} public functions, classes and methods, {len(py_missing)} without a docstring")
        for line in py_missing:
            print(f"  missing: {line}")
        print(f"Python: {properties} properties, {len(properties_missing)} without a docstring (not yet required)")
        failed = failed or bool(py_missing) or count == 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
