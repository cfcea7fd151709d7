"""The package's version is the crates': the extension reports its own crate's version
(CARGO_PKG_VERSION), which is the library's, and the wheel's metadata says the same."""

from __future__ import annotations

import importlib.metadata
import re

import billiard_contact as bc
from conftest import REPO


def package_version(cargo_toml: str) -> str:
    text = (REPO / cargo_toml).read_text()
    package = text.split("[package]", 1)[1].split("\n[", 1)[0]
    return re.search(r'^version = "([^"]+)"$', package, re.M).group(1)


def test_version_is_the_crates():
    library, binding = package_version("Cargo.toml"), package_version("python/Cargo.toml")
    assert bc.__version__ == binding == library
    assert importlib.metadata.version("billiard-contact") == library
    assert re.fullmatch(r"\d+\.\d+\.\d+(-[0-9A-Za-z.]+)?", library)
