"""Generates the Sync message classes from DTRON's Sync.proto while the package is built."""

from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent
# proto/Sync.proto links to dtron-api/src/main/proto/Sync.proto: one definition for Java, Python and C
PROTO = HERE / "proto" / "Sync.proto"


class BuildWithProto(build_py):
    """build_py that first runs protoc (from grpcio-tools) on Sync.proto into the build's dtron/_proto."""

    def run(self) -> None:
        from grpc_tools import protoc  # a build requirement, see pyproject.toml

        target = Path(self.build_lib) / "dtron" / "_proto"
        target.mkdir(parents=True, exist_ok=True)
        (target / "__init__.py").write_text('"""Generated from Sync.proto at build time."""\n')
        status = protoc.main(["protoc", f"-I{PROTO.parent}", f"--python_out={target}", f"--pyi_out={target}", str(PROTO)])
        if status != 0:
            raise RuntimeError(f"protoc failed on {PROTO} ({status})")
        super().run()


def protobuf_requirement() -> str:
    """protobuf at least as new as the one of grpcio-tools: generated code refuses an older runtime."""
    from google.protobuf import __version__ as protoc_version  # installed with grpcio-tools

    major, minor = protoc_version.split(".")[:2]
    return f"protobuf>={major}.{minor}"


setup(cmdclass={"build_py": BuildWithProto}, install_requires=["nats-py>=2.6", protobuf_requirement()])
