"""Source generation: the installed rosidl generators, driven as ``rosidl generate`` would.

The generators' own command-line extensions are used directly: the ``rosidl`` command
itself cannot load them from the PyPI wheels (each is registered twice and the ``.msg``
translator wants catkin_pkg), so ``.msg``/``.srv``/``.action`` files are translated here
with rosidl_adapter (an action becomes its Goal/Result/Feedback, the SendGoal and GetResult
services and the FeedbackMessage, exactly as ament would expand it).
Every generator writes into its own tree, ``<build>/<generator>/<package>/...``, which is
also the include root the compiler gets for it.
"""

from __future__ import annotations

import contextlib
import io
import os
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from rosidl_adapter.action import convert_action_to_idl
from rosidl_adapter.msg import convert_msg_to_idl
from rosidl_adapter.srv import convert_srv_to_idl
from rosidl_generator_c.cli import GenerateC
from rosidl_generator_py.cli import GeneratePython
from rosidl_generator_type_description.cli import HashTypeDescription
from rosidl_typesupport_c.cli import GenerateCTypesupport
from rosidl_typesupport_fastrtps_c.cli import GenerateFastRTPSCTypesupport
from rosidl_typesupport_introspection_c.cli import GenerateIntrospectionCTypesupport

from amiro.core.config import ConfigError
from amiro.ros2.msgbuild.package import InterfacePackage

# The C type supports rclpy can use; typesupport_c dispatches between them at run time.
TYPESUPPORTS = ("rosidl_typesupport_fastrtps_c", "rosidl_typesupport_introspection_c")
CONVERTERS = {"msg": convert_msg_to_idl, "srv": convert_srv_to_idl, "action": convert_action_to_idl}


@dataclass(frozen=True)
class GeneratedSources:
    package: InterfacePackage
    build_dir: Path
    idl_files: tuple[Path, ...]  # idl/<package>/<kind>/X.idl
    type_descriptions: tuple[Path, ...]  # type_description/<package>/<kind>/X.json

    def tree(self, generator: str) -> Path:
        """The include root of one generator's output (``py`` holds the Python package)."""
        return self.build_dir / generator

    def sources(self, generator: str, pattern: str) -> list[Path]:
        """``pattern`` under each interface kind's directory (``detail/*.c``)."""
        root = self.tree(generator) / self.package.name
        return sorted(p for kind in self.package.kinds for p in root.glob(f"{kind}/{pattern}"))


@contextlib.contextmanager
def _ament_prefix(prefix: Path) -> Iterator[None]:
    """The generators find their templates through the ament index of ``prefix``."""
    old = os.environ.get("AMENT_PREFIX_PATH")
    os.environ["AMENT_PREFIX_PATH"] = str(prefix) + (os.pathsep + old if old else "")
    try:
        yield
    finally:
        if old is None:
            del os.environ["AMENT_PREFIX_PATH"]
        else:
            os.environ["AMENT_PREFIX_PATH"] = old


def generate_sources(
    package: InterfacePackage, ros_prefix: Path, build_dir: Path
) -> GeneratedSources:
    """Every source file of the package's C libraries and Python module, under ``build_dir``."""
    name = package.name
    idl_root = build_dir / "idl" / name
    missing = [d for d in package.dependencies if not (ros_prefix / "share" / d).is_dir()]
    if missing:
        raise ConfigError(f"{name} needs {', '.join(missing)}, not installed in {ros_prefix}")
    include_paths = [str(ros_prefix / "share" / dep) for dep in package.dependencies]
    with _ament_prefix(ros_prefix), contextlib.redirect_stdout(io.StringIO()):
        idl_files = tuple(
            CONVERTERS[rel.parts[0]](package.source_dir, name, rel, idl_root / rel.parent)
            for rel in package.interfaces
        )
        interface_files = [f"{idl_root}:{p.relative_to(idl_root).as_posix()}" for p in idl_files]
        descriptions = HashTypeDescription("type_description").generate_type_hashes(
            name, interface_files, include_paths, output_path=build_dir / "type_description" / name
        )
        GenerateC("c").generate(
            name,
            interface_files,
            include_paths,
            output_path=build_dir / "c" / name,
            type_description_files=descriptions,
        )
        for tree, extension in (
            ("fastrtps_c", GenerateFastRTPSCTypesupport("fastrtps_c")),
            ("introspection_c", GenerateIntrospectionCTypesupport("introspection_c")),
            ("typesupport_c", GenerateCTypesupport("c")),
        ):
            extension.generate(
                name, interface_files, include_paths, output_path=build_dir / tree / name
            )
        GeneratePython(
            "py", typesupport_implementations=["rosidl_typesupport_c", *TYPESUPPORTS]
        ).generate(name, interface_files, include_paths, output_path=build_dir / "py" / name)
    return GeneratedSources(package, build_dir, idl_files, tuple(Path(p) for p in descriptions))
