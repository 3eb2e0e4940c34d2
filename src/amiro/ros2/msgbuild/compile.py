"""Compilation: the shared libraries ament would build for an interface package, with gcc.

The targets and their link lines mirror what ``rosidl_generate_interfaces`` produces, so the
result is laid out and named like an upstream package: ``lib<pkg>__rosidl_generator_c.so``,
one library per type support, ``lib<pkg>__rosidl_generator_py.so`` and the Python extension
modules ``<pkg>_s__<typesupport>``.  Libraries find each other through ``$ORIGIN``.
"""

from __future__ import annotations

import shutil
import subprocess
import sysconfig
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from amiro.core.config import ConfigError
from amiro.ros2.msgbuild.generate import TYPESUPPORTS, GeneratedSources

EXT_SUFFIX = str(sysconfig.get_config_var("EXT_SUFFIX"))


@dataclass(frozen=True)
class Target:
    """One shared object: what it is built from and what it links against."""

    output: Path
    sources: tuple[Path, ...]
    includes: tuple[Path, ...]
    libraries: tuple[str, ...]
    rpath: str = "$ORIGIN"

    @property
    def cxx(self) -> bool:
        return any(s.suffix == ".cpp" for s in self.sources)


def _lib(package: str, kind: str) -> str:
    return f"{package}__{kind}"


def plan_targets(gen: GeneratedSources, ros_prefix: Path, out_dir: Path) -> list[Target]:
    """Every target of the package in dependency order; ``out_dir`` gets lib/ and <package>/."""
    pkg, deps = gen.package.name, gen.package.dependencies
    ros_includes = (ros_prefix / "include", *sorted((ros_prefix / "include").iterdir()))
    c_tree = gen.tree("c")

    def target(name: str, sources: list[Path], trees: tuple[Path, ...], libs: list[str]) -> Target:
        return Target(
            out_dir / "lib" / f"lib{name}.so",
            tuple(sources),
            (*trees, *ros_includes),
            (*libs, "rosidl_runtime_c", "rcutils"),
        )

    generator_c = target(
        _lib(pkg, "rosidl_generator_c"),
        gen.sources("c", "detail/*.c"),
        (c_tree,),
        [_lib(d, "rosidl_generator_c") for d in deps],
    )
    fastrtps_c = target(
        _lib(pkg, "rosidl_typesupport_fastrtps_c"),
        gen.sources("fastrtps_c", "detail/*.cpp"),
        (c_tree, gen.tree("fastrtps_c")),
        [
            _lib(pkg, "rosidl_generator_c"),
            *(_lib(d, "rosidl_typesupport_fastrtps_c") for d in deps),
            "rosidl_typesupport_fastrtps_c",
            "rosidl_typesupport_fastrtps_cpp",
            "fastcdr",
            "rmw",
        ],
    )
    introspection_c = target(
        _lib(pkg, "rosidl_typesupport_introspection_c"),
        gen.sources("introspection_c", "detail/*.c"),
        (c_tree, gen.tree("introspection_c")),
        [
            _lib(pkg, "rosidl_generator_c"),
            *(_lib(d, "rosidl_typesupport_introspection_c") for d in deps),
            "rosidl_typesupport_introspection_c",
        ],
    )
    typesupport_c = target(
        _lib(pkg, "rosidl_typesupport_c"),
        gen.sources("typesupport_c", "*.cpp"),
        (c_tree, gen.tree("typesupport_c")),
        # an action's type support refers to its dependencies' (action_msgs' CancelGoal)
        [
            _lib(pkg, "rosidl_generator_c"),
            *(_lib(d, "rosidl_typesupport_c") for d in deps),
            "rosidl_typesupport_c",
        ],
    )
    py_includes = (Path(sysconfig.get_paths()["include"]), Path(np.get_include()))
    generator_py = target(
        _lib(pkg, "rosidl_generator_py"),
        gen.sources("py", "*_s.c"),
        (c_tree, *py_includes),
        [
            _lib(pkg, "rosidl_generator_c"),
            _lib(pkg, "rosidl_typesupport_c"),
            *(
                _lib(d, kind)
                for d in deps
                for kind in ("rosidl_generator_py", "rosidl_generator_c")
            ),
        ],
    )
    extensions = [
        Target(
            out_dir / pkg / f"{pkg}_s__{ts}{EXT_SUFFIX}",
            (gen.tree("py") / pkg / f"_{pkg}_s.ep.{ts}.c",),
            (c_tree, *py_includes, *ros_includes),
            (_lib(pkg, "rosidl_generator_py"), _lib(pkg, ts), _lib(pkg, "rosidl_generator_c")),
            rpath="$ORIGIN/../../..",  # site-packages/<pkg> -> lib
        )
        for ts in ("rosidl_typesupport_c", *TYPESUPPORTS)
    ]
    return [generator_c, fastrtps_c, introspection_c, typesupport_c, generator_py, *extensions]


def compiler(cxx: bool) -> str:
    name = "g++" if cxx else "gcc"
    path = shutil.which(name)
    if path is None:
        raise ConfigError(
            f"{name} not found: install it (apt-get install -y g++) to build messages"
        )
    return path


def build(target: Target, lib_dirs: tuple[Path, ...]) -> None:
    """Compile and link one target; a compiler error becomes a one-line ConfigError."""
    target.output.parent.mkdir(parents=True, exist_ok=True)
    cmd = [
        compiler(target.cxx),
        "-shared",
        "-fPIC",
        "-O2",
        "-w",
        *(["-std=gnu++17"] if target.cxx else ["-std=gnu11"]),
        *(f"-I{p}" for p in target.includes),
        *(str(s) for s in target.sources),
        "-o",
        str(target.output),
        *(f"-L{p}" for p in lib_dirs),
        f"-Wl,-rpath,{target.rpath}",
        *(f"-l{lib}" for lib in target.libraries),
    ]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        first = next((ln for ln in done.stderr.splitlines() if "error" in ln), done.stderr[-300:])
        raise ConfigError(f"cannot build {target.output.name}: {first.strip()}")
