"""Installation into a prefix laid out like a ROS 2 install (a venv is one).

What goes where is what rclpy, ``ros2 interface`` and the ament index look for:
``lib/`` the shared libraries, ``site-packages/<pkg>`` the Python package,
``share/<pkg>/{msg,srv,action}`` the definitions and type descriptions (one per definition
file, as upstream installs them), ``include/<pkg>`` the headers,
``share/ament_index/resource_index/{packages,rosidl_interfaces}/<pkg>`` the index entries.
A stamp records the definitions' fingerprint, so an up-to-date package is never rebuilt.
"""

from __future__ import annotations

import json
import shutil
import sysconfig
from pathlib import Path

from amiro.ros2.msgbuild.generate import GeneratedSources
from amiro.ros2.msgbuild.package import InterfacePackage

STAMP = "amiro_msgbuild.json"
HEADER_TREES = ("c", "fastrtps_c", "introspection_c")


def site_packages(prefix: Path) -> Path:
    return Path(sysconfig.get_path("platlib", vars={"base": str(prefix), "platbase": str(prefix)}))


def stamp_path(package: InterfacePackage, prefix: Path) -> Path:
    return prefix / "share" / package.name / STAMP


def is_current(package: InterfacePackage, prefix: Path) -> bool:
    """Whether ``prefix`` holds this package built from these very definitions."""
    try:
        stamp = json.loads(stamp_path(package, prefix).read_text("utf-8"))
    except (OSError, ValueError):
        return False
    return (
        isinstance(stamp, dict)
        and stamp.get("fingerprint") == package.fingerprint
        and all(
            (site_packages(prefix) / package.name / kind / "__init__.py").is_file()
            for kind in package.kinds
        )
    )


def _copy(src: Path, dst: Path) -> None:
    dst.parent.mkdir(parents=True, exist_ok=True)
    shutil.copy2(src, dst)


def install(gen: GeneratedSources, stage: Path, prefix: Path) -> list[Path]:
    """Copy the staged build and the definitions into ``prefix``; returns the libraries."""
    pkg = gen.package
    libs = sorted((stage / "lib").glob("*.so"))
    for lib in libs:
        _copy(lib, prefix / "lib" / lib.name)
    py_dst = site_packages(prefix) / pkg.name
    py_dst.mkdir(parents=True, exist_ok=True)
    (py_dst / "__init__.py").touch()
    for kind in pkg.kinds:
        for module in (gen.tree("py") / pkg.name / kind).glob("*.py"):
            _copy(module, py_dst / kind / module.name)
    for ext in (stage / pkg.name).glob("*.so"):
        _copy(ext, py_dst / ext.name)
    share = prefix / "share" / pkg.name
    interfaces: list[str] = []
    for rel in pkg.interfaces:
        _copy(pkg.source_dir / rel, share / rel)
        interfaces += [rel.with_suffix(".idl").as_posix(), rel.as_posix()]
    stems = {rel.stem for rel in pkg.interfaces}
    for generated in (*gen.idl_files, *gen.type_descriptions):
        if generated.stem in stems:
            _copy(generated, share / generated.parent.name / generated.name)
    for tree in HEADER_TREES:
        root = gen.tree(tree)
        for header in root.rglob("*.h"):
            _copy(header, prefix / "include" / pkg.name / header.relative_to(root))
    index = prefix / "share" / "ament_index" / "resource_index"
    (index / "packages").mkdir(parents=True, exist_ok=True)
    (index / "packages" / pkg.name).touch()
    (index / "rosidl_interfaces").mkdir(parents=True, exist_ok=True)
    (index / "rosidl_interfaces" / pkg.name).write_text("\n".join(sorted(interfaces)), "utf-8")
    stamp = {"fingerprint": pkg.fingerprint, "dependencies": list(pkg.dependencies)}
    stamp_path(pkg, prefix).write_text(json.dumps(stamp), "utf-8")
    return [prefix / "lib" / lib.name for lib in libs]
