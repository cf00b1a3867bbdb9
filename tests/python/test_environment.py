"""The install script must provide the whole training stack in the project venv."""

import importlib

import pytest


@pytest.mark.parametrize("module", ["torch", "stable_baselines3", "gymnasium", "numpy", "matplotlib", "tqdm"])
def test_training_dependency_importable(module):
    importlib.import_module(module)


def test_package_points_at_repository():
    import guidewire_nav

    assert (guidewire_nav.REPO_ROOT / "CMakeLists.txt").is_file()
    assert (guidewire_nav.REPO_ROOT / "training" / "pyproject.toml").is_file()
